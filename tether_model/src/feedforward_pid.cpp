#include "ferret/tether_model/feedforward_pid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ferret::tether {

FeedForwardPid::FeedForwardPid(Options options, std::shared_ptr<const RequiredLengthModel> model)
    : options_(options), model_(std::move(model)), estimator_(options.control) {
  if (!model_) throw std::invalid_argument("FeedForwardPid: no required-length model");
  if (!(options_.control.control_period_s > 0.0))
    throw std::invalid_argument("FeedForwardPid: control period must be > 0");
}

void FeedForwardPid::reset() {
  integral_m_s_ = 0.0;
  last_error_m_ = 0.0;
  has_last_ = false;
  last_command_mps_ = 0.0;
  estimator_.reset();
}

double FeedForwardPid::step(const TetherObservation& obs) {
  const auto& c = options_.control;
  const double dt = c.control_period_s;
  // Latency compensation with the desired velocity only: the classic feed-forward
  // (or, as an option, with the miniUGV's planned motion).
  UgvMotion now = estimator_.filter_pose(obs.t_s - obs.ugv_age_s, obs.ugv);
  if (options_.use_preview && !obs.ugv_preview.empty()) {
    now = planned_motion(now, obs.ugv_preview, obs.ugv_age_s);
  } else {
    now.a_WG.setZero();
    now = now.extrapolated(obs.ugv_age_s, c.ugv_max_speed_mps);
  }
  const double required = model_->required_length_m(now.p_WG);
  const double feedforward = options_.feedforward_gain * required_length_rate_mps(*model_, now);
  const double slack =
      estimator_.slack_observer.estimate_m(obs.released_m, required, obs.winch_tension_n);
  const double error = c.slack_reference_m + c.margin_m(obs) - slack;  // > 0: too taut, pay out
  const double derivative = has_last_ ? (error - last_error_m_) / dt : 0.0;
  last_error_m_ = error;
  has_last_ = true;

  const double unsaturated = feedforward + options_.kp_per_s * error +
                             options_.ki_per_s2 * integral_m_s_ + options_.kd * derivative;
  // Limits: speed, acceleration (rate of the command), and the braking distance to
  // the ends of the tether (0 and L).
  const double vmax = c.limits.max_speed_mps, amax = c.limits.max_acceleration_mps2;
  double hi = std::min(
      vmax, std::sqrt(2.0 * amax * std::max(0.0, c.limits.total_length_m - obs.released_m)));
  double lo = -std::min(vmax, std::sqrt(2.0 * amax * std::max(0.0, obs.released_m)));
  hi = std::min(hi, last_command_mps_ + amax * dt);
  lo = std::max(lo, last_command_mps_ - amax * dt);
  if (lo > hi)
    lo = hi = std::clamp(0.0, last_command_mps_ - amax * dt, last_command_mps_ + amax * dt);
  const double command =
      c.reel_in_guard.limit(std::clamp(unsaturated, lo, hi), slack - c.margin_m(obs),
                            required_length_rate_mps(*model_, now), c.limits, lo, hi);
  // Conditional integration: stop integrating while the error pushes further into saturation.
  const bool saturated_up = unsaturated > hi && error > 0.0;
  const bool saturated_down = unsaturated < lo && error < 0.0;
  if (!saturated_up && !saturated_down)
    integral_m_s_ = std::clamp(integral_m_s_ + error * dt, -options_.integral_limit_m_s,
                               options_.integral_limit_m_s);
  last_command_mps_ = command;
  return command;
}

}  // namespace ferret::tether
