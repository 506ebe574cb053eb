// `ferret bench-plan`: OMPL's Benchmark over the UAV approach and miniUGV problems
// of a world, writing OMPL benchmark logs (one per problem). ompl_benchmark_statistics
// (Debian's ompl-demos) turns them into a Planner Arena database (docs/planning.md).

#include <fmt/format.h>
#include <ompl/base/Planner.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/tools/benchmark/Benchmark.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "command.hpp"
#include "ferret/core/atomic_file.hpp"
#include "ferret/core/error.hpp"
#include "ferret/planning/benchmark_problems.hpp"
#include "ferret/planning/ompl_setup.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/planning/tethered_rrt.hpp"
#include "ferret/planning/uav_planner.hpp"
#include "ferret/planning/ugv_planner.hpp"

namespace ferret::cli {
namespace {
namespace fs = std::filesystem;
namespace ob = ompl::base;
namespace og = ompl::geometric;

struct Args {
  std::string world, output_dir, robots = "uav,ugv", planners = "rrtconnect,rrt,prm,kpiece,est";
  int problems = 1;
  int runs = 20;
  double time_limit_s = 1.0;
  std::uint64_t seed = 1;
  double tether_max_m = 14.0;
};

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

void run_benchmark(og::SimpleSetup& setup, const std::vector<ob::PlannerPtr>& planners, const Args& a,
                   const std::string& name, const fs::path& log) {
  ompl::tools::Benchmark benchmark(setup, name);
  for (const auto& p : planners) benchmark.addPlanner(p);
  // saveConsoleOutput off: OMPL would write an "ompl_<host>_<date>.console" file into
  // the current directory on every run.
  ompl::tools::Benchmark::Request request(a.time_limit_s, 4096.0, static_cast<unsigned>(a.runs),
                                          0.05,
                                          /*displayProgress=*/true, /*saveConsoleOutput=*/false,
                                          /*simplify=*/true);
  benchmark.benchmark(request);
  write_file_atomically(log, [&](const fs::path& tmp) {
    if (!benchmark.saveResultsToFile(tmp.c_str())) throw InputError(log.string(), "", "a writable log file");
  });
  std::cout << fmt::format("{}: {} planners x {} runs -> {}\n", name, planners.size(), a.runs, log.string());
}

void run(const Args& a) {
  if (a.runs < 1 || a.runs > 10000) throw InputError("--runs", "", "1 to 10000", std::to_string(a.runs));
  if (a.problems < 1 || a.problems > 1000) throw InputError("--problems", "", "1 to 1000", std::to_string(a.problems));
  if (!(a.time_limit_s > 0 && a.time_limit_s <= 600))
    throw InputError("--time-limit", "", "seconds in (0, 600]", std::to_string(a.time_limit_s));
  const auto robots = split(a.robots);
  for (const auto& r : robots)
    if (r != "uav" && r != "ugv") throw InputError("--robots", "", "a list of uav and ugv", a.robots);
  const auto planner_names = split(a.planners);
  if (planner_names.empty()) throw InputError("--planners", "", "at least one OMPL planner name", a.planners);
  const auto& known = ompl_planner_names();
  for (const auto& n : planner_names)
    if (std::find(known.begin(), known.end(), n) == known.end())
      throw InputError("--planners", "", "names from: " + fmt::format("{}", fmt::join(known, ", ")), n);
  seed_ompl_once(a.seed);
  const PlanningWorld world = load_planning_world(a.world);
  if (!world.spec || world.spec->hidden_spaces.empty())
    throw InputError(a.world, "hidden_spaces", "a world YAML with at least one hidden space (the problems come from it)");
  const fs::path dir(a.output_dir);

  if (std::find(robots.begin(), robots.end(), "uav") != robots.end()) {
    const auto map = CollisionMap::build(*world.tree, uav_map_options(world.spec));
    UavPlannerOptions opt;
    const WorldSpec& w = *world.spec;
    opt.geofence = {{w.bounds_min_m.x() + 0.5, w.bounds_min_m.y() + 0.5, std::max(w.bounds_min_m.z(), 0.0) + 0.5},
                    {w.bounds_max_m.x() - 0.5, w.bounds_max_m.y() - 0.5, w.bounds_max_m.z() - 0.5}};
    UavPlanner planner(map, uav_shape(), opt);
    const auto problems = uav_approach_problems(w, planner.checker(), opt.geofence, a.problems, a.seed);
    for (std::size_t k = 0; k < problems.size(); ++k) {
      auto si = planner.space_information();
      og::SimpleSetup setup(si);
      ob::ScopedState<> s(si->getStateSpace()), g(si->getStateSpace());
      planner.to_ompl_state(problems[k].start, s.get());
      planner.to_ompl_state(problems[k].goal, g.get());
      setup.setStartAndGoalStates(s, g);
      std::vector<ob::PlannerPtr> planners;
      for (const auto& n : planner_names) planners.push_back(make_ompl_planner(n, si, "--planners"));
      run_benchmark(setup, planners, a, fmt::format("ferret uav approach {} ({})", k, w.name),
                    dir / fmt::format("uav_{}.log", k));
    }
  }
  if (std::find(robots.begin(), robots.end(), "ugv") != robots.end()) {
    const HiddenSpaceFrame frame = hidden_space_frame(world.spec->hidden_spaces.front());
    const auto map = ugv_collision_map(*world.tree, frame);
    UgvPlanner planner(map, frame);
    const auto problems = ugv_problems(planner, a.problems, a.seed);
    for (std::size_t k = 0; k < problems.size(); ++k) {
      auto si = planner.space_information();
      og::SimpleSetup setup(si);
      ob::ScopedState<> s(si->getStateSpace()), g(si->getStateSpace());
      s[0] = problems[k].start.x_m;
      s[1] = problems[k].start.y_m;
      s[2] = problems[k].start.yaw_rad;
      g[0] = problems[k].goal.x_m;
      g[1] = problems[k].goal.y_m;
      g[2] = problems[k].goal.yaw_rad;
      setup.setStartAndGoalStates(s, g);
      UgvPlanRequest req;
      req.start = {problems[k].start.x_m, problems[k].start.y_m, problems[k].start.yaw_rad};
      // The tether-aware planner, and the named OMPL planners, which ignore the tether
      // (their paths may need more tether than there is: compare path lengths).
      std::vector<ob::PlannerPtr> planners{
          std::make_shared<TetheredRRT>(si, planner.tether_at_start(req), a.tether_max_m, a.seed)};
      for (const auto& n : planner_names) planners.push_back(make_ompl_planner(n, si, "--planners"));
      run_benchmark(setup, planners, a, fmt::format("ferret ugv {} ({})", k, world.spec->hidden_spaces.front().name),
                    dir / fmt::format("ugv_{}.log", k));
    }
  }
}

const CommandRegistration kBenchPlan{"bench-plan", [](CLI::App& app) {
  auto a = std::make_shared<Args>();
  auto* cmd = app.add_subcommand("bench-plan", "Run OMPL's Benchmark on the UAV and miniUGV problems of a world");
  cmd->add_option("--world", a->world, "world YAML with hidden spaces")->required();
  cmd->add_option("-o,--output-dir", a->output_dir, "directory for the OMPL logs (<robot>_<k>.log)")->required();
  cmd->add_option("--robots", a->robots, "uav, ugv or both")->capture_default_str();
  cmd->add_option("--planners", a->planners, "OMPL planners to compare")->capture_default_str();
  cmd->add_option("--problems", a->problems, "problems per robot (one log each)")->capture_default_str();
  cmd->add_option("--runs", a->runs, "runs per planner and problem")->capture_default_str();
  cmd->add_option("--time-limit", a->time_limit_s, "seconds per run")->capture_default_str();
  cmd->add_option("--seed", a->seed, "seed of the problems and of OMPL")->capture_default_str();
  cmd->add_option("--tether", a->tether_max_m, "miniUGV taut tether budget L - l_0, m")->capture_default_str();
  cmd->callback([a] { run(*a); });
}};

}  // namespace
}  // namespace ferret::cli
