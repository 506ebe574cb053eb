#pragma once
// The winch's taut-tether control loop: a narrow interface with two named
// implementations, "mpc" (TautTetherMpc) and "baseline" (FeedForwardPid). Both see
// the same observation: the winch encoder, the winch's tension estimate, and the
// miniUGV's pose, desired velocity and desired acceleration as received over the
// link (with its age). Both output a spool velocity command (positive pays out).

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/tether_model/required_length.hpp"

namespace ferret::tether {

/// Winch and tether limits shared by the controllers and the simulation.
struct WinchLimits {
  double total_length_m = 15.0;             ///< L: l_t never exceeds it
  double max_speed_mps = 0.6;               ///< spool surface speed (MX-64: 63 rpm on a 9 cm spool)
  double max_acceleration_mps2 = 2.0;       ///< profile acceleration
  double velocity_time_constant_s = 0.025;  ///< first-order lag of the servo's velocity loop
};

/// Elastic tether: tension = EA / l * stretch (stretch = -slack when negative).
struct TensionModel {
  double axial_stiffness_n = 1500.0;  ///< EA of a 1 mm nylon line
  double hanging_weight_n =
      0.5;  ///< weight of the hanging part (winch to entry): the winch always feels it
  double max_tension_n = 10.0;  ///< above this the tether drags the miniUGV: an over-tension event

  /// Spring rate of `length_m` of tether (N/m).
  [[nodiscard]] double stiffness_npm(double length_m) const;
  /// Tension of `length_m` of tether with slack `slack_m` (0 when slack).
  [[nodiscard]] double tension_n(double length_m, double slack_m) const;
};

struct TetherObservation {
  double t_s = 0.0;
  double released_m = 0.0;       ///< l_t from the spool encoder
  double spool_speed_mps = 0.0;  ///< measured
  double winch_tension_n = 0.0;  ///< from motor current, includes the hanging weight
  UgvMotion ugv;                 ///< last message from the miniUGV
  double ugv_age_s = 0.0;        ///< how old that message is (link latency)
  UgvMotionPreview ugv_preview;  ///< the miniUGV's planned motion after the message, if sent
  /// Slack asked for beyond the reference: how much longer the real tether may be than
  /// the required-length model says (the miniUGV's bound of its tether less its
  /// estimate, where its map has not seen every corner the line can wrap).
  double slack_margin_m = 0.0;
};

/// Slack the controllers act on: geometric slack l_t - l_req from the (latency-
/// compensated) miniUGV position, but never more than the tension implies. A tension
/// above `guard_n` with geometric slack means the tether is caught somewhere (a snag):
/// the measured stretch wins, so the winch stops reeling in against it.
struct SlackEstimator {
  TensionModel tension;
  double guard_n = 1.5;  ///< tension (above the hanging weight) that overrides geometry

  [[nodiscard]] double estimate_m(double released_m, double required_m,
                                  double winch_tension_n) const;
};

/// The slack the controllers act on, with the winch tension fused in: a one-state
/// censored (Tobit) Kalman filter on the error b of the geometric slack, s = g - b.
/// b comes from the pose estimate (UgvPositionFilter's error projected on the tether,
/// an AR(1) process with the filter's time constant) and from the latency
/// extrapolation (the miniUGV's velocity error). The tension measures the stretch
/// k * max(0, -s) now, without the link's latency, and says nothing more than "not
/// stretched" while the line is slack; the update uses the exact mean and covariance
/// of that rectified measurement under the Gaussian prior, so it is informative on
/// both sides of taut and never pulls the estimate past what the tension allows.
/// A pull above the SlackEstimator guard (a snag) is left to the guard, and |b| is
/// capped at a few standard deviations: larger errors are not pose noise.
class SlackObserver {
 public:
  struct Options {
    bool tension_fusion = true;        ///< false: the geometric SlackEstimator alone
    double pose_noise_m = 0.01;        ///< assumed std of a reported position, per axis
    double tension_noise_n = 0.2;      ///< assumed std of the current-based tension
    double ugv_speed_noise_mps = 0.02; ///< assumed miniUGV velocity error (process noise)
    double max_bias_sigmas = 4.0;      ///< cap of |b| in steady-state standard deviations
    /// A pull above the guard that the pose error cannot explain is the required-length
    /// model falling short (a corner the miniUGV's map has not seen): the shortfall is
    /// kept as a model offset, so the winch does not reel the line taut again, and
    /// forgotten at this rate (m/s) while the line is not pulling (0: never).
    double model_offset_decay_mps = 0.1;
  };

