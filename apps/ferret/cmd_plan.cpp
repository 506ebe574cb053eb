// `ferret plan uav | ugv`: one OMPL plan in a world (world YAML, .bt or .ot) written
// as plan JSON (docs/planning.md). Exit 0 with a plan, 1 when no path was found (no
// file is written), 2 for bad input.

#include <fmt/format.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/planning/benchmark_problems.hpp"
#include "ferret/planning/ompl_setup.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/planning/uav_planner.hpp"
#include "ferret/planning/ugv_planner.hpp"
#include "ferret/urdf/mission_config.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::cli {
namespace {

struct Common {
  std::string world, output, config, robot;
  double time_limit_s = 1.0;
  std::uint64_t seed = 1;
};

void add_common(CLI::App* sub, Common& c) {
  sub->add_option("--world", c.world, "world YAML, .bt or .ot")->required();
  sub->add_option("-o,--output", c.output, "plan JSON to write")->required();
  sub->add_option("--config", c.config, "mission YAML (motion limits, tether L and l_0)");
  sub->add_option("--robot", c.robot,
                  "robot URDF for the collision shapes (default: urdf/models/m100.urdf or miniugv.urdf; "
                  "\"builtin\" for ferret's simple shapes)");
  sub->add_option("--time-limit", c.time_limit_s, "planning time limit, seconds")->capture_default_str();
  sub->add_option("--seed", c.seed, "random seed")->capture_default_str();
}

MissionConfig mission(const Common& c) { return c.config.empty() ? MissionConfig{} : load_mission_config(c.config); }

// The collision shapes: the robot's URDF (the shipped model by default), or the
// built-in shapes. Returns the URDF path recorded in the plan ("" for built-in).
std::string robot_model(const Common& c, const char* default_model, const MissionConfig& config,
                        RobotKind expected, std::optional<RobotShape>& shape) {
  if (c.robot == "builtin") return {};
  const std::filesystem::path path = c.robot.empty() ? find_model(default_model) : std::filesystem::path(c.robot);
  const RobotDescription robot = load_robot_description(path, config);
  if (robot.kind != expected)
    throw InputError("--robot", "", fmt::format("a URDF of a {}", to_string(expected)), path.string());
  shape = robot_shape_from_description(robot);
  return path.lexically_normal().string();
}

void check_time_limit(const Common& c) {
  if (!(c.time_limit_s > 0.0 && c.time_limit_s <= 3600.0))
    throw InputError("--time-limit", "", "seconds in (0, 3600]", std::to_string(c.time_limit_s));
}

double path_length(const std::vector<Waypoint>& s) {
  double l = 0.0;
  for (std::size_t k = 1; k < s.size(); ++k) l += (s[k].position() - s[k - 1].position()).norm();
  return l;
}

void write_and_report(const PlanFile& plan, const std::string& output) {
  save_plan(plan, output);
  std::cout << fmt::format("solved in {:.1f} ms: {} states, {:.2f} m, {:.2f} s -> {}\n", plan.planning_time_s * 1e3,
                           plan.states.size(), path_length(plan.states), plan.states.back().t_s, output);
}

Waypoint xyz_yaw(const std::string& text, const std::string& option) {
  const auto v = parse_number_list(text, 4, option);
  Waypoint w;
  w.x_m = v[0];
  w.y_m = v[1];
  w.z_m = v[2];
  w.yaw_rad = v[3];
  return w;
}

struct UavArgs {
  Common common;
  std::string from, to, approach, geofence, altitude, unknown = "free", planner = "rrtconnect";
  std::optional<double> tether_length_m;
};

void run_uav(const UavArgs& a) {
  check_time_limit(a.common);
  if (a.to.empty() == a.approach.empty())
    throw InputError("--to", "", "either --to x,y,z,yaw or --approach HIDDEN_SPACE (not both)");
  const Waypoint start = xyz_yaw(a.from, "--from");
  Waypoint goal = a.to.empty() ? Waypoint{} : xyz_yaw(a.to, "--to");
  if (a.tether_length_m && !(*a.tether_length_m >= 0.0 && *a.tether_length_m <= 100.0))
    throw InputError("--tether-length", "", "a released length in [0, 100] m", std::to_string(*a.tether_length_m));
  const UnknownPolicy unknown = parse_unknown_policy(a.unknown, "--unknown");
  const auto& names = ompl_planner_names();
  if (std::find(names.begin(), names.end(), a.planner) == names.end()) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw InputError("--planner", "", "one of " + list, a.planner);
  }
  const MissionConfig config = mission(a.common);
  const PlanningWorld world = load_planning_world(a.common.world);
  if (!a.approach.empty()) {
    const int index = world.spec ? world.spec->find_hidden_space(a.approach) : -1;
    if (index < 0) throw InputError("--approach", "", "a hidden space of the world YAML " + a.common.world, a.approach);
    goal = approach_hover_pose(world.spec->hidden_spaces[static_cast<std::size_t>(index)]);
  }

