#pragma once
// Offline plan validation (`ferret validate`): every segment checked at the exact
// checker's resolution (FCL alone, with the map's unknown-space policy), the
// geofence, speed and yaw-rate limits, monotonic time, and for miniUGV plans the
// tether: replayed from its initial wrap points, l_0 + taut length <= L everywhere.

#include <optional>
#include <string>

#include "ferret/planning/collision_checker.hpp"
#include "ferret/planning/plan_file.hpp"

namespace ferret {

struct ValidationOptions {
  CheckResolution resolution;
  std::optional<Aabb3> geofence;
  double max_velocity_mps = 2.0;
  double max_yaw_rate_radps = 2.0;
  /// The taut-tether budget L - l_0; nullopt: from the plan's tether section.
  std::optional<double> tether_max_m;
  /// Entry point for plans without a tether section (CSV); the tether starts straight.
  std::optional<Eigen::Vector2d> p_WE;
};

struct Violation {
  std::size_t index = 0;  ///< the state at which it happens (for a segment: its end)
  double t_s = 0.0;       ///< time of the offending pose
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  std::string reason;
};

/// The first violation of the plan, or nullopt when it is valid. `corners` are the
/// tether's obstacle corners (required for miniUGV plans).
[[nodiscard]] std::optional<Violation> validate_plan(const PlanFile& plan, CollisionChecker& exact,
                                                     const std::shared_ptr<const TetherCorners>& corners,
                                                     const ValidationOptions& options);

/// The check resolution the planners use for a robot (validation uses the same).
[[nodiscard]] CheckResolution default_resolution(PlanRobot robot);

}  // namespace ferret