  SlackObserver(const SlackEstimator& estimator, const Options& options, double pose_filter_gain,
                double control_period_s);
  /// One control cycle: the estimate of s = l_t - l_req (call once a cycle).
  [[nodiscard]] double estimate_m(double released_m, double required_m, double winch_tension_n);
  void reset();
  [[nodiscard]] double bias_m() const { return bias_m_; }
  /// How much longer than the model the tether was found to be (>= 0).
  [[nodiscard]] double model_offset_m() const { return offset_m_; }
  /// The model offset `ahead_s` after the last cycle, and its rate then: given back at
  /// give_back_mps() unless the last cycle's line was pulling (then held).
  [[nodiscard]] double model_offset_after_m(double ahead_s) const {
    return pulling_ ? offset_m_ : std::max(0.0, offset_m_ - give_back_mps_ * ahead_s);
  }
  [[nodiscard]] double model_offset_rate_mps(double ahead_s) const {
    return model_offset_after_m(ahead_s) > 0.0 && !pulling_ ? -give_back_mps_ : 0.0;
  }
  /// The rate the model offset is given back at from the next cycle on: never below
  /// model_offset_decay_mps (NaN or less: that rate), and not at all when that is 0. A
  /// controller that knows the offset cannot be a corner its model lacks gives it back
  /// faster (TautTetherMpc).
  void set_give_back_mps(double rate_mps) {
    const double base = options_.model_offset_decay_mps;
    give_back_mps_ = base > 0.0 && rate_mps > base ? rate_mps : base;
  }
  [[nodiscard]] double give_back_mps() const { return give_back_mps_; }
  [[nodiscard]] double bias_variance_m2() const { return variance_m2_; }
  /// Largest |b| the observer accepts as pose error (larger: not pose noise).
  [[nodiscard]] double max_bias_m() const;

