#pragma once
// OMPL's Benchmark over the planning problems of a world (benchmark_problems.hpp):
// UAV approaches to the hover poses of its hidden spaces, and miniUGV start/goal
// pairs in its first hidden space, one OMPL log per problem (`ferret bench-plan`;
// ompl_benchmark_statistics turns the logs into a Planner Arena database). No OMPL
// types here.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "ferret/planning/mission_config.hpp"
#include "ferret/planning/planning_world.hpp"

namespace ferret {

struct PlanBenchmarkRequest {
  bool uav = true;  ///< run the UAV approach problems
  bool ugv = true;  ///< run the miniUGV problems (TetheredRRT beside the named planners)
  std::vector<std::string> planners{"rrtconnect", "rrt", "prm", "kpiece", "est"};
  int problems = 1;           ///< per robot, [1, 1000]
  int runs = 20;              ///< per planner and problem, [1, 10000]
  double time_limit_s = 1.0;  ///< per run, (0, 600]
  std::uint64_t seed = 1;     ///< the problems' and OMPL's
  /// The miniUGV's taut tether budget L - l_0; nullopt: the mission's.
  std::optional<double> tether_budget_m;
  /// The robots' shapes: ferret's built-in ones by default (what the published figures
  /// were measured with); a URDF for either.
  PlanRobotModel uav_robot{{}, true};
  PlanRobotModel ugv_robot{{}, true};
  MissionConfig mission;
};

struct PlanBenchmarkLog {
  std::string experiment;      ///< "ferret uav approach 0 (world)"
  std::filesystem::path path;  ///< <out_dir>/<robot>_<k>.log
  std::size_t planners = 0;
};

/// Runs the benchmarks of `request` in `world` and writes one log per problem into
/// `out_dir` (created; all the logs appear together at the end, or none). Throws InputError (source
/// "PlanBenchmarkRequest") for counts or limits out of range, an unknown planner (the
/// message lists them), no robot, or a world without hidden spaces.
std::vector<PlanBenchmarkLog> run_plan_benchmarks(const PlanningWorld& world,
                                                  const PlanBenchmarkRequest& request,
                                                  const std::filesystem::path& out_dir);

}  // namespace ferret
