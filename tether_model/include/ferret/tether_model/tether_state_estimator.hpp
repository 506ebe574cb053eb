#pragma once
// What both controllers estimate from an observation: the miniUGV's motion and the
// slack.

#include <optional>

#include "ferret/tether_model/slack_observer.hpp"
#include "ferret/tether_model/taut_control_options.hpp"
#include "ferret/tether_model/ugv_position_filter.hpp"
#include "ferret/tether_model/ugv_response_identifier.hpp"

namespace ferret::tether {

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

}  // namespace ferret::tether
