#pragma once
// Checks a plan from the one-call planners as `ferret validate` checks a plan file:
// FCL alone at the planners' resolution, the plan's unknown-space policy, bounds and
// limits (or the given ones), and a miniUGV plan's tether replayed from its wraps.

#include <limits>
#include <memory>
#include <optional>

#include "ferret/planning/collision_checker.hpp"
#include "ferret/planning/plan_validation.hpp"
#include "ferret/planning/planning_world.hpp"

namespace ferret::test {

inline std::optional<Violation> check_plan(
    const PlanningWorld& world, const PlanFile& plan,
    const std::optional<MotionLimits>& limits = std::nullopt) {
  CollisionMapOptions map_options;
  map_options.unknown = plan.unknown_policy.value_or(UnknownPolicy::kFree);
  map_options.bounds = plan.bounds;
  const auto map = CollisionMap::build(*world.tree, map_options);
  const LoadedPlanRobot robot = load_plan_robot(
      plan.robot, {plan.robot_model, plan.robot_model.empty()}, {}, plan.released_length_m);
  CollisionChecker exact(map, robot.shape);
  MotionLimits plan_limits;
  plan_limits.max_velocity_mps = plan.max_velocity_mps.value();
  plan_limits.max_yaw_rate_radps = plan.max_yaw_rate_radps.value();
  plan_limits.max_acceleration_mps2 =
      plan.max_acceleration_mps2.value_or(std::numeric_limits<double>::infinity());
  ValidationOptions options(limits.value_or(plan_limits), default_resolution(plan.robot));
  options.geofence = plan.bounds;
  std::shared_ptr<const TetherCorners> corners;
  if (plan.robot == PlanRobot::kUgv) {
    HiddenSpaceFrame space;
    space.lo_m = plan.bounds->lo.head<2>();
    space.hi_m = plan.bounds->hi.head<2>();
    space.floor_z_m = plan.bounds->lo.z();
    corners = tether_corners_from_map(*map, space, UgvGeometry{});
  }
  const ValidationReport report = validate_plan(plan, exact, corners, options);
  if (report.valid()) return std::nullopt;
  return report.violations.front();
}

}  // namespace ferret::test