  UavPlannerOptions opt;
  // Geofence: the world's bounds (YAML) or the map's known extent, unless given.
  double mx, my, mz, Mx, My, Mz;
  world.tree->getMetricMin(mx, my, mz);
  world.tree->getMetricMax(Mx, My, Mz);
  Eigen::Vector3d lo(mx, my, mz), hi(Mx, My, Mz);
  if (world.spec) {
    lo = world.spec->bounds_min_m;
    hi = world.spec->bounds_max_m;
  }
  opt.geofence = {{lo.x(), lo.y(), std::max(lo.z(), 0.0) + 0.5}, {hi.x(), hi.y(), hi.z() - 0.5}};
  if (!a.geofence.empty()) {
    const auto g = parse_number_list(a.geofence, 4, "--geofence");
    if (g[0] >= g[2] || g[1] >= g[3]) throw InputError("--geofence", "", "x0,y0,x1,y1 with x0 < x1, y0 < y1", a.geofence);
    opt.geofence.lo.head<2>() = Eigen::Vector2d(g[0], g[1]);
    opt.geofence.hi.head<2>() = Eigen::Vector2d(g[2], g[3]);
  }
  if (!a.altitude.empty()) {
    const auto z = parse_number_list(a.altitude, 2, "--altitude");
    if (z[0] >= z[1]) throw InputError("--altitude", "", "zmin,zmax with zmin < zmax", a.altitude);
    opt.geofence.lo.z() = z[0];
    opt.geofence.hi.z() = z[1];
  }
  opt.planner = a.planner;
  opt.time_limit_s = a.common.time_limit_s;
  opt.seed = a.common.seed;
  opt.max_velocity_mps = config.uav_limits.max_velocity_mps;
  opt.max_yaw_rate_radps = config.uav_limits.max_yaw_rate_radps;
  seed_ompl_once(a.common.seed);

  const auto map = CollisionMap::build(*world.tree, uav_map_options(world.spec, unknown, opt.geofence));
  const PlanRobot robot = a.tether_length_m ? PlanRobot::kUavWithUgv : PlanRobot::kUav;
  std::optional<RobotShape> urdf_shape;
  const std::string model = robot_model(a.common, "m100.urdf", config, RobotKind::kUav, urdf_shape);
  UavPlanner planner(map, plan_robot_shape(robot, a.tether_length_m.value_or(0.0), urdf_shape ? &*urdf_shape : nullptr),
                     opt);
  const UavPlan result = planner.plan(start, goal);
  if (!result.solved) throw CheckFailed("no UAV path: " + result.status);

  PlanFile plan;
  plan.robot = robot;
  plan.robot_model = model;
  plan.released_length_m = a.tether_length_m.value_or(0.0);
  plan.states = result.states;
  plan.unknown_policy = unknown;
  plan.bounds = opt.geofence;
  plan.max_velocity_mps = opt.max_velocity_mps;
  plan.max_yaw_rate_radps = opt.max_yaw_rate_radps;
  plan.planner = opt.planner;
  plan.planning_time_s = result.planning_time_s;
  plan.seed = a.common.seed;
  plan.world = a.common.world;
  write_and_report(plan, a.common.output);
}

