#include "ferret/planning/plan_benchmark.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <ompl/base/Planner.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/tools/benchmark/Benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "ferret/core/error.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/planning/benchmark_problems.hpp"
#include "ferret/planning/ompl_setup.hpp"
#include "ferret/planning/tethered_rrt.hpp"
#include "ferret/planning/uav_planner.hpp"
#include "ferret/planning/ugv_planner.hpp"

namespace ferret {
namespace {
namespace fs = std::filesystem;
namespace ob = ompl::base;
namespace og = ompl::geometric;

constexpr const char* kSource = "PlanBenchmarkRequest";

// Writes the log into the output set as `file`; the result names its final path.
PlanBenchmarkLog run_benchmark(og::SimpleSetup& setup, const std::vector<ob::PlannerPtr>& planners,
                               const PlanBenchmarkRequest& r, const std::string& name,
                               OutputSet& out, const std::string& file) {
  const fs::path log = out.target() / file;
  ompl::tools::Benchmark benchmark(setup, name);
  for (const auto& p : planners) benchmark.addPlanner(p);
  // saveConsoleOutput off: OMPL would write an "ompl_<host>_<date>.console" file into
  // the current directory on every run.
  ompl::tools::Benchmark::Request request(r.time_limit_s, 4096.0, static_cast<unsigned>(r.runs),
                                          0.05,
                                          /*displayProgress=*/true, /*saveConsoleOutput=*/false,
                                          /*simplify=*/true);
  benchmark.benchmark(request);
  out.write(file, [&](const fs::path& staged) {
    if (!benchmark.saveResultsToFile(staged.c_str()))
      throw InputError(log.string(), "", "a writable log file");
  });
  return {name, log, planners.size()};
}

void check(const PlanningWorld& world, const PlanBenchmarkRequest& r) {
  if (r.runs < 1 || r.runs > 10000)
    throw InputError(kSource, "runs", "1 to 10000", std::to_string(r.runs));
  if (r.problems < 1 || r.problems > 1000)
    throw InputError(kSource, "problems", "1 to 1000", std::to_string(r.problems));
  if (!(std::isfinite(r.time_limit_s) && r.time_limit_s > 0 && r.time_limit_s <= 600))
    throw InputError(kSource, "time_limit_s", "seconds in (0, 600]",
                     fmt::format("{}", r.time_limit_s));
  if (!r.uav && !r.ugv) throw InputError(kSource, "robots", "uav, ugv or both");
  if (r.planners.empty()) throw InputError(kSource, "planners", "at least one OMPL planner name");
  const auto& known = ompl_planner_names();
  for (const auto& n : r.planners)
    if (std::find(known.begin(), known.end(), n) == known.end())
      throw InputError(kSource, "planners", fmt::format("names from: {}", fmt::join(known, ", ")),
                       n);
  if (r.tether_budget_m && !(std::isfinite(*r.tether_budget_m) && *r.tether_budget_m > 0.0 &&
                             *r.tether_budget_m <= 1000.0))
    throw InputError(kSource, "tether_budget_m", "a taut tether length in (0, 1000] m",
                     fmt::format("{}", *r.tether_budget_m));
  if (!world.spec || world.spec->hidden_spaces.empty())
    throw InputError(world.source.string(), "hidden_spaces",
                     "a world YAML with at least one hidden space (the problems come from it)");
}

}  // namespace

std::vector<PlanBenchmarkLog> run_plan_benchmarks(const PlanningWorld& world,
                                                  const PlanBenchmarkRequest& r,
                                                  const fs::path& out_dir) {
  check(world, r);
  // Every log of the request, or none: staged while the benchmarks run, moved in at the end.
  OutputSet out(out_dir, OutputKind::kDirectory);
  seed_ompl_once(r.seed);
  const WorldSpec& w = *world.spec;
  std::vector<PlanBenchmarkLog> logs;
  if (r.uav) {
    const LoadedPlanRobot robot =
        load_plan_robot(PlanRobot::kUav, r.uav_robot, r.mission, 0.0, kSource, "uav_robot");
    UavPlannerOptions opt;
    // The default geofence, half a metre in from the world's sides too: the random
    // starts are drawn inside it.
    opt.geofence = default_uav_bounds(world);
    opt.geofence.lo.head<2>() += Eigen::Vector2d::Constant(0.5);
    opt.geofence.hi.head<2>() -= Eigen::Vector2d::Constant(0.5);
    const auto map = CollisionMap::build(*world.tree, uav_map_options(world.spec));
    UavPlanner planner(map, robot.shape, opt);
    const auto problems =
        uav_approach_problems(w, planner.checker(), opt.geofence, r.problems, r.seed);
    for (std::size_t k = 0; k < problems.size(); ++k) {
      auto si = planner.space_information();
      og::SimpleSetup setup(si);
      ob::ScopedState<> s(si->getStateSpace()), g(si->getStateSpace());
      planner.to_ompl_state(problems[k].start, s.get());
      planner.to_ompl_state(problems[k].goal, g.get());
      setup.setStartAndGoalStates(s, g);
      std::vector<ob::PlannerPtr> planners;
      for (const auto& n : r.planners) planners.push_back(make_ompl_planner(n, si, kSource));
      logs.push_back(run_benchmark(setup, planners, r,
                                   fmt::format("ferret uav approach {} ({})", k, w.name), out,
                                   fmt::format("uav_{}.log", k)));
    }
  }
  if (r.ugv) {
    const LoadedPlanRobot robot =
        load_plan_robot(PlanRobot::kUgv, r.ugv_robot, r.mission, 0.0, kSource, "ugv_robot");
    const double budget_m = r.tether_budget_m.value_or(r.mission.tether.total_length_m -
                                                       r.mission.tether.entry_offset_m);
    const HiddenSpaceFrame frame = hidden_space_frame(w.hidden_spaces.front());
    const auto map = ugv_collision_map(*world.tree, frame, robot.ugv);
    UgvPlannerOptions opt;
    opt.shape = robot.shape;
    UgvPlanner planner(map, frame, robot.ugv, opt);
    const auto problems = ugv_problems(planner, r.problems, r.seed);
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
          std::make_shared<TetheredRRT>(si, planner.tether_at_start(req), budget_m, r.seed)};
      for (const auto& n : r.planners) planners.push_back(make_ompl_planner(n, si, kSource));
      logs.push_back(run_benchmark(
          setup, planners, r, fmt::format("ferret ugv {} ({})", k, w.hidden_spaces.front().name),
          out, fmt::format("ugv_{}.log", k)));
    }
  }
  out.commit();
  return logs;
}

}  // namespace ferret
