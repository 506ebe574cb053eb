#include "ferret/tether_model/tether_state_estimator.hpp"

namespace ferret::tether {

TetherStateEstimator::TetherStateEstimator(const TautControlOptions& options)
    : pose_filter(options.pose_filter_gain, options.ugv_velocity_lag_s, options.ugv_velocity_error,
                  options.slack_observer.pose_noise_m, options.control_period_s),
      slack_observer(options.slack_estimator, options.slack_observer, options.pose_filter_gain,
                     options.control_period_s),
      fixed_model_{options.ugv_velocity_lag_s, options.ugv_tracking_time_s} {
  pose_filter.set_response_model(options.ugv_velocity_lag_s, options.ugv_tracking_time_s);
  if (options.ugv_response_identification.enabled)
    response_identifier.emplace(options.ugv_response_identification, options.pose_filter_gain,
                                options.slack_observer.pose_noise_m);
}

void TetherStateEstimator::reset() {
  pose_filter.reset();
  pose_filter.set_response_model(fixed_model_.velocity_lag_s, fixed_model_.tracking_time_s);
  slack_observer.reset();
  if (response_identifier) response_identifier->reset();
}

UgvMotion TetherStateEstimator::filter_pose(double t_msg_s, const UgvMotion& measured) {
  if (response_identifier) {
    const auto m = response_identifier->update(t_msg_s, measured);
    pose_filter.set_response_model(m.velocity_lag_s, m.tracking_time_s);
  }
  return pose_filter.update(t_msg_s, measured);
}

}  // namespace ferret::tether
