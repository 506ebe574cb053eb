#pragma once
// The options both winch controllers share.

#include <algorithm>

#include "ferret/tether_model/reel_in_guard.hpp"
#include "ferret/tether_model/slack_estimator.hpp"
#include "ferret/tether_model/slack_observer.hpp"
#include "ferret/tether_model/tether_observation.hpp"
#include "ferret/tether_model/ugv_position_filter.hpp"
#include "ferret/tether_model/ugv_response_identifier.hpp"
#include "ferret/tether_model/winch_limits.hpp"

namespace ferret::tether {

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
  double control_period_s = 0.02;         ///< 50 Hz
  double ugv_max_speed_mps = 2.0;         ///< caps the miniUGV prediction
  double pose_filter_gain = 0.05;         ///< UgvPositionFilter gain a cycle (1: raw positions)
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

}  // namespace ferret::tether
