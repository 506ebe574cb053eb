#include "ferret/planning/uav_approach.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>

#include "ferret/core/error.hpp"
#include "ferret/planning/ompl_setup.hpp"
#include "ferret/planning/uav_planner.hpp"

namespace ferret {
namespace {

constexpr const char* kSource = "UavApproachRequest";

void check_pose(const Waypoint& w, const char* field) {
  if (!(std::isfinite(w.x_m) && std::isfinite(w.y_m) && std::isfinite(w.z_m) &&
        std::isfinite(w.yaw_rad)))
    throw InputError(kSource, field, "a finite pose x, y, z, yaw",
                     fmt::format("{},{},{},{}", w.x_m, w.y_m, w.z_m, w.yaw_rad));
}

}  // namespace

namespace {

void check_request(const UavApproachRequest& r) {
  check_pose(r.start, "start");
  if (r.goal.has_value() == !r.hidden_space.empty())
    throw InputError(kSource, "goal", "either a goal pose or a hidden space's name (not both)");
  if (r.goal) check_pose(*r.goal, "goal");
  if (!(std::isfinite(r.time_limit_s) && r.time_limit_s > 0.0 && r.time_limit_s <= 3600.0))
    throw InputError(kSource, "time_limit_s", "seconds in (0, 3600]",
                     fmt::format("{}", r.time_limit_s));
  const auto& names = ompl_planner_names();
  if (std::find(names.begin(), names.end(), r.planner) == names.end())
    throw InputError(kSource, "planner", fmt::format("one of {}", fmt::join(names, ", ")),
                     r.planner);
}

}  // namespace

UavApproachSetup prepare_uav_approach(const PlanningWorld& world,
                                      const UavApproachRequest& request) {
  const UavApproachRequest& r = request;
  if (r.tether_released_m && !(std::isfinite(*r.tether_released_m) && *r.tether_released_m >= 0.0 &&
                               *r.tether_released_m <= 100.0))
    throw InputError(kSource, "tether_released_m", "a released length in [0, 100] m",
                     fmt::format("{}", *r.tether_released_m));
  if (r.bounds && !(r.bounds->lo.allFinite() && r.bounds->hi.allFinite() &&
                    (r.bounds->lo.array() < r.bounds->hi.array()).all()))
    throw InputError(kSource, "bounds", "a box with min < max on every axis");
  UavApproachSetup setup;
  setup.robot = r.tether_released_m ? PlanRobot::kUavWithUgv : PlanRobot::kUav;
  setup.released_m = r.tether_released_m.value_or(0.0);
  setup.model =
      load_plan_robot(setup.robot, r.robot, r.mission, setup.released_m, kSource, "robot");
  setup.geofence = r.bounds.value_or(default_uav_bounds(world));
  check_box_in_key_range(setup.geofence, world.tree->getResolution(), kSource, "bounds");
  setup.map =
      CollisionMap::build(*world.tree, uav_map_options(world.spec, r.unknown, setup.geofence));
  return setup;
}

PlanResult plan_uav_approach(const PlanningWorld& world, const UavApproachRequest& request) {
  check_request(request);
  return plan_uav_approach(world, request, prepare_uav_approach(world, request));
}

PlanResult plan_uav_approach(const PlanningWorld& world, const UavApproachRequest& request,
                             const UavApproachSetup& setup) {
  const UavApproachRequest& r = request;
  check_request(r);
  const Waypoint goal =
      r.goal
          ? *r.goal
          : approach_hover_pose(find_hidden_space(world, r.hidden_space, kSource, "hidden_space"));
  const LoadedPlanRobot& model = setup.model;
  UavPlannerOptions opt;
  opt.geofence = setup.geofence;
  opt.planner = r.planner;
  opt.time_limit_s = r.time_limit_s;
  opt.seed = r.seed;
  opt.cancelled = r.cancelled;
  opt.max_velocity_mps = model.limits.max_velocity_mps;
  opt.max_yaw_rate_radps = model.limits.max_yaw_rate_radps;
  opt.max_acceleration_mps2 = model.limits.max_acceleration_mps2;
  seed_ompl_once(r.seed);
  UavPlanner planner(setup.map, model.shape, opt);
  const UavPlan found = planner.plan(r.start, goal);

  PlanResult out;
  out.solved = found.solved;
  out.status = found.status;
  out.failure = found.failure;
  out.planning_time_s = found.planning_time_s;
  PlanFile& plan = out.plan;
  plan.robot = setup.robot;
  plan.robot_model = model.model;
  plan.released_length_m = setup.released_m;
  if (found.solved) plan.states = found.states;
  plan.unknown_policy = r.unknown;
  plan.bounds = setup.geofence;
  plan.max_velocity_mps = opt.max_velocity_mps;
  plan.max_yaw_rate_radps = opt.max_yaw_rate_radps;
  plan.max_acceleration_mps2 = opt.max_acceleration_mps2;
  plan.planner = opt.planner;
  plan.planning_time_s = found.planning_time_s;
  plan.seed = r.seed;
  plan.world = world.source.string();
  return out;
}

}  // namespace ferret