struct UgvArgs {
  Common common;
  std::string from, to, entry, driven, hidden_space, bounds;
  std::optional<double> tether_max_m, floor_z_m;
  bool return_path = false;
};

void run_ugv(const UgvArgs& a) {
  check_time_limit(a.common);
  const auto f = parse_number_list(a.from, 3, "--from"), t = parse_number_list(a.to, 3, "--to");
  const MissionConfig config = mission(a.common);
  TetherParams tether = config.tether;
  if (a.tether_max_m) {
    if (!(*a.tether_max_m > 0.0 && *a.tether_max_m <= 1000.0))
      throw InputError("--tether", "", "a taut-length budget in (0, 1000] m", std::to_string(*a.tether_max_m));
    tether.total_length_m = tether.entry_offset_m + *a.tether_max_m;
  }
  std::vector<Eigen::Vector2d> driven;
  if (!a.driven.empty()) {
    std::stringstream ss(a.driven);
    for (std::string point; std::getline(ss, point, ';');) {
      const auto p = parse_number_list(point, 2, "--driven");
      driven.emplace_back(p[0], p[1]);
    }
  }
  const PlanningWorld world = load_planning_world(a.common.world);

  // The hidden space: named, or the one the start lies in (world YAML), or explicit.
  HiddenSpaceFrame space;
  bool have_space = false;
  if (world.spec) {
    int index = -1;
    if (!a.hidden_space.empty()) {
      index = world.spec->find_hidden_space(a.hidden_space);
      if (index < 0) throw InputError("--hidden-space", "", "a hidden space of " + a.common.world, a.hidden_space);
    } else {
      index = hidden_space_at(*world.spec, {f[0], f[1]});
    }
    if (index >= 0) {
      space = hidden_space_frame(world.spec->hidden_spaces[static_cast<std::size_t>(index)]);
      have_space = true;
    }
  } else if (!a.hidden_space.empty()) {
    throw InputError("--hidden-space", "", "a world YAML (an OctoMap file has no named hidden spaces)", a.common.world);
  }
  if (!a.bounds.empty()) {
    const auto b = parse_number_list(a.bounds, 4, "--bounds");
    if (b[0] >= b[2] || b[1] >= b[3]) throw InputError("--bounds", "", "x0,y0,x1,y1 with x0 < x1, y0 < y1", a.bounds);
    space.lo_m = {b[0], b[1]};
    space.hi_m = {b[2], b[3]};
    have_space = true;
  }
  if (a.floor_z_m) space.floor_z_m = *a.floor_z_m;
  if (!a.entry.empty()) {
    const auto e = parse_number_list(a.entry, 2, "--entry");
    space.p_WE = {e[0], e[1]};
  } else if (!have_space || !world.spec) {
    throw InputError("--entry", "", "the tether's entry point x,y (required unless a world YAML names the hidden space)");
  }
  if (!have_space)
    throw InputError("--bounds", "", "the hidden space's x0,y0,x1,y1 (or a world YAML whose hidden space holds --from)");

  const auto map = ugv_collision_map(*world.tree, space);
  std::optional<RobotShape> urdf_shape;
  const std::string model = robot_model(a.common, "miniugv.urdf", config, RobotKind::kUgv, urdf_shape);
  UgvPlannerOptions opt;
  if (urdf_shape) opt.shape = plan_robot_shape(PlanRobot::kUgv, 0.0, &*urdf_shape);
  opt.time_limit_s = a.common.time_limit_s;
  opt.seed = a.common.seed;
  opt.max_velocity_mps = config.ugv_limits.max_velocity_mps;
  opt.max_yaw_rate_radps = config.ugv_limits.max_yaw_rate_radps;
  UgvPlanner planner(map, space, {}, opt);
  UgvPlanRequest req;
  req.start = {f[0], f[1], f[2]};
  req.goal = {t[0], t[1], t[2]};
  req.driven = driven;
  req.tether = tether;
  const UgvPlan result = a.return_path ? planner.plan_return(req) : planner.plan(req);
  if (!result.solved) throw CheckFailed("no miniUGV path: " + result.status);

  PlanFile plan;
  plan.robot = PlanRobot::kUgv;
  plan.robot_model = model;
  plan.states = result.states;
  plan.tether = PlanTether{space.p_WE, result.initial_wraps, tether.total_length_m, tether.entry_offset_m};
  plan.unknown_policy = UnknownPolicy::kOccupied;
  plan.bounds = ugv_policy_bounds(space);
  plan.max_velocity_mps = opt.max_velocity_mps;
  plan.max_yaw_rate_radps = opt.max_yaw_rate_radps;
  plan.planner = "TetheredRRT";
  plan.planning_time_s = result.planning_time_s;
  plan.seed = a.common.seed;
  plan.world = a.common.world;
  write_and_report(plan, a.common.output);
  std::cout << fmt::format("tether: {:.2f} m taut at the goal (budget {:.2f} m), {} wrap points\n",
                           plan.states.back().tether_length_m, tether.total_length_m - tether.entry_offset_m,
                           result.final_wraps.size());
}

