// `ferret bench-plan`: OMPL's Benchmark over the UAV approach and miniUGV problems
// of a world, writing OMPL benchmark logs (one per problem). ompl_benchmark_statistics
// (Debian's ompl-demos) turns them into a Planner Arena database (docs/planning.md).
// The benchmarks are the library's (plan_benchmark.hpp); this file maps options.

#include <fmt/format.h>

#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/planning/ompl_setup.hpp"
#include "ferret/planning/plan_benchmark.hpp"
#include "ferret/planning/planning_world.hpp"

namespace ferret::cli {
namespace {

struct Args {
  std::string world, out, robots = "uav,ugv", planners = "rrtconnect,rrt,prm,kpiece,est",
                          robot = "builtin", mission;
  int problems = 1;
  int runs = 20;
  double time_limit_s = 1.0;
  std::uint64_t seed = 1;
  std::optional<double> tether_budget_m;
};

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

void run(const Args& a) {
  (void)checked_out_dir(a.out, "the directory for the OMPL logs");
  PlanBenchmarkRequest req;
  req.uav = req.ugv = false;
  for (const auto& r : split(a.robots)) {
    check_choice("--robots", r, {"uav", "ugv"});
    (r == "uav" ? req.uav : req.ugv) = true;
  }
  if (!req.uav && !req.ugv) throw InputError("--robots", "", "uav, ugv or both", a.robots);
  req.planners = split(a.planners);
  for (const auto& n : req.planners) check_choice("--planners", n, ompl_planner_names());
  req.problems = a.problems;
  req.runs = a.runs;
  req.time_limit_s = a.time_limit_s;
  req.seed = a.seed;
  req.tether_budget_m = checked_tether_budget(a.tether_budget_m);
  req.mission = load_mission_or_defaults(a.mission);
  if (a.robot != "builtin") {
    // One URDF is one robot: it replaces the built-in shapes of its kind, so --robots
    // must name that kind alone (load_plan_robot rejects the other).
    if (req.uav && req.ugv)
      throw InputError("--robots", "", "uav or ugv alone with --robot (a URDF is one robot)",
                       a.robots);
    PlanRobotModel& model = req.uav ? req.uav_robot : req.ugv_robot;
    model = {resolve_robot(a.robot, req.uav ? "m100.urdf" : "miniugv.urdf"), false};
  }
  const PlanningWorld world = load_planning_world(a.world);
  std::vector<PlanBenchmarkLog> logs;
  try {
    logs = run_plan_benchmarks(world, req, a.out);
  } catch (const InputError& e) {
    // The request's fields as the options that set them, with the value typed.
    const std::map<std::string, std::pair<std::string, std::string>> options{
        {"runs", {"--runs", std::to_string(a.runs)}},
        {"problems", {"--problems", std::to_string(a.problems)}},
        {"time_limit_s", {"--time-limit", fmt::format("{}", a.time_limit_s)}},
        {"uav_robot", {"--robot", a.robot}},
        {"ugv_robot", {"--robot", a.robot}}};
    const auto it = options.find(e.field());
    if (e.source() != "PlanBenchmarkRequest" || it == options.end()) throw;
    throw InputError(it->second.first, "", e.expected(), it->second.second);
  }
  for (const auto& log : logs)
    std::cout << fmt::format("{}: {} planners x {} runs -> {}\n", log.experiment, log.planners,
                             a.runs, log.path.string());
}

const CommandRegistration kBenchPlan{
    "bench-plan", [](CLI::App& app) {
      auto a = std::make_shared<Args>();
      auto* cmd = app.add_subcommand(
          "bench-plan", "Run OMPL's Benchmark on the UAV and miniUGV problems of a world");
      add_world_option(cmd, a->world, true, "world YAML with hidden spaces");
      add_out_option(cmd, a->out, "directory for the OMPL logs (<robot>_<k>.log)");
      cmd->add_option("--robots", a->robots, "uav, ugv or both")->capture_default_str();
      cmd->add_option(
             "--planners", a->planners,
             "OMPL planners to compare, comma-separated, each " + one_of(ompl_planner_names()))
          ->capture_default_str();
      add_robot_option(
          cmd, a->robot,
          "builtin: ferret's simple shapes; a URDF replaces the shapes of its kind, with --robots "
          "naming that kind");
      add_mission_option(cmd, a->mission);
      cmd->add_option("--problems", a->problems, "problems per robot (one log each)")
          ->capture_default_str();
      cmd->add_option("--runs", a->runs, "runs per planner and problem")->capture_default_str();
      cmd->add_option("--time-limit", a->time_limit_s, "seconds per run")->capture_default_str();
      add_seed_option(cmd, a->seed, "seed of the problems and of OMPL");
      add_tether_budget_option(cmd, a->tether_budget_m, "the mission's L - l_0, 14 m built in");
      cmd->callback([a] { run(*a); });
    }};

}  // namespace
}  // namespace ferret::cli