 private:
  SlackEstimator estimator_;
  Options options_;
  double decay_ = 0.0;         ///< AR(1) factor of b a cycle: 1 - pose filter gain
  double process_m2_ = 0.0;    ///< variance b gains a cycle
  double steady_m2_ = 0.0;     ///< variance of b without tension information
  double bias_m_ = 0.0, variance_m2_ = 0.0;
  double offset_m_ = 0.0;
  double give_back_mps_ = 0.0;  ///< the model offset's rate of decay (set_give_back_mps)
  bool pulling_ = false;  ///< the last cycle's pull was above the guard
  double control_period_s_ = 0.02;
};

/// The miniUGV's velocity error: how far its actual velocity is from what its desired
/// motion (and the lag model) says, estimated from its reported positions. Off with
/// `sigma_mps` 0.
struct UgvVelocityErrorOptions {
  /// Standard deviation of the error per axis (Gauss-Markov prior); 0: not estimated.
  double sigma_mps = 0.0;
  double time_s = 0.5;  ///< its correlation time
  /// Memory of the likelihood comparison between the two filters (exponential, s).
  double window_s = 0.5;
  /// Log-odds against the velocity-error filter before any evidence (> 0: the
  /// obedient filter is kept on a tie).
  double prior_log_odds = 2.0;
  /// The prior while the filter models a lag (a robot known not to do exactly what it
  /// says is more likely to deviate from its model too).
  double prior_log_odds_with_lag = 2.0;
  /// Memory of the same evidence over which a robot that keeps deviating (log-odds
  /// above prior_log_odds) is also given prior_log_odds_with_lag.
  double long_window_s = 20.0;
  /// The MPC's settings (docs/tether.md): a robot's error beside its identified response.
  [[nodiscard]] static UgvVelocityErrorOptions estimated() { return {0.05, 0.5, 0.5, 6.0, 0.0, 20.0}; }
};

/// Smooths the miniUGV's reported position with its own desired motion: each message
/// is first predicted from the previous estimate with the desired velocity and
/// acceleration, then corrected towards the measurement by `gain` (1: no filtering).
/// A fixed-gain (steady-state) Kalman filter for a robot that follows its commands.
/// With `velocity_lag_s` > 0 the robot's velocity loop is modelled as a first-order
/// lag: the filter keeps the robot's estimated actual velocity, predicts with it, and
/// reports it with the acceleration of the lag, (v_desired - v) / lag.
///
/// With a velocity error (UgvVelocityErrorOptions::sigma_mps > 0) a second filter runs
/// beside it: a two-state Kalman filter per axis, position and velocity error e
/// (actual velocity = the model's + e, e a Gauss-Markov process), on reported
/// positions of standard deviation `pose_noise_m`, its position process noise the one
/// whose steady-state gain alone would be `gain`. Each message scores both filters by
/// the likelihood of its innovation (the normalised square capped at 25 per axis, so
/// one outlier does not decide), with exponential forgetting over `window_s`; the
/// output is the mixture by the posterior weight w of the second filter: position
/// (1 - w) p_fixed + w p_kalman, velocity the model's + w e. An obedient robot's
/// innovations favour the smoother fixed-gain filter (w ~ 0: as without the option);
/// a robot that does not do what it says leaves the fixed-gain filter lagging, its
/// innovations biased, and w goes to 1.
class UgvPositionFilter {
 public:
  explicit UgvPositionFilter(double gain = 1.0, double velocity_lag_s = 0.0,
                             const UgvVelocityErrorOptions& velocity_error = {},
                             double pose_noise_m = 0.01, double period_s = 0.02);
  /// @param t_msg_s time the message was sent (its pose's time stamp)
  /// @return the motion with the filtered position (and, with a lag, velocity and
  /// acceleration; with a velocity error, the mixture above)
  UgvMotion update(double t_msg_s, const UgvMotion& measured);
  void reset();
  /// The robot's response model: the velocity loop's lag (0: the robot follows its
  /// desired motion exactly) and its path follower's time constant (0: none), which
  /// steers it back onto the desired path integrated from its desired motion.
  void set_response_model(double velocity_lag_s, double tracking_time_s);
  /// Whether the filter models the robot's response (a lag > 0).
  [[nodiscard]] bool models_response() const { return lag_s_ > 0.0; }
  /// The desired motion at the last message, its position on the integrated desired path.
  [[nodiscard]] UgvMotion desired_at_message() const;
  /// The robot's motion at `times_s` after the last message (ascending, >= 0): the
  /// response model from the filtered state, driven by the desired motion `desired`
  /// returns for a time after the message (position on the desired path, velocity),
  /// plus the velocity error as believed. Needs a lag (models_response()).
  template <class DesiredMotion>
  [[nodiscard]] std::vector<UgvMotion> response(const std::vector<double>& times_s,
                                                const DesiredMotion& desired) const;
  /// The velocity error as output: w e (zero without the error filter).
  [[nodiscard]] Eigen::Vector2d velocity_error_mps() const { return weight_ * error_; }
  /// The Kalman filter's velocity error and its variance (per axis).
  [[nodiscard]] const Eigen::Vector2d& raw_velocity_error_mps() const { return error_; }
  [[nodiscard]] double velocity_error_variance() const { return P_(1, 1); }
  /// Posterior weight of the velocity-error filter (0 without it).
  [[nodiscard]] double velocity_error_weight() const { return weight_; }
  /// The last message's position innovation of the fixed-gain filter (before its
  /// correction; zero for the first message).
  [[nodiscard]] const Eigen::Vector2d& innovation_m() const { return innovation_; }

