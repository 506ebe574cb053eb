#include "ferret/planning/ugv_path.hpp"

#include <fmt/format.h>
#include <octomap/OcTree.h>

#include <cmath>

#include "ferret/core/error.hpp"
#include "ferret/planning/ugv_planner.hpp"

namespace ferret {
namespace {

constexpr const char* kSource = "UgvPathRequest";

void check_pose(const Pose2& p, const char* field) {
  if (!(std::isfinite(p.x_m) && std::isfinite(p.y_m) && std::isfinite(p.yaw_rad)))
    throw InputError(kSource, field, "a finite pose x, y, yaw",
                     fmt::format("{},{},{}", p.x_m, p.y_m, p.yaw_rad));
}

// The hidden space of a request: named, else the one holding the start (world YAML),
// with the explicit box, floor and entry laid over it.
HiddenSpaceFrame request_space(const PlanningWorld& world, const UgvPathRequest& r) {
  HiddenSpaceFrame space;
  bool have_space = false, have_entry = false;
  if (!r.hidden_space.empty()) {
    space = hidden_space_frame(find_hidden_space(world, r.hidden_space, kSource, "hidden_space"));
    have_space = have_entry = true;
  } else if (world.spec) {
    const int index = hidden_space_at(*world.spec, r.start.position());
    if (index >= 0) {
      space = hidden_space_frame(world.spec->hidden_spaces[static_cast<std::size_t>(index)]);
      have_space = have_entry = true;
    }
  } else if (world.map_2d) {
    space = map_2d_frame(*world.map_2d);  // a 2D map is one hidden space; no entry of its own
    have_space = true;
  }
  if (r.bounds) {
    const Aabb3& b = *r.bounds;
    if (!(b.lo.allFinite() && b.hi.allFinite() && (b.lo.array() < b.hi.array()).all()))
      throw InputError(kSource, "bounds", "a box with min < max on every axis");
    space.lo_m = b.lo.head<2>();
    space.hi_m = b.hi.head<2>();
    space.floor_z_m = b.lo.z();
    have_space = true;
  }
  if (r.floor_z_m) {
    // Within the map's key range (+-2^15 voxels), like every box the map is cut to.
    const double reach_m = 32767.0 * world.tree->getResolution();
    if (!(std::isfinite(*r.floor_z_m) && std::abs(*r.floor_z_m) < reach_m))
      throw InputError(
          kSource, "floor_z_m",
          fmt::format("a finite height within +-{:g} m (the map's key range)", reach_m),
          fmt::format("{:g}", *r.floor_z_m));
    space.floor_z_m = *r.floor_z_m;
  }
  if (r.p_WE) {
    if (!r.p_WE->allFinite()) throw InputError(kSource, "p_WE", "a finite entry point x, y");
    space.p_WE = *r.p_WE;
    have_entry = true;
  }
  // No box given and none found: the start is where the search for one failed.
  if (!have_space)
    throw InputError(kSource, "start",
                     "a start inside one of the world's hidden spaces (or a box as bounds)",
                     world.source.string());
  if (!have_entry)
    throw InputError(kSource, "p_WE",
                     "the tether's entry point (a box or a 2D map alone does not give one)");
  return space;
}

}  // namespace

namespace {

// The request's own fields: poses, path driven, time limit; and the tether it gives.
TetherParams checked_tether(const UgvPathRequest& r) {
  check_pose(r.start, "start");
  check_pose(r.goal, "goal");
  for (const Eigen::Vector2d& p : r.driven)
    if (!p.allFinite()) throw InputError(kSource, "driven", "finite points x, y");
  if (!(std::isfinite(r.time_limit_s) && r.time_limit_s > 0.0 && r.time_limit_s <= 3600.0))
    throw InputError(kSource, "time_limit_s", "seconds in (0, 3600]",
                     fmt::format("{}", r.time_limit_s));
  TetherParams tether = r.mission.tether;
  if (r.tether_budget_m) {
    if (!(std::isfinite(*r.tether_budget_m) && *r.tether_budget_m > 0.0 &&
          *r.tether_budget_m <= 1000.0))
      throw InputError(kSource, "tether_budget_m", "a taut tether length in (0, 1000] m",
                       fmt::format("{}", *r.tether_budget_m));
    tether.total_length_m = tether.entry_offset_m + *r.tether_budget_m;
  }
  return tether;
}

}  // namespace

HiddenSpaceFrame ugv_request_space(const PlanningWorld& world, const UgvPathRequest& request) {
  return request_space(world, request);
}

UgvPathSetup prepare_ugv_path(const PlanningWorld& world, const UgvPathRequest& request,
                              const HiddenSpaceFrame& space) {
  UgvPathSetup setup;
  setup.space = space;
  setup.model =
      load_plan_robot(PlanRobot::kUgv, request.robot, request.mission, 0.0, kSource, "robot");
  setup.map = [&] {
    try {
      return ugv_collision_map(*world.tree, space, setup.model.ugv);
    } catch (const InputError& e) {
      if (e.source() != "map") throw;
      throw InputError(kSource, "bounds", e.expected(),
                       fmt::format("{:g},{:g} to {:g},{:g}", space.lo_m.x(), space.lo_m.y(),
                                   space.hi_m.x(), space.hi_m.y()));
    }
  }();
  setup.corners = tether_corners_from_map(*setup.map, space, setup.model.ugv);
  return setup;
}

UgvPathResult plan_ugv_path(const PlanningWorld& world, const UgvPathRequest& request) {
  (void)checked_tether(request);  // bad poses are named before the space is looked for
  const HiddenSpaceFrame space = request_space(world, request);
  return plan_ugv_path(world, request, prepare_ugv_path(world, request, space));
}

UgvPathResult plan_ugv_path(const PlanningWorld& world, const UgvPathRequest& request,
                            const UgvPathSetup& setup) {
  const UgvPathRequest& r = request;
  const TetherParams tether = checked_tether(r);
  const HiddenSpaceFrame& space = setup.space;
  const LoadedPlanRobot& model = setup.model;
  UgvPlannerOptions opt;
  opt.shape = model.shape;
  opt.time_limit_s = r.time_limit_s;
  opt.seed = r.seed;
  opt.cancelled = r.cancelled;
  // The robot's limits: a URDF's wheel joints cap the mission's speed.
  opt.max_velocity_mps = model.limits.max_velocity_mps;
  opt.max_yaw_rate_radps = model.limits.max_yaw_rate_radps;
  opt.max_acceleration_mps2 = model.limits.max_acceleration_mps2;
  UgvPlanner planner(setup.map, space, model.ugv, opt, setup.corners);
  UgvPlanRequest req;
  req.start = r.start;
  req.goal = r.goal;
  req.driven = r.driven;
  req.tether = tether;
  const UgvPlan found =
      r.mode == UgvPathMode::kReturnAlongTether ? planner.plan_return(req) : planner.plan(req);

  UgvPathResult out;
  out.solved = found.solved;
  out.status = found.status;
  out.failure = found.failure;
  out.planning_time_s = found.planning_time_s;
  out.final_wraps = found.final_wraps;
  out.tether_budget_m = tether.total_length_m - tether.entry_offset_m;
  PlanFile& plan = out.plan;
  plan.robot = PlanRobot::kUgv;
  plan.robot_model = model.model;
  if (found.solved) plan.states = found.states;
  plan.tether =
      PlanTether{space.p_WE, found.initial_wraps, tether.total_length_m, tether.entry_offset_m};
  plan.unknown_policy = UnknownPolicy::kOccupied;
  plan.bounds = ugv_policy_bounds(space, model.ugv);
  plan.max_velocity_mps = opt.max_velocity_mps;
  plan.max_yaw_rate_radps = opt.max_yaw_rate_radps;
  plan.max_acceleration_mps2 = opt.max_acceleration_mps2;
  plan.planner = "TetheredRRT";
  plan.planning_time_s = found.planning_time_s;
  plan.seed = r.seed;
  plan.world = world.source.string();
  return out;
}

}  // namespace ferret
