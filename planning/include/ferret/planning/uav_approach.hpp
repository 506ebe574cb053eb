#pragma once
// One call for a UAV leg: from a start pose to a goal pose, or to the hover pose in
// front of a hidden space's opening, in a loaded world, with the robot's shapes and
// limits, returning the whole plan file `ferret plan uav` writes. What it decides
// (the geofence from the world, the goal from a hidden space's name, the shape with
// the miniUGV hanging below) is decided here once, for the CLI, the service and
// downstream programs alike. No OMPL or FCL types.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "ferret/planning/mission_config.hpp"
#include "ferret/planning/plan_file.hpp"
#include "ferret/planning/planning_world.hpp"

namespace ferret {

struct UavApproachRequest {
  Waypoint start;                ///< x, y, z, yaw in the world frame
  std::optional<Waypoint> goal;  ///< the goal pose; or, exactly one of the two:
  std::string hidden_space;      ///< goal: approach_hover_pose() of this hidden space
  /// Tether paid out below the UAV (l_t): plan with the miniUGV hanging on it
  /// (robot "uav_with_ugv"); nullopt: the UAV alone. [0, 100] m.
  std::optional<double> tether_released_m;
  /// The geofence, its z range the altitude band; nullopt: default_uav_bounds(world).
  std::optional<Aabb3> bounds;
  UnknownPolicy unknown = UnknownPolicy::kFree;  ///< kOccupied: unknown inside the fence blocks
  std::string planner = "rrtconnect";            ///< one of ompl_planner_names()
  PlanRobotModel robot;                          ///< default: the shipped m100.urdf
  MissionConfig mission;      ///< limits for built-in shapes, the URDF's otherwise
  double time_limit_s = 1.0;  ///< a cap on a search that finds nothing, (0, 3600]
  std::uint64_t seed = 1;     ///< seeds OMPL once per process (seed_ompl_once)
  /// Polled during the search (cheap: an atomic load); true stops it.
  std::function<bool()> cancelled;
};

/// Plans the UAV leg of `request` in `world`. Returns solved = false with the reason
/// when no path is found. Throws InputError naming the request field
/// (source "UavApproachRequest") for bad input: non-finite poses, both or neither of
/// goal and hidden_space, a hidden space the world does not have (the message lists
/// the world's), an unknown planner (the message lists them), a time limit or a tether
/// length out of range, a URDF of a ground robot; and the loaders' errors.
[[nodiscard]] PlanResult plan_uav_approach(const PlanningWorld& world,
                                           const UavApproachRequest& request);

/// What a UAV plan needs besides its poses: the robot (with the miniUGV hanging at the
/// request's l_t), the geofence and the collision snapshot inside it. A program
/// planning many legs in one world (the planner service) makes it once per geofence,
/// unknown policy and l_t.
struct UavApproachSetup {
  LoadedPlanRobot model;
  PlanRobot robot = PlanRobot::kUav;
  double released_m = 0.0;
  Aabb3 geofence;
  std::shared_ptr<const CollisionMap> map;
};

/// The setup for `request` (its poses, planner, time limit and seed are not read).
/// InputError as plan_uav_approach() for the fields it reads.
[[nodiscard]] UavApproachSetup prepare_uav_approach(const PlanningWorld& world,
                                                    const UavApproachRequest& request);
/// plan_uav_approach() with a setup prepare_uav_approach() made in this world for the
/// request's robot, l_t, geofence and unknown policy.
[[nodiscard]] PlanResult plan_uav_approach(const PlanningWorld& world,
                                           const UavApproachRequest& request,
                                           const UavApproachSetup& setup);

}  // namespace ferret