 private:
  [[nodiscard]] UgvMotion output() const;
  /// What the robot's velocity loop is asked for: the desired velocity less the path
  /// follower's correction.
  [[nodiscard]] Eigen::Vector2d commanded_velocity() const;
  /// The velocity-error filter and its evidence back to their start.
  void forget_velocity_error();
  /// The integrated desired path moved on `dt` with the last message's desired motion.
  void advance_desired_path(double dt);
  double gain_;
  double lag_s_;
  double tracking_time_s_ = 0.0;
  Eigen::Vector2d desired_p_WG_ = Eigen::Vector2d::Zero();  ///< desired path, integrated
  Eigen::Vector2d innovation_ = Eigen::Vector2d::Zero();
  UgvVelocityErrorOptions error_options_;
  double r_m2_ = 1e-4, q_p_m2_per_s_ = 0.0;
  bool initialised_ = false;
  double t_s_ = 0.0;
  UgvMotion estimate_;  ///< filtered position; the desired velocity and acceleration
  Eigen::Vector2d velocity_ = Eigen::Vector2d::Zero();  ///< estimated actual velocity (lag > 0)
  Eigen::Vector2d error_ = Eigen::Vector2d::Zero();     ///< velocity error (sigma > 0)
  Eigen::Vector2d kalman_p_WG_ = Eigen::Vector2d::Zero();    ///< the Kalman filter's position
  Eigen::Vector2d obedient_p_WG_ = Eigen::Vector2d::Zero();  ///< the obedient filter's
  Eigen::Matrix2d P_ = Eigen::Matrix2d::Zero(), P0_ = Eigen::Matrix2d::Zero();
  double log_odds_ = 0.0;  ///< evidence for the Kalman filter (without the prior)
  double long_log_odds_ = 0.0;  ///< the same over long_window_s
  double weight_ = 0.0;
};

/// One step `h` of a first-order velocity lag `lag_s` (> 0) whose command changes
/// linearly, `c0 + c1 s`: exact for that command.
inline void lagged_velocity_step(Eigen::Vector2d& p, Eigen::Vector2d& v, const Eigen::Vector2d& c0,
                                 const Eigen::Vector2d& c1, double lag_s, double h) {
  const double decay = std::exp(-h / lag_s);
  const Eigen::Vector2d transient = v - c0 + c1 * lag_s;
  p += c0 * h + c1 * (0.5 * h * h - lag_s * h) + transient * lag_s * (1.0 - decay);
  v = c0 + c1 * (h - lag_s) + transient * decay;
}

template <class DesiredMotion>
std::vector<UgvMotion> UgvPositionFilter::response(const std::vector<double>& times_s,
                                                   const DesiredMotion& desired) const {
  std::vector<UgvMotion> out;
  out.reserve(times_s.size());
  constexpr double kStepS = 0.005;
  const Eigen::Vector2d error = weight_ * error_;
  Eigen::Vector2d p = estimate_.p_WG, v = velocity_;
  double t = 0.0;
  UgvMotion d = desired(0.0);
  for (const double target : times_s) {
    while (t < target - 1e-12) {
      const double h = std::min(kStepS, target - t);
      // The command at the step's start and its rate (the desired velocity's change
      // over the step, less the path follower's reaction to the velocity error).
      const UgvMotion d_next = desired(t + h);
      Eigen::Vector2d command = d.v_WG, rate = (d_next.v_WG - d.v_WG) / h;
      if (tracking_time_s_ > 0.0) {
        command -= (p - d.p_WG) / tracking_time_s_;
        rate -= (v - d.v_WG) / tracking_time_s_;
      }
      lagged_velocity_step(p, v, command, rate, lag_s_, h);
      t += h;
      d = d_next;
    }
    UgvMotion m;
    m.p_WG = p + error * t;
    m.v_WG = v + error;
    out.push_back(m);
  }
  return out;
}

/// Which response model the miniUGV follows, identified online from its messages: a
/// bank of fixed-gain filters, one a hypothesis (the obedient robot, and every pair of
/// a velocity lag and a path follower's time constant), each scored by the squared
/// innovations of its position predictions (normalised, capped at 25 per axis) with
/// exponential forgetting over `window_s`. A robot's response is a property of the
/// robot, not of a moment, so the memory is long; the obedient hypothesis wins ties by
/// `prior_log_odds`. Scoring starts after 3 / gain messages, when the filters have
/// forgotten their first position. Off by default (both controllers as published); the
/// MPC turns it on.
struct UgvResponseIdentificationOptions {
  bool enabled = false;
  std::array<double, 6> lags_s = {0.05, 0.1, 0.15, 0.2, 0.3, 0.5};
  /// Path follower time constants; 0: the robot does not steer back onto its path.
  std::array<double, 5> tracking_times_s = {0.0, 0.5, 1.0, 2.0, 4.0};
  double window_s = 20.0;
  double prior_log_odds = 4.0;
  /// The defaults, turned on (the MPC's and the mission's winch's).
  [[nodiscard]] static UgvResponseIdentificationOptions on() {
    UgvResponseIdentificationOptions o;
    o.enabled = true;
    return o;
  }
};

class UgvResponseIdentifier {
 public:
  struct Model {
    double velocity_lag_s = 0.0;  ///< 0: obedient
    double tracking_time_s = 0.0;
    bool operator==(const Model&) const = default;
  };
  /// Throws std::invalid_argument for negative or non-finite hypotheses, a window <= 0.
  UgvResponseIdentifier(const UgvResponseIdentificationOptions& options, double gain,
                        double pose_noise_m);
  /// Scores every hypothesis on one message; returns the most likely model.
  Model update(double t_msg_s, const UgvMotion& measured);
  void reset();
  [[nodiscard]] const Model& best() const { return models_[best_]; }
  /// Log-likelihood of the best model over the obedient one (without the prior).
  [[nodiscard]] double best_log_odds() const;
  /// Every hypothesis ([0] the obedient robot) and its log-likelihood (without the prior).
  [[nodiscard]] const std::vector<Model>& models() const { return models_; }
  [[nodiscard]] double log_likelihood(std::size_t i) const { return -0.5 * score_.at(i); }

