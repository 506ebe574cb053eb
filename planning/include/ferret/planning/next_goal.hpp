#pragma once
// One exploration decision from maps received from elsewhere (the planner service's
// POST /v1/explore/next-goal): the grid G and the object map O as probabilities, the
// robot's pose and velocity; the policy (cdos, rapid, ...) chooses the next goal as it
// would inside the miniUGV's search loop. Stateless: the frontier history the loop
// keeps (blacklisted cells, a committed goal) starts empty each call.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/grid.hpp"
#include "ferret/core/pose.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/planning/mission_config.hpp"

namespace ferret {

struct NextGoalRequest {
  GridGeometry geometry;
  /// Per cell (row-major from the origin, rows along y): the occupancy probability in
  /// [0, 1], or a negative value for unknown.
  std::vector<float> occupancy;
  /// Per cell, the object's probability in [0, 1]; empty: the prior 0.5 everywhere.
  std::vector<float> object_probability;
  /// Per cell, the confidence in [0, 1] of the last detection fused into it (0: none),
  /// which CDOS predicts the next view's confidence from. Empty: a cell with evidence
  /// (p > 0.5) is taken as seen once, from the prior, so its last confidence is p
  /// itself (at most the confidence cap).
  std::vector<float> object_confidence;
  Pose2 pose;
  Eigen::Vector2d velocity_W = Eigen::Vector2d::Zero();
  std::string method = "cdos";  ///< any registered policy but the oracle
  MissionConfig mission;        ///< the object search's constants, the speed
  double ir_fov_rad = 0.5235987755982988;
  double ir_range_m = 4.0;
  double camera_range_m = 4.0;
  double clearance_m = 0.15;  ///< the robot's radius plus margin (the grid's inflation)
  std::uint64_t seed = 1;
};

/// The policy's next goal, with its path from the robot over known-free cells; none
/// when no frontier is reachable. InputError (source "NextGoalRequest", the field named)
/// for a map whose size does not match its geometry, probabilities or confidences outside [0, 1], a
/// pose outside the grid, an unknown method or the oracle.
[[nodiscard]] std::optional<ExplorationGoal> next_exploration_goal(const NextGoalRequest& request);

}  // namespace ferret
