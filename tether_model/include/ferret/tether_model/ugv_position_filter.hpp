#pragma once
// The miniUGV's reported position smoothed with its own desired motion, and its
// velocity error estimated.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "ferret/tether_model/required_length.hpp"

namespace ferret::tether {

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
  [[nodiscard]] static UgvVelocityErrorOptions estimated() {
    return {0.05, 0.5, 0.5, 6.0, 0.0, 20.0};
  }
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
  Eigen::Vector2d velocity_ = Eigen::Vector2d::Zero();     ///< estimated actual velocity (lag > 0)
  Eigen::Vector2d error_ = Eigen::Vector2d::Zero();        ///< velocity error (sigma > 0)
  Eigen::Vector2d kalman_p_WG_ = Eigen::Vector2d::Zero();  ///< the Kalman filter's position
  Eigen::Vector2d obedient_p_WG_ = Eigen::Vector2d::Zero();  ///< the obedient filter's
  Eigen::Matrix2d P_ = Eigen::Matrix2d::Zero(), P0_ = Eigen::Matrix2d::Zero();
  double log_odds_ = 0.0;       ///< evidence for the Kalman filter (without the prior)
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

}  // namespace ferret::tether