 private:
  UgvResponseIdentificationOptions options_;
  double innovation_var_m2_;
  std::vector<Model> models_;  ///< [0] obedient
  std::vector<UgvPositionFilter> filters_;
  std::vector<double> score_;  ///< sum of normalised squared innovations, forgotten
  double t_s_ = 0.0;
  bool started_ = false;
  int messages_ = 0, settle_messages_ = 0;  ///< scored only after settle_messages_
  std::size_t best_ = 0;
};

class TetherController {
 public:
  virtual ~TetherController() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  /// Forget integrators and the previous command.
  virtual void reset() = 0;
  /// One control cycle; returns the spool velocity command in m/s (positive pays out).
  [[nodiscard]] virtual double step(const TetherObservation& obs) = 0;
};

/// The miniUGV can drive off without warning (a decision cycle that ends a stop): while
/// the spool reels in, the slack left must cover what the miniUGV takes before the
/// spool has turned round and caught up with it. With the miniUGV starting from its
/// present required-length rate at `ugv_acceleration_mps2` up to `ugv_speed_mps`, and
/// the spool answering `reaction_s` later at `spool_acceleration_fraction` of its
/// limit, the guard raises a command whose worst-case loss would leave less than
/// `min_slack_m`. Off (ugv_speed_mps 0) by default: the tether study's controllers as
/// published; the mission turns it on.
struct ReelInGuard {
  double ugv_speed_mps = 0.0;          ///< the fastest the tethered miniUGV drives; 0: off
  double ugv_acceleration_mps2 = 2.0;
  double reaction_s = 0.06;            ///< a control period, the servo's lag and the link's age
  double spool_acceleration_fraction = 0.9;
  double min_slack_m = 0.02;

