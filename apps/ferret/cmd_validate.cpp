// `ferret validate`: checks a plan (plan JSON, or a CSV of t,x,y,z,yaw written by
// another tool) against a world: collisions at the exact checker's resolution (FCL,
// unknown space by the policy), geofence, speed and yaw-rate limits, and for miniUGV
// plans the taut tether. Exit 0 valid, 1 invalid (the first violation is printed),
// 2 bad input.

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/planning/plan_validation.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::cli {
namespace {

struct ValidateArgs {
  std::string world, plan, robot, config, entry, unknown, bounds;
  std::optional<double> tether_max_m, floor_z_m;
};

void run(const ValidateArgs& a) {
  PlanFile plan = load_plan(a.plan);
  const MissionConfig config = a.config.empty() ? MissionConfig{} : load_mission_config(a.config);
  // The robot's shapes: --robot, else the URDF the plan was made with, else built-in.
  std::optional<RobotDescription> urdf;
  if (!a.robot.empty() && a.robot != "builtin") urdf = load_robot_description(a.robot, config);
  else if (a.robot.empty() && !plan.robot_model.empty()) {
    // A model path written relative to another directory: the shipped model of that name.
    std::filesystem::path model = plan.robot_model;
    if (!std::filesystem::exists(model)) model = find_model(model.filename().string());
    urdf = load_robot_description(model, config);
  }
  if (!plan.robot_known) {
    if (!urdf) throw InputError("--robot", "", "a URDF for a CSV plan (it does not say which robot it is)");
    plan.robot = urdf->kind == RobotKind::kUgv ? PlanRobot::kUgv : PlanRobot::kUav;
  } else if (urdf && (urdf->kind == RobotKind::kUgv) != (plan.robot == PlanRobot::kUgv)) {
    throw InputError("--robot", "", fmt::format("a URDF of the plan's robot ({})", to_string(plan.robot)), a.robot);
  }
  if (a.tether_max_m && !(*a.tether_max_m > 0.0))
    throw InputError("--tether-max", "", "a taut-length budget > 0 m", std::to_string(*a.tether_max_m));
  const PlanningWorld world = load_planning_world(a.world);

  // The map with its unknown-space policy: the command line, else the plan, else the
  // robot's default (occupied inside the hidden space for the miniUGV, free for the UAV).
  std::optional<Aabb3> bounds = plan.bounds;
  if (!a.bounds.empty()) {
    const auto b = parse_number_list(a.bounds, 6, "--bounds");
    bounds = Aabb3{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
    if ((bounds->lo.array() > bounds->hi.array()).any())
      throw InputError("--bounds", "", "x0,y0,z0,x1,y1,z1 with min <= max", a.bounds);
  }
  std::optional<Eigen::Vector2d> entry;
  if (!a.entry.empty()) {
    const auto e = parse_number_list(a.entry, 2, "--entry");
    entry = Eigen::Vector2d(e[0], e[1]);
  }
  HiddenSpaceFrame space;
  if (plan.robot == PlanRobot::kUgv && !bounds && world.spec) {
    const int index = hidden_space_at(*world.spec, {plan.states.front().x_m, plan.states.front().y_m});
    if (index >= 0) {
      space = hidden_space_frame(world.spec->hidden_spaces[static_cast<std::size_t>(index)]);
      bounds = ugv_policy_bounds(space);
      if (!entry && !plan.tether) entry = space.p_WE;
    }
  }
  UnknownPolicy unknown = plan.unknown_policy.value_or(plan.robot == PlanRobot::kUgv ? UnknownPolicy::kOccupied
                                                                                     : UnknownPolicy::kFree);
  if (!a.unknown.empty()) unknown = parse_unknown_policy(a.unknown, "--unknown");
  if (unknown == UnknownPolicy::kOccupied && !bounds)
    throw InputError("--bounds", "", "x0,y0,z0,x1,y1,z1: where unknown space counts as occupied");
  CollisionMapOptions map_opt;
  map_opt.unknown = unknown;
  map_opt.bounds = bounds;
  const auto map = CollisionMap::build(*world.tree, map_opt);

  std::optional<RobotShape> urdf_shape;
  if (urdf) urdf_shape = robot_shape_from_description(*urdf);
  CollisionChecker checker(map, plan_robot_shape(plan.robot, plan.released_length_m,
                                                 urdf_shape ? &*urdf_shape : nullptr));
  ValidationOptions opt;
  opt.resolution = default_resolution(plan.robot);
  opt.geofence = bounds;
  const MotionLimits& limits = urdf ? urdf->limits : (plan.robot == PlanRobot::kUgv ? config.ugv_limits : config.uav_limits);
  opt.max_velocity_mps = plan.max_velocity_mps.value_or(limits.max_velocity_mps);
  opt.max_yaw_rate_radps = plan.max_yaw_rate_radps.value_or(limits.max_yaw_rate_radps);
  if ((!a.robot.empty() && a.robot != "builtin") || !a.config.empty()) {  // given limits win over the plan's
    opt.max_velocity_mps = limits.max_velocity_mps;
    opt.max_yaw_rate_radps = limits.max_yaw_rate_radps;
  }
  opt.tether_max_m = a.tether_max_m;
  opt.p_WE = entry;
  if (plan.robot == PlanRobot::kUgv && !plan.tether && !opt.tether_max_m)
    opt.tether_max_m = config.tether.total_length_m - config.tether.entry_offset_m;
  if (plan.robot == PlanRobot::kUgv && !plan.tether && !entry)
    throw InputError("--entry", "", "the tether's entry point x,y (the plan has no tether section)");
  std::shared_ptr<const TetherCorners> corners;
  if (plan.robot == PlanRobot::kUgv) {
    if (!bounds) throw InputError("--bounds", "", "the hidden space's bounds for the tether's obstacles");
    HiddenSpaceFrame f;
    f.lo_m = bounds->lo.head<2>();
    f.hi_m = bounds->hi.head<2>();
    f.floor_z_m = a.floor_z_m.value_or(bounds->lo.z());
    corners = tether_corners_from_map(*map, f, UgvGeometry{});
  }
  const auto violation = validate_plan(plan, checker, corners, opt);
  if (!violation) {
    std::cout << fmt::format("valid: {} states of a {} plan checked against {} (unknown space {})\n",
                             plan.states.size(), to_string(plan.robot), a.world, to_string(unknown));
    return;
  }
  const Violation& v = *violation;
  std::cout << fmt::format("invalid: state {} at t = {:.3f} s, position ({:.3f}, {:.3f}, {:.3f}): {}\n", v.index,
                           v.t_s, v.p_W.x(), v.p_W.y(), v.p_W.z(), v.reason);
  set_exit_code(1);
}

const CommandRegistration kValidate{"validate", [](CLI::App& app) {
  auto args = std::make_shared<ValidateArgs>();
  auto* cmd = app.add_subcommand("validate", "Check a plan (JSON or CSV t,x,y,z,yaw) against a world");
  cmd->add_option("--world", args->world, "world YAML, .bt or .ot")->required();
  cmd->add_option("--plan", args->plan, "plan JSON or CSV")->required();
  cmd->add_option("--robot", args->robot,
                  "robot URDF (required for CSV plans; default: the plan's robot_model, else \"builtin\" shapes)");
  cmd->add_option("--config", args->config, "mission YAML (motion limits, tether L and l_0)");
  cmd->add_option("--tether-max", args->tether_max_m, "taut tether budget L - l_0, m (default: the plan's)");
  cmd->add_option("--entry", args->entry, "tether entry x,y for plans without a tether section");
  cmd->add_option("--unknown", args->unknown, "unknown space: free or occupied (default: the plan's)");
  cmd->add_option("--bounds", args->bounds, "x0,y0,z0,x1,y1,z1: geofence / hidden space (default: the plan's)");
  cmd->add_option("--floor-z", args->floor_z_m, "floor height for the tether's obstacles (default: bounds' z0)");
  cmd->callback([args] { run(*args); });
}};

}  // namespace
}  // namespace ferret::cli
