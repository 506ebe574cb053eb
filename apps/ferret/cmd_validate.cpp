// `ferret validate`: checks a plan (plan JSON, a JSON of states or a CSV of
// t,x,y,z,yaw written by another tool) against a world; the checks are
// validate_plan_file() (docs/validate.md). Exit 0 valid, 1 invalid, 2 bad input.

#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/planning/plan_validation.hpp"
#include "ferret/planning/planning_world.hpp"

namespace ferret::cli {
namespace {

struct ValidateArgs {
  std::string world, plan, robot, mission, entry, unknown, bounds;
  std::optional<double> tether_budget_m, floor_z_m;
  bool json = false, all = false;
};

void run(const ValidateArgs& a) {
  ValidateRequest request;
  if (a.robot == "builtin")
    request.builtin_shapes = true;
  else if (!a.robot.empty())
    request.robot_urdf = resolve_robot(a.robot, "miniugv.urdf");
  if (!a.mission.empty()) request.mission = a.mission;
  request.bounds = parse_bounds(a.bounds);
  request.tether_budget_m = checked_tether_budget(a.tether_budget_m);
  if (!a.entry.empty()) {
    const auto e = parse_number_list(a.entry, 2, "--entry");
    request.p_WE = Eigen::Vector2d(e[0], e[1]);
  }
  if (!a.unknown.empty()) request.unknown = parse_unknown_policy(a.unknown, "--unknown");
  request.floor_z_m = a.floor_z_m;
  const ValidationReport report = validate_plan_file(a.plan, a.world, request);

  if (a.json) {
    std::cout << validation_report_to_json(report);
  } else if (report.valid()) {
    std::cout << fmt::format(
        "valid: {} states of a {} plan checked against {} (unknown space {})\n",
        report.inputs.states, to_string(report.inputs.robot), a.world,
        to_string(report.inputs.unknown));
  } else {
    const std::size_t shown = a.all ? report.violations.size() : 1;
    for (std::size_t k = 0; k < shown; ++k)
      std::cout << "invalid: " << report.violations[k].describe() << "\n";
    if (shown < report.violations.size())
      std::cout << fmt::format("({} more violations: --all lists them)\n",
                               report.violations.size() - shown);
  }
  if (!report.valid()) set_exit_code(1);
}

const CommandRegistration kValidate{
    "validate", [](CLI::App& app) {
      auto args = std::make_shared<ValidateArgs>();
      auto* cmd = app.add_subcommand(
          "validate",
          "Check a plan (plan JSON, JSON of states, or CSV t,x,y,z,yaw) against a world");
      add_world_option(cmd, args->world, true,
                       "world YAML, map_server YAML (a 2D hidden space), .bt or .ot");
      cmd->add_option("--plan", args->plan,
                      "plan: ferret plan JSON, a JSON {\"states\": [...]}, or a CSV with a "
                      "header naming t,x,y,z,yaw (docs/planning.md)")
          ->required();
      add_robot_option(
          cmd, args->robot,
          "the plan's robot_model, else \"builtin\" shapes; required for CSV and states-only JSON");
      add_mission_option(cmd, args->mission);
      add_tether_budget_option(cmd, args->tether_budget_m,
                               "the plan's tether section, else the mission's L - l_0");
      cmd->add_option("--entry", args->entry,
                      "tether entry x,y (metres) for plans without a tether section "
                      "(default: the hidden space's entry)");
      cmd->add_option("--unknown", args->unknown,
                      "unknown space: free or occupied (default: the plan's, else "
                      "occupied for the miniUGV, free for the UAV)");
      add_bounds_option(cmd, args->bounds,
                        "geofence, and where unknown space is occupied (default: the plan's, else "
                        "the hidden space, "
                        "else the world's bounds / the map's extent)");
      cmd->add_option(
          "--floor-z", args->floor_z_m,
          "floor height (m) for the tether's obstacles (default: the one found in the map)");
      cmd->add_flag("--json", args->json,
                    "the report as JSON on stdout (docs/validate.md; lists every violation)");
      cmd->add_flag("--all", args->all, "print every violation (default: the first)");
      cmd->callback([args] { run(*args); });
    }};

}  // namespace
}  // namespace ferret::cli