  [[nodiscard]] bool on() const { return ugv_speed_mps > 0.0; }
  /// Line the miniUGV takes beyond the spool, starting now, if the spool turns at `u_mps`
  /// and the required length grows at `rate_mps` (both positive out).
  [[nodiscard]] double worst_loss_m(double u_mps, double rate_mps, const WinchLimits& limits) const;
  /// `command` raised (never lowered) so the worst loss stays within `slack_m` less
  /// min_slack_m, within [lo, hi] (the command's rate and speed limits).
  [[nodiscard]] double limit(double command, double slack_m, double rate_mps, const WinchLimits& limits,
                             double lo, double hi) const;
};

/// Options common to both controllers.
struct TautControlOptions {
  WinchLimits limits;
  SlackEstimator slack_estimator;
  double slack_reference_m = 0.0;  ///< slack aimed for: taut (tuned, docs/tether.md)
  double max_slack_m = 0.15;       ///< s_max: slack kept in [0, s_max] (plus the margin)
  /// The most of an observation's slack_margin_m honoured: slack beyond this on the
  /// floor is a loop that can snag, so a larger doubt is left to the tension guard.
  double max_slack_margin_m = 0.5;
  /// The slack margin of an observation as honoured (0 for NaN or negative).
  [[nodiscard]] double margin_m(const TetherObservation& obs) const {
    return obs.slack_margin_m > 0.0 ? std::min(obs.slack_margin_m, max_slack_margin_m) : 0.0;
  }
  double control_period_s = 0.02;  ///< 50 Hz
  double ugv_max_speed_mps = 2.0;  ///< caps the miniUGV prediction
  double pose_filter_gain = 0.05;  ///< UgvPositionFilter gain a cycle (1: raw positions)
  SlackObserver::Options slack_observer;  ///< tension fusion (both controllers)
  /// The miniUGV's velocity-loop time constant as the filter models it (0: it
  /// follows its desired motion exactly).
  double ugv_velocity_lag_s = 0.0;
  /// The time constant of the miniUGV's path follower as the filter models it (0: none;
  /// only with a lag).
  double ugv_tracking_time_s = 0.0;
  /// The pose filter's velocity-error state (default off: both controllers as
  /// published; the MPC turns it on with TautTetherMpc::Options::ugv_velocity_error).
  UgvVelocityErrorOptions ugv_velocity_error;
  /// Online identification of the miniUGV's response model, which then replaces
  /// ugv_velocity_lag_s / ugv_tracking_time_s (default off; the MPC turns it on with
  /// TautTetherMpc::Options::ugv_response_identification).
  UgvResponseIdentificationOptions ugv_response_identification;
  ReelInGuard reel_in_guard;  ///< off by default
};

/// What both controllers estimate from an observation: the miniUGV's filtered motion
/// and the tension-fused slack, built from the same options and reset together.
struct TetherStateEstimator {
  explicit TetherStateEstimator(const TautControlOptions& options);
  void reset();
  /// The message through the response identification (when on) and the pose filter.
  UgvMotion filter_pose(double t_msg_s, const UgvMotion& measured);

  UgvPositionFilter pose_filter;
  SlackObserver slack_observer;
  std::optional<UgvResponseIdentifier> response_identifier;  ///< when identification is on

 private:
  UgvResponseIdentifier::Model fixed_model_;
};

/// A controller of tether_controllers() (winch_controllers.hpp), "mpc" or "baseline",
/// with WinchControllerOptions::following(options): the MPC gets
/// options.ugv_velocity_error (default off), not TautTetherMpc's default.
/// @throws InputError listing the names for another name.
[[nodiscard]] std::unique_ptr<TetherController> make_tether_controller(
    std::string_view name, const TautControlOptions& options,
    std::shared_ptr<const RequiredLengthModel> model);

/// The names of tether_controllers(), in the order registered.
[[nodiscard]] std::vector<std::string> tether_controller_names();

}  // namespace ferret::tether
