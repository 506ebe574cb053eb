#include "ferret/tether_model/taut_mpc.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "ferret/tether_model/line_catch.hpp"

namespace ferret::tether {
namespace {

TautControlOptions with_own_estimation(TautControlOptions control,
                                       const TautTetherMpc::Options& options) {
  control.ugv_velocity_error = options.ugv_velocity_error;
  control.ugv_response_identification = options.ugv_response_identification;
  return control;
}

}  // namespace

TautTetherMpc::TautTetherMpc(Options options, std::shared_ptr<const RequiredLengthModel> model)
    : options_(options),
      model_(std::move(model)),
      estimator_(with_own_estimation(options.control, options)) {
  if (!model_) throw std::invalid_argument("TautTetherMpc: no required-length model");
  if (options_.horizon < 2) throw std::invalid_argument("TautTetherMpc: horizon must be >= 2");
  if (!(options_.give_back_stiffness_factor >= 1.0) ||
      !std::isfinite(options_.give_back_stiffness_factor))
    throw std::invalid_argument("TautTetherMpc: give_back_stiffness_factor must be >= 1");
  if (!(options_.prediction_dt_s > 0.0) || !(options_.control.control_period_s > 0.0))
    throw std::invalid_argument("TautTetherMpc: time steps must be > 0");
  if (!(options_.control.limits.velocity_time_constant_s > 0.0))
    throw std::invalid_argument("TautTetherMpc: servo time constant must be > 0");
  build();
}

void TautTetherMpc::reset() {
  last_command_mps_ = 0.0;
  last_ = QpResult{};
  estimator_.reset();
}

// Servo model: the spool speed follows the command with a first-order lag tau,
// v' = (u - v) / tau, so over one step of length dt with the command u held
//   v+ = alpha v + (1 - alpha) u,   l+ = l + c v + (dt - c) u,
// alpha = exp(-dt / tau), c = tau (1 - alpha) (the exact discretisation).
void TautTetherMpc::build() {
  const int N = options_.horizon;
  const double dt = options_.prediction_dt_s;
  const double tau = options_.control.limits.velocity_time_constant_s;
  const double alpha = std::exp(-dt / tau), c = tau * (1.0 - alpha);
  n_ = N + 3;
  Phi_l_ = Eigen::MatrixXd::Zero(N, n_);
  free_l_from_l_ = Eigen::VectorXd::Ones(N);
  free_l_from_v_ = Eigen::VectorXd::Zero(N);
  Eigen::RowVectorXd dl = Eigen::RowVectorXd::Zero(n_), dv = Eigen::RowVectorXd::Zero(n_);
  double fl_v = 0.0, fv_v = 1.0;  // free response of l and v to the initial speed
  for (int k = 0; k < N; ++k) {
    dl = dl + c * dv;
    dl[k] += dt - c;
    dv = alpha * dv;
    dv[k] += 1.0 - alpha;
    fl_v += c * fv_v;
    fv_v *= alpha;
    Phi_l_.row(k) = dl;
    free_l_from_v_[k] = fl_v;
  }

  // Hessian of J = sum_k w_k (l_k - r_k - s_ref)^2 + w_rate sum (u_k - u_k-1)^2
  //             + w_ff sum (u_k - rdot_k)^2 + rho_lo e_lo + rho1 e_hi + rho2 (e_lo^2 + e_hi^2)
  // written as 1/2 z' H z + g' z with z = [u_0..u_N-1, e_lo, e_hi].
  H_ = Eigen::MatrixXd::Zero(n_, n_);
  for (int k = 0; k < N; ++k) {
    const double w = options_.weight_slack * (k == N - 1 ? options_.weight_terminal : 1.0);
    H_ += 2.0 * w * Phi_l_.row(k).transpose() * Phi_l_.row(k);
  }
  const double w_rate = options_.weight_command_rate;
  for (int k = 0; k < N; ++k) {
    H_(k, k) += 2.0 * w_rate + 2.0 * std::max(options_.weight_feedforward, 1e-6);
    if (k > 0) {
      H_(k - 1, k - 1) += 2.0 * w_rate;
      H_(k, k - 1) -= 2.0 * w_rate;
      H_(k - 1, k) -= 2.0 * w_rate;
    }
  }
  H_(N, N) = H_(N + 1, N + 1) = 2.0 * options_.soft_quadratic_weight;
  H_(N + 2, N + 2) = 2.0 * options_.length_quadratic_weight;

  // Constraint rows: command rate (N), l_t <= L and l_t >= 0 softened by e_len
  // (2N), slack >= 0 softened by e_lo (N), slack <= s_max softened by e_hi (N),
  // command box (N), e >= 0 (3). The length bounds are soft only so that a state
  // already past them (a spool that cannot stop in time) still has a solution: their
  // penalty is far above everything else, so they hold whenever they can.
  row_rate_ = 0;
  row_length_ = N;
  row_length_lo_ = 2 * N;
  row_slack_lo_ = 3 * N;
  row_slack_hi_ = 4 * N;
  row_box_ = 5 * N;
  row_soft_ = 6 * N;
  rows_ = 6 * N + 3;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(rows_, n_);
  for (int k = 0; k < N; ++k) {
    C(row_rate_ + k, k) = 1.0;
    if (k > 0) C(row_rate_ + k, k - 1) = -1.0;
    C.row(row_length_ + k) = Phi_l_.row(k);
    C(row_length_ + k, N + 2) = -1.0;
    C.row(row_length_lo_ + k) = Phi_l_.row(k);
    C(row_length_lo_ + k, N + 2) = 1.0;
    C.row(row_slack_lo_ + k) = Phi_l_.row(k);
    C(row_slack_lo_ + k, N) = 1.0;
    C.row(row_slack_hi_ + k) = Phi_l_.row(k);
    C(row_slack_hi_ + k, N + 1) = -1.0;
    C(row_box_ + k, k) = 1.0;
  }
  C(row_soft_, N) = 1.0;
  C(row_soft_ + 1, N + 1) = 1.0;
  C(row_soft_ + 2, N + 2) = 1.0;
  solver_.setup(H_, C);
  required_ = Eigen::VectorXd::Zero(N);
  required_rate_ = Eigen::VectorXd::Zero(N);
  tracking_rate_ = Eigen::VectorXd::Zero(N + 1);
  tracking_command_ = Eigen::VectorXd::Zero(N + 1);
}

double TautTetherMpc::step(const TetherObservation& obs) {
  const int N = options_.horizon;
  const auto& ctl = options_.control;
  const double dt = options_.prediction_dt_s;
  const double vmax = ctl.limits.max_speed_mps, amax = ctl.limits.max_acceleration_mps2;
  const double inf = std::numeric_limits<double>::infinity();

  // Required length now (the link message is ugv_age_s old) and over the horizon,
  // from the desired velocity and acceleration.
  // With the miniUGV's planned motion (preview) the predictions follow its plan;
  // without, the desired acceleration is held for acceleration_time_s.
  const double ta = options_.acceleration_time_s;
  const bool preview = options_.use_preview && !obs.ugv_preview.empty();
  const UgvMotion at_message = estimator_.filter_pose(obs.t_s - obs.ugv_age_s, obs.ugv);
  // The plan says nothing of the robot's velocity error; the filter's estimate (zero
  // unless estimated and past its gate) is added to it.
  const Eigen::Vector2d velocity_error = estimator_.pose_filter.velocity_error_mps();
  const auto planned = [&](double dt_s) {
    UgvMotion m = planned_motion(at_message, obs.ugv_preview, dt_s);
    m.p_WG += velocity_error * dt_s;
    m.v_WG += velocity_error;
    return m;
  };
  // With a response model the robot's motion is simulated from the desired motion
  // (the plan, or the desired velocity and acceleration extrapolated as above).
  std::vector<UgvMotion> response;
  if (estimator_.pose_filter.models_response()) {
    std::vector<double> times(N + 1);
    for (int k = 0; k <= N; ++k) times[k] = obs.ugv_age_s + k * dt;
    const UgvMotion desired = estimator_.pose_filter.desired_at_message();
    if (preview) {
      response = estimator_.pose_filter.response(
          times, [&](double t) { return planned_motion(desired, obs.ugv_preview, t); });
    } else {
      response = estimator_.pose_filter.response(
          times, [&](double t) { return desired.extrapolated(t, ctl.ugv_max_speed_mps, ta); });
    }
  }
  const UgvMotion now = !response.empty() ? response[0]
                        : preview
                            ? planned(obs.ugv_age_s)
                            : at_message.extrapolated(obs.ugv_age_s, ctl.ugv_max_speed_mps, ta);
  const double required_now = model_->required_length_m(now.p_WG);
  // The observer's correction of the geometric slack (the pose error the tension
  // reveals, or a snag's measured stretch) shifts every prediction: the tether
  // behaves as if it were that much longer.
  if (options_.give_back_at_stopping_speed) {
    LineCatchLimit stop = LineCatchLimit::for_winch(ctl);
    stop.axial_stiffness_n *= options_.give_back_stiffness_factor;
    // NaN says nothing: the doubt is assumed.
    const bool no_doubt = obs.slack_margin_m <= stop.stretch_m(obs.released_m);
    estimator_.slack_observer.set_give_back_mps(no_doubt ? stop.speed_mps(obs.released_m) : 0.0);
  }
  const double slack =
      estimator_.slack_observer.estimate_m(obs.released_m, required_now, obs.winch_tension_n);
  const double bias = (obs.released_m - required_now) - slack;
  // The observer's model offset (a snag's length held) is given back while the line
  // does not pull: the prediction knows it will shrink.
  const auto& observer = estimator_.slack_observer;
  for (int k = 0; k < N; ++k) {
    const UgvMotion future = !response.empty() ? response[k + 1]
                             : preview         ? planned(obs.ugv_age_s + (k + 1) * dt)
                                       : now.extrapolated((k + 1) * dt, ctl.ugv_max_speed_mps,
                                                          std::max(0.0, ta - obs.ugv_age_s));
    const double ahead_s = (k + 1) * dt;
    required_[k] = model_->required_length_m(future.p_WG) + bias -
                   (observer.model_offset_m() - observer.model_offset_after_m(ahead_s));
    required_rate_[k] =
        required_length_rate_mps(*model_, future) + observer.model_offset_rate_mps(ahead_s);
  }
  // While the pull is above the guard the line may be caught on a corner (a snag):
  // then the winch side ends at the pin and cannot get shorter, whatever the miniUGV
  // does beyond it. So no prediction may ask for less line than the line needs now;
  // otherwise slack predicted beyond the pin (past s_max, which no winch can take in)
  // would make the MPC hold the stretch against it. Growth is still followed, so an
  // ordinary stretch behind a miniUGV driving away is paid out as before.
  const auto& tension = ctl.slack_estimator.tension;
  const bool pulling = obs.winch_tension_n - tension.hanging_weight_n > ctl.slack_estimator.guard_n;
  if (pulling) {
    for (int k = 0; k < N; ++k) {
      required_[k] = std::max(required_[k], obs.released_m - slack);
      required_rate_[k] = std::max(required_rate_[k], 0.0);
    }
  }

  const double margin = ctl.margin_m(obs);
  const double l0 = obs.released_m, v0 = obs.spool_speed_mps;
  const Eigen::VectorXd free_l = free_l_from_l_ * l0 + free_l_from_v_ * v0;
  last_free_l_ = free_l;
  // Linear term.
  Eigen::VectorXd g = Eigen::VectorXd::Zero(n_);
  for (int k = 0; k < N; ++k) {
    const double w = options_.weight_slack * (k == N - 1 ? options_.weight_terminal : 1.0);
    const double offset = free_l[k] - required_[k] - ctl.slack_reference_m - margin;
    g += 2.0 * w * offset * Phi_l_.row(k).transpose();
    g[k] -= 2.0 * std::max(options_.weight_feedforward, 1e-6) * required_rate_[k];
  }
  g[0] -= 2.0 * options_.weight_command_rate * last_command_mps_;
  // The rate penalty about the command that tracks the prediction exactly (docs/tether.md):
  // it damps the corrections, not the feed-forward. On the command's change alone it
  // smoothed the known plan symmetrically, paying out ahead of every acceleration of the
  // required length. Only along the miniUGV's plan (without one, the prediction past the
  // desired acceleration's 0.1 s is an assumption: following it undamped cost 2-3 %),
  // as far as the robot is believed to follow its model (its velocity-error weight), and
  // not while the line pulls or a model offset is held (the required length is then
  // known to be wrong: undamped, it reeled in against a pin, 10.4 N, in a random snag).
  if (options_.rate_penalty_about_tracking_command && preview && !pulling &&
      observer.model_offset_m() <= 0.0) {
    // The required length's rate over each step (f), led by the servo's lag: the
    // tracking command u* = f + tau f', scaled by how far the robot follows its model.
    const double tau = ctl.limits.velocity_time_constant_s;
    const double r_now = required_now + bias;
    const double trust = 1.0 - estimator_.pose_filter.velocity_error_weight();
    tracking_rate_[0] =
        required_length_rate_mps(*model_, now) + observer.model_offset_rate_mps(0.0);
    for (int k = 0; k < N; ++k)
      tracking_rate_[k + 1] = (required_[k] - (k == 0 ? r_now : required_[k - 1])) / dt;
    for (int k = 0; k <= N; ++k) {
      const int a = std::max(0, k - 1), b = std::min(N, k + 1);
      tracking_command_[k] =
          trust *
          (tracking_rate_[k] + tau * (tracking_rate_[b] - tracking_rate_[a]) / ((b - a) * dt));
    }
    for (int k = 0; k < N; ++k) {
      const double d = tracking_command_[k + 1] - tracking_command_[k];
      g[k] -= 2.0 * options_.weight_command_rate * d;
      if (k > 0) g[k - 1] += 2.0 * options_.weight_command_rate * d;
    }
  }

  g[N] = options_.stretch_linear_weight;
  g[N + 1] = options_.soft_linear_weight;
  g[N + 2] = options_.length_linear_weight;

  // Bounds.
  Eigen::VectorXd lo(rows_), hi(rows_);
  for (int k = 0; k < N; ++k) {
    const double step_dt = k == 0 ? ctl.control_period_s : dt;
    lo[row_rate_ + k] = (k == 0 ? last_command_mps_ : 0.0) - amax * step_dt;
    hi[row_rate_ + k] = (k == 0 ? last_command_mps_ : 0.0) + amax * step_dt;
    lo[row_length_ + k] = -inf;
    hi[row_length_ + k] = ctl.limits.total_length_m - free_l[k];
    lo[row_length_lo_ + k] = 0.0 - free_l[k];
    hi[row_length_lo_ + k] = inf;
    lo[row_slack_lo_ + k] = required_[k] - free_l[k];
    hi[row_slack_lo_ + k] = inf;
    lo[row_slack_hi_ + k] = -inf;
    hi[row_slack_hi_ + k] = required_[k] + ctl.max_slack_m + margin - free_l[k];
    lo[row_box_ + k] = -vmax;
    hi[row_box_ + k] = vmax;
  }
  lo[row_soft_] = lo[row_soft_ + 1] = lo[row_soft_ + 2] = 0.0;
  hi[row_soft_] = hi[row_soft_ + 1] = hi[row_soft_ + 2] = inf;

  last_ = solver_.solve(g, lo, hi);
  double command;
  if (last_.status == QpResult::Status::kOptimal) {
    command = std::clamp(last_.x[0], -vmax, vmax);
  } else {
    // Only the iteration limit can get here (every constraint that can conflict is
    // soft): brake towards zero speed as hard as allowed.
    ++fallbacks_;
    spdlog::debug("tether MPC: QP {} at t = {:.3f} s; braking", to_string(last_.status), obs.t_s);
    const double step = amax * ctl.control_period_s;
    command = std::clamp(0.0, last_command_mps_ - step, last_command_mps_ + step);
  }
  if (ctl.reel_in_guard.on()) {
    const double step = amax * ctl.control_period_s;
    const double hi =
        std::min({vmax, last_command_mps_ + step,
                  std::sqrt(2.0 * amax * std::max(0.0, ctl.limits.total_length_m - l0))});
    command =
        ctl.reel_in_guard.limit(command, slack - margin, required_length_rate_mps(*model_, now),
                                ctl.limits, last_command_mps_ - step, hi);
  }
  last_command_mps_ = command;
  return command;
}

Eigen::VectorXd TautTetherMpc::predicted_released_m() const {
  if (last_.x.size() != n_) return {};
  return last_free_l_ + Phi_l_ * last_.x;
}

}  // namespace ferret::tether
