// Planning time percentiles of both planners, and a validation of every returned
// path with the exact checker (`ferret validate`'s checks; failures must be 0).
//
//   build/<dir>/bench/ferret_bench_planning [--benchmark_filter=uav|ugv]
//
// uav_approach: 100 approaches in examples/worlds/default.yaml from random free
//   poses in the geofence (60 x 60 m, 0.5-7.5 m up) to the hover poses in front of
//   the two hidden-space openings; RRTConnect, 1 s limit each.
// ugv_cellar: 100 random start/goal pairs (>= 3 m apart) in the 12 x 8 m cellar of
//   examples/scenarios/tether_detour.yaml, 14 m of tether budget; TetheredRRT, 1 s limit.
// ugv_detour: the scenario's infeasible-shortest-path problem, 20 seeds.
// Robots: the collision shapes of urdf/models/m100.urdf and miniugv.urdf.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <limits>
#include <vector>

#include "ferret/mapping/world_octree.hpp"
#include "ferret/planning/benchmark_problems.hpp"
#include "ferret/planning/ompl_setup.hpp"
#include "ferret/planning/plan_validation.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/planning/uav_planner.hpp"
#include "ferret/planning/ugv_planner.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

// The limits the planners time their paths with. They have no acceleration model (a
// drive starts and stops at full speed), so acceleration is not counted here:
// validation failures are geometry, speed, yaw rate and tether.
MotionLimits planner_limits(double max_velocity_mps, double max_yaw_rate_radps) {
  return {max_velocity_mps, std::numeric_limits<double>::infinity(), max_yaw_rate_radps};
}

// The shipped URDFs' collision shapes, as `ferret plan` uses them.
RobotShape urdf_shape(const char* model, PlanRobot robot) {
  const RobotShape s = robot_shape_from_description(load_robot_description(find_model(model)));
  return plan_robot_shape(robot, 0.0, &s);
}

void report(benchmark::State& state, std::vector<double> times_ms, int solved, int total,
            int invalid) {
  std::sort(times_ms.begin(), times_ms.end());
  auto pct = [&](double q) {
    return times_ms.empty() ? 0.0
                            : times_ms[static_cast<std::size_t>(q * (times_ms.size() - 1) + 0.5)];
  };
  state.counters["solved_pct"] = 100.0 * solved / total;
  state.counters["median_ms"] = pct(0.5);
  state.counters["p90_ms"] = pct(0.9);
  state.counters["max_ms"] = pct(1.0);
  state.counters["problems"] = total;
  state.counters["validation_failures"] = invalid;
}

void BM_UavApproach(benchmark::State& state) {
  seed_ompl_once(1);
  const PlanningWorld world =
      load_planning_world(std::string(FERRET_SOURCE_DIR) + "/examples/worlds/default.yaml");
  const auto map = CollisionMap::build(*world.tree, uav_map_options(world.spec));
  UavPlannerOptions opt;
  opt.geofence = {{-29.5, -29.5, 0.5}, {29.5, 29.5, 7.5}};
  const RobotShape shape = urdf_shape("m100.urdf", PlanRobot::kUav);
  UavPlanner planner(map, shape, opt);
  CollisionChecker exact(map, shape);
  const auto problems = uav_approach_problems(*world.spec, planner.checker(), opt.geofence, 100, 1);
  for (auto _ : state) {
    std::vector<double> times_ms;
    int solved = 0, invalid = 0;
    for (const auto& p : problems) {
      const UavPlan plan = planner.plan(p.start, p.goal);
      times_ms.push_back(plan.planning_time_s * 1e3);
      if (!plan.solved) continue;
      ++solved;
      PlanFile file;
      file.robot = PlanRobot::kUav;
      file.states = plan.states;
      ValidationOptions v(planner_limits(opt.max_velocity_mps, opt.max_yaw_rate_radps),
                          default_resolution(PlanRobot::kUav));
      v.geofence = opt.geofence;
      invalid += validate_plan(file, exact, nullptr, v).valid() ? 0 : 1;
    }
    report(state, times_ms, solved, static_cast<int>(problems.size()), invalid);
  }
}

struct Cellar {
  PlanningWorld world;
  HiddenSpaceFrame frame;
  std::shared_ptr<const CollisionMap> map;
  Cellar()
      : world(load_planning_world(std::string(FERRET_SOURCE_DIR) +
                                  "/examples/scenarios/tether_detour.yaml")) {
    frame = hidden_space_frame(world.spec->hidden_spaces.at(0));
    map = ugv_collision_map(*world.tree, frame);
  }
};

int validate_ugv(const UgvPlan& plan, const Cellar& c, UgvPlanner& planner,
                 const TetherParams& tether) {
  PlanFile file;
  file.robot = PlanRobot::kUgv;
  file.states = plan.states;
  file.tether =
      PlanTether{c.frame.p_WE, plan.initial_wraps, tether.total_length_m, tether.entry_offset_m};
  const UgvPlannerOptions timing;
  ValidationOptions v(planner_limits(timing.max_velocity_mps, timing.max_yaw_rate_radps),
                      default_resolution(PlanRobot::kUgv));
  v.geofence = ugv_policy_bounds(c.frame);
  CollisionChecker exact(c.map, *planner.options().shape);
  return validate_plan(file, exact, planner.corners(), v).valid() ? 0 : 1;
}

void BM_UgvCellar(benchmark::State& state) {
  const Cellar c;
  UgvPlannerOptions opt;
  opt.shape = urdf_shape("miniugv.urdf", PlanRobot::kUgv);
  UgvPlanner planner(c.map, c.frame, {}, opt);
  const auto problems = ugv_problems(planner, 100, 1);
  const TetherParams tether{15.0, 1.0};
  for (auto _ : state) {
    std::vector<double> times_ms;
    int solved = 0, invalid = 0;
    for (const auto& p : problems) {
      UgvPlanRequest req;
      req.start = {p.start.x_m, p.start.y_m, p.start.yaw_rad};
      req.goal = {p.goal.x_m, p.goal.y_m, p.goal.yaw_rad};
      req.tether = tether;
      const UgvPlan plan = planner.plan(req);
      times_ms.push_back(plan.planning_time_s * 1e3);
      if (!plan.solved) continue;
      ++solved;
      invalid += validate_ugv(plan, c, planner, tether);
    }
    report(state, times_ms, solved, static_cast<int>(problems.size()), invalid);
  }
}

void BM_UgvDetour(benchmark::State& state) {
  const Cellar c;
  const TetherParams tether{13.5, 1.0};
  for (auto _ : state) {
    std::vector<double> times_ms;
    int solved = 0, invalid = 0;
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
      UgvPlannerOptions opt;
      opt.seed = seed;
      opt.shape = urdf_shape("miniugv.urdf", PlanRobot::kUgv);
      UgvPlanner planner(c.map, c.frame, {}, opt);
      UgvPlanRequest req;
      req.driven = {{1.0, 6.5}, {10.0, 6.5}};
      req.start = {10.0, 4.5, -1.57};
      req.goal = {10.0, 1.5, -1.57};
      req.tether = tether;
      const UgvPlan plan = planner.plan(req);
      times_ms.push_back(plan.planning_time_s * 1e3);
      if (!plan.solved) continue;
      ++solved;
      invalid += validate_ugv(plan, c, planner, tether);
    }
    report(state, times_ms, solved, 20, invalid);
  }
}

BENCHMARK(BM_UavApproach)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(BM_UgvCellar)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK(BM_UgvDetour)->Iterations(1)->Unit(benchmark::kSecond);

}  // namespace
}  // namespace ferret

BENCHMARK_MAIN();