const CommandRegistration kPlan{"plan", [](CLI::App& app) {
  auto* plan = app.add_subcommand("plan", "Plan a UAV approach or a tether-aware miniUGV path (OMPL) to plan JSON");
  plan->require_subcommand(1);

  auto ua = std::make_shared<UavArgs>();
  auto* uav = plan->add_subcommand("uav", "UAV in x, y, z, yaw inside a geofence and altitude band");
  add_common(uav, ua->common);
  uav->add_option("--from", ua->from, "start x,y,z,yaw (m, rad)")->required();
  uav->add_option("--to", ua->to, "goal x,y,z,yaw (m, rad)");
  uav->add_option("--approach", ua->approach,
                  "goal: the hover pose 1 m in front of this hidden space's opening, 1.5 m up, facing it");
  uav->add_option("--tether-length", ua->tether_length_m,
                  "plan with the miniUGV hanging on this much released tether (m)");
  uav->add_option("--geofence", ua->geofence, "x0,y0,x1,y1 (default: the world's bounds)");
  uav->add_option("--altitude", ua->altitude, "zmin,zmax (default: 0.5 m above the ground to 0.5 m below the top)");
  uav->add_option("--unknown", ua->unknown, "unknown space: free or occupied (inside the geofence)")
      ->capture_default_str();
  uav->add_option("--planner", ua->planner, "OMPL planner: rrtconnect, rrt, rrtstar, prm, lazyprm, kpiece, bkpiece, est, bitstar")
      ->capture_default_str();
  uav->callback([ua] { run_uav(*ua); });

  auto ga = std::make_shared<UgvArgs>();
  auto* ugv = plan->add_subcommand("ugv", "miniUGV in a hidden space (SE2, unknown occupied, tether-aware)");
  add_common(ugv, ga->common);
  ugv->add_option("--from", ga->from, "start x,y,yaw (m, rad)")->required();
  ugv->add_option("--to", ga->to, "goal x,y,yaw (m, rad)")->required();
  ugv->add_option("--entry", ga->entry, "tether entry point x,y (default: the hidden space's)");
  ugv->add_option("--tether", ga->tether_max_m, "taut tether budget L - l_0 on the floor, m (default: from the mission)");
  ugv->add_option("--driven", ga->driven, "path driven since the entry, \"x,y;x,y;...\" (gives the tether's wraps)");
  ugv->add_option("--hidden-space", ga->hidden_space, "hidden space of a world YAML (default: the one holding --from)");
  ugv->add_option("--bounds", ga->bounds, "plan bounds x0,y0,x1,y1 (needed for .bt/.ot worlds)");
  ugv->add_option("--floor-z", ga->floor_z_m, "floor height, m (top of the floor voxels)");
  ugv->add_flag("--return", ga->return_path, "return along the tether (retrace its wrap points)");
  ugv->callback([ga] { run_ugv(*ga); });
}};

}  // namespace
}  // namespace ferret::cli
