// `ferret plan uav | ugv`: one OMPL plan in a world (world YAML, .bt or .ot) written
// as plan JSON (docs/planning.md). Exit 0 with a plan, 1 when no path was found (no
// file is written), 2 for bad input. The planning is the library's one-call
// functions (uav_approach.hpp, ugv_path.hpp); this file maps options onto requests.

#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/planning/ompl_setup.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/planning/uav_approach.hpp"
#include "ferret/planning/ugv_path.hpp"

namespace ferret::cli {
namespace {

struct Common {
  std::string world, out, mission, robot;
  double time_limit_s = 1.0;
  std::uint64_t seed = 1;
};

void add_common(CLI::App* sub, Common& c, const char* default_model) {
  add_world_option(sub, c.world, true,
                   "world YAML, map_server YAML (a 2D hidden space), .bt or .ot");
  add_out_option(sub, c.out, "plan JSON to write");
  add_mission_option(sub, c.mission);
  add_robot_option(
      sub, c.robot,
      fmt::format("{}; \"builtin\" for ferret's simple shapes with the mission's limits",
                  default_model));
  sub->add_option("--time-limit", c.time_limit_s,
                  "planning time limit, seconds (a cap on a search that finds nothing)")
      ->capture_default_str();
  add_seed_option(sub, c.seed, "seed of the planner");
}

PlanRobotModel robot_model(const Common& c, const char* default_model) {
  if (c.robot == "builtin") return {{}, true};
  return {resolve_robot(c.robot, default_model), false};
}

// The library names its request's fields; the user typed options. Errors about a
// field the command line set are reported under the option's name.
[[noreturn]] void rethrow_as_option(const InputError& e, const std::string& source,
                                    const std::map<std::string, std::string>& options) {
  const auto it = options.find(e.field());
  if (e.source() != source || it == options.end()) throw e;
  const std::string head = e.source() + ": " + e.field() + ": expected " + e.expected();
  std::string got = std::string(e.what()).substr(head.size());  // " (got X)" or ""
  if (got.size() > 7) got = got.substr(6, got.size() - 7);
  throw InputError(it->second, "", e.expected(), got);
}

double path_length(const std::vector<Waypoint>& s) {
  double l = 0.0;
  for (std::size_t k = 1; k < s.size(); ++k) l += (s[k].position() - s[k - 1].position()).norm();
  return l;
}

void write_and_report(const PlanResult& result, const std::string& out) {
  save_plan(result.plan, out);
  const auto& states = result.plan.states;
  std::cout << fmt::format("solved in {:.1f} ms: {} states, {:.2f} m, {:.2f} s -> {}\n",
                           result.planning_time_s * 1e3, states.size(), path_length(states),
                           states.back().t_s, out);
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

Pose2 xy_yaw(const std::string& text, const std::string& option) {
  const auto v = parse_number_list(text, 3, option);
  return {v[0], v[1], v[2]};
}

struct UavArgs {
  Common common;
  std::string from, to, approach, bounds, geofence, altitude, unknown = "free",
                                                              planner = "rrtconnect";
  std::optional<double> tether_released_m;
};

// --bounds, or the old --geofence x0,y0,x1,y1 / --altitude z0,z1 laid over the default.
std::optional<Aabb3> uav_bounds(const UavArgs& a, const PlanningWorld& world) {
  if (!a.bounds.empty()) return parse_bounds(a.bounds);
  if (a.geofence.empty() && a.altitude.empty()) return std::nullopt;
  Aabb3 fence = default_uav_bounds(world);
  if (!a.geofence.empty()) {
    const auto g = parse_number_list(a.geofence, 4, "--geofence");
    if (g[0] >= g[2] || g[1] >= g[3])
      throw InputError("--geofence", "", "x0,y0,x1,y1 with x0 < x1, y0 < y1", a.geofence);
    fence.lo.head<2>() = Eigen::Vector2d(g[0], g[1]);
    fence.hi.head<2>() = Eigen::Vector2d(g[2], g[3]);
  }
  if (!a.altitude.empty()) {
    const auto z = parse_number_list(a.altitude, 2, "--altitude");
    if (z[0] >= z[1]) throw InputError("--altitude", "", "zmin,zmax with zmin < zmax", a.altitude);
    fence.lo.z() = z[0];
    fence.hi.z() = z[1];
  }
  return fence;
}

void run_uav(const UavArgs& a) {
  (void)checked_out_file(a.common.out, "the plan JSON to write");
  if (a.to.empty() == a.approach.empty())
    throw InputError("--to", "", "either --to x,y,z,yaw or --approach HIDDEN_SPACE (not both)");
  check_choice("--planner", a.planner, ompl_planner_names());
  UavApproachRequest req;
  req.start = xyz_yaw(a.from, "--from");
  if (!a.to.empty()) req.goal = xyz_yaw(a.to, "--to");
  req.hidden_space = a.approach;
  req.tether_released_m = a.tether_released_m;
  req.unknown = parse_unknown_policy(a.unknown, "--unknown");
  req.planner = a.planner;
  req.robot = robot_model(a.common, "m100.urdf");
  req.mission = load_mission_or_defaults(a.common.mission);
  req.time_limit_s = a.common.time_limit_s;
  req.seed = a.common.seed;
  const PlanningWorld world = load_planning_world(a.common.world);
  req.bounds = uav_bounds(a, world);
  PlanResult result;
  try {
    result = plan_uav_approach(world, req);
  } catch (const InputError& e) {
    rethrow_as_option(e, "UavApproachRequest",
                      {{"start", "--from"},
                       {"goal", "--to"},
                       {"hidden_space", "--approach"},
                       {"time_limit_s", "--time-limit"},
                       {"tether_released_m", "--tether-released"},
                       {"planner", "--planner"},
                       {"bounds", "--bounds"},
                       {"robot", "--robot"}});
  }
  if (!result.solved) throw CheckFailed("no UAV path: " + result.status);
  write_and_report(result, a.common.out);
}

struct UgvArgs {
  Common common;
  std::string from, to, entry, driven, hidden_space, bounds;
  std::optional<double> tether_budget_m, floor_z_m;
  bool return_path = false;
};

void run_ugv(const UgvArgs& a) {
  (void)checked_out_file(a.common.out, "the plan JSON to write");
  UgvPathRequest req;
  req.start = xy_yaw(a.from, "--from");
  req.goal = xy_yaw(a.to, "--to");
  req.hidden_space = a.hidden_space;
  if (std::count(a.bounds.begin(), a.bounds.end(), ',') == 3) {
    // The old x0,y0,x1,y1 (hidden): the floor at --floor-z, else z = 0.
    const auto b = parse_number_list(a.bounds, 4, "--bounds");
    if (b[0] >= b[2] || b[1] >= b[3])
      throw InputError("--bounds", "", "x0,y0,z0,x1,y1,z1 with min < max", a.bounds);
    const double z0 = a.floor_z_m.value_or(0.0);
    req.bounds = Aabb3{{b[0], b[1], z0}, {b[2], b[3], z0 + 1.0}};
  } else {
    req.bounds = parse_bounds(a.bounds);
  }
  req.floor_z_m = a.floor_z_m;
  if (!a.entry.empty()) {
    const auto e = parse_number_list(a.entry, 2, "--entry");
    req.p_WE = Eigen::Vector2d(e[0], e[1]);
  }
  req.tether_budget_m = checked_tether_budget(a.tether_budget_m);
  if (!a.driven.empty()) {
    std::stringstream ss(a.driven);
    for (std::string point; std::getline(ss, point, ';');) {
      const auto p = parse_number_list(point, 2, "--driven");
      req.driven.emplace_back(p[0], p[1]);
    }
  }
  req.mode = a.return_path ? UgvPathMode::kReturnAlongTether : UgvPathMode::kPlan;
  req.robot = robot_model(a.common, "miniugv.urdf");
  req.mission = load_mission_or_defaults(a.common.mission);
  req.time_limit_s = a.common.time_limit_s;
  req.seed = a.common.seed;
  const PlanningWorld world = load_planning_world(a.common.world);
  UgvPathResult result;
  try {
    result = plan_ugv_path(world, req);
  } catch (const InputError& e) {
    rethrow_as_option(e, "UgvPathRequest",
                      {{"start", "--from"},
                       {"goal", "--to"},
                       {"hidden_space", "--hidden-space"},
                       {"time_limit_s", "--time-limit"},
                       {"tether_budget_m", "--tether-budget"},
                       {"bounds", "--bounds"},
                       {"p_WE", "--entry"},
                       {"floor_z_m", "--floor-z"},
                       {"driven", "--driven"},
                       {"robot", "--robot"}});
  }
  if (!result.solved) throw CheckFailed("no miniUGV path: " + result.status);
  write_and_report(result, a.common.out);
  std::cout << fmt::format("tether: {:.2f} m taut at the goal (budget {:.2f} m), {} wrap points\n",
                           result.plan.states.back().tether_length_m, result.tether_budget_m,
                           result.final_wraps.size());
}

const CommandRegistration kPlan{
    "plan", [](CLI::App& app) {
      auto* plan = app.add_subcommand(
          "plan", "Plan a UAV approach or a tether-aware miniUGV path (OMPL) to plan JSON");
      plan->require_subcommand(1);

      auto ua = std::make_shared<UavArgs>();
      auto* uav = plan->add_subcommand(
          "uav", "UAV in x, y, z, yaw inside a geofence box (its z range the altitude band)");
      add_common(uav, ua->common, "m100");
      uav->add_option("--from", ua->from, "start x,y,z,yaw (m, rad)")->required();
      uav->add_option("--to", ua->to, "goal x,y,z,yaw (m, rad); required unless --approach");
      uav->add_option(
          "--approach", ua->approach,
          "goal: the hover pose 1 m in front of this hidden space's opening, 1.5 m up, facing it "
          "(required unless --to)");
      uav->add_option(
          "--tether-released", ua->tether_released_m,
          "plan with the miniUGV hanging on this much released tether l_t, metres in [0, 100] "
          "(default: none, the UAV alone)");
      add_hidden_alias(uav, "--tether-length", ua->tether_released_m);
      add_bounds_option(uav, ua->bounds,
                        "the geofence, its z range the altitude band (default: the world's bounds, "
                        "from 0.5 m above the ground to 0.5 m below the top)");
      add_hidden_alias(uav, "--geofence", ua->geofence);
      add_hidden_alias(uav, "--altitude", ua->altitude);
      uav->add_option("--unknown", ua->unknown,
                      "unknown space: free or occupied (inside the geofence)")
          ->capture_default_str();
      uav->add_option("--planner", ua->planner, "OMPL planner: " + one_of(ompl_planner_names()))
          ->capture_default_str();
      uav->callback([ua] { run_uav(*ua); });

      auto ga = std::make_shared<UgvArgs>();
      auto* ugv = plan->add_subcommand(
          "ugv", "miniUGV in a hidden space (SE2, unknown occupied, tether-aware)");
      add_common(ugv, ga->common, "miniugv");
      ugv->add_option("--from", ga->from, "start x,y,yaw (m, rad)")->required();
      ugv->add_option("--to", ga->to, "goal x,y,yaw (m, rad)")->required();
      ugv->add_option("--entry", ga->entry, "tether entry point x,y (default: the hidden space's)");
      add_tether_budget_option(ugv, ga->tether_budget_m,
                               "the mission's L - l_0, 15 - 1 m built in");
      ugv->add_option(
          "--driven", ga->driven,
          "path driven since the entry, \"x,y;x,y;...\" (gives the tether's wraps; default: "
          "none, the tether straight from the entry)");
      ugv->add_option("--hidden-space", ga->hidden_space,
                      "hidden space of a world YAML (default: the one holding --from)");
      add_bounds_option(
          ugv, ga->bounds,
          "the hidden space's box, x and y the plan bounds, z0 the floor (default: the hidden "
          "space's; needed for .bt/.ot worlds)");
      ugv->add_option("--floor-z", ga->floor_z_m,
                      "floor height, m (top of the floor voxels; default: the space's)");
      ugv->add_flag("--return", ga->return_path,
                    "return along the tether (retrace its wrap points)");
      ugv->callback([ga] { run_ugv(*ga); });
    }};

}  // namespace
}  // namespace ferret::cli
