// The CPU of one goal decision of the object search, grid planner against the OMPL
// frontier sampler, on the same states. The states are snapshots (every 1 s) of cdos
// searches with the grid planner on the maps of
// examples/scenarios/ompl_frontier_experiment.yaml, one object a zone: G, O, the pose
// and the velocity, with the frontiers and the path-distance field computed as the
// explore controller computes them before it asks the policy (both planners need the
// field: F_g is the reachable frontier). A decision is what each planner adds on top:
//   grid  cdos chooses (curiosity loss or the rapid rule) and G's shortest path to the goal
//   ompl  cdos+ompl weighs the candidates and PRM (frontier sampler, goal region) plans
// Every decision starts afresh (no committed goal). For scale, `field` is what both pay
// before they decide (the field and the frontier sets).
//
//   build/<dir>/bench/ferret_bench_frontier_planner
//
// Prints Google Benchmark's table (the mean over all states, 15 repetitions) and then
// the median and 90th percentile of the CPU time of single decisions of each planner.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "ferret/mapping/frontier.hpp"
#include "ferret/mission/experiment.hpp"
#include "ferret/mission/exploration_run.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/planning/grid_path_planner.hpp"
#include "ferret/sim/sim_ugv_base.hpp"
#include "ferret/ugv/explore_controller.hpp"

namespace ferret {
namespace {

struct Snapshot {
  IrGrid grid;
  ObjectMap objects;
  FrontierTracker tracker;
  GridPathPlanner paths;
  FrontierSets sets;
  Pose2 pose;
  Eigen::Vector2d v_W;
  UgvSensorGeometry sensors;
  double escape_m;

  Snapshot(const IrGrid& g, const ObjectMap& o, const Pose2& p, const Eigen::Vector2d& v,
           const UgvSensorGeometry& s, double escape_m)
      : grid(g),
        objects(o),
        tracker(g.geometry()),
        paths(g.geometry()),
        pose(p),
        v_W(v),
        sensors(s),
        escape_m(escape_m) {
    tracker.update(grid);
    paths.compute(grid, grid.geometry().cell_at(p.x_m, p.y_m),
                  GridPathPlanner::Traversal::kKnownFree, escape_m);
    sets = tracker.extract(paths.distances_m(), pose, s.ir_fov_rad, s.ir_range_m);
  }
  [[nodiscard]] ExplorationState state() const {
    return {grid,
            objects,
            tracker,
            sets,
            paths,
            pose,
            v_W,
            sensors.ir_fov_rad,
            sensors.ir_range_m,
            std::nullopt};
  }
};

struct States {
  std::vector<std::unique_ptr<Snapshot>>
      all;  // mutable: the field benchmark recomputes the same field
  PolicyOptions options;
};

const States& states() {
  static const States s = [] {
    States out;
    const auto config = load_experiment_config(std::string(FERRET_SOURCE_DIR) +
                                               "/examples/scenarios/ompl_frontier_experiment.yaml");
    const ExplorationSettings& settings = config.base;
    for (const ExperimentMap& m : config.maps)
      for (const ZoneSpec& zone : m.zones) {
        const auto objects = sample_zone_objects(m.map, zone, 1, config.object_clearance_m, 1);
        if (objects.empty()) continue;
        HiddenSpaceSim sim(m.map, objects.front(), settings.sensors, 1);
        SimUgvOptions base_options;
        base_options.robot = settings.robot;
        base_options.battery_endurance_s = 1e9;
        SimUgvBase base(sim, m.start, base_options);
        const ExploreOptions eo = explore_options(settings, 1, objects.front());
        out.options =
            PolicyOptions::from(eo.mission, eo.sensors.camera_range_m, eo.robot.max_velocity_mps);
        ExploreController controller(m.map.geometry, m.start, eo);
        const double escape_m = std::max(eo.robot.escape_radius_m,
                                         eo.robot.clearance_m + 2 * m.map.geometry.resolution_m);
        Pose2 last = m.start;
        for (long step = 0; step * controller.tick_s() < 60.0; ++step) {
          const Pose2 pose = base.odometry();
          controller.observe_scan(base.ir_scan());
          if (controller.frame_due(step) &&
              controller.observe_frame(base.camera_frame(step * controller.tick_s())))
            break;
          if (step > 0 && step % 20 == 0)
            out.all.push_back(std::make_unique<Snapshot>(
                controller.grid(), controller.objects(), pose,
                (pose.position() - last.position()) / controller.tick_s(), eo.sensors, escape_m));
          last = pose;
          const auto command = controller.decide(step, pose);
          if (command.explored) break;
          base.command_velocity(command.velocity.v_mps, command.velocity.w_radps);
          base.step(controller.tick_s());
        }
      }
    return out;
  }();
  return s;
}

// One decision on state `k`: the policy's goal and the path to it.
std::size_t decide(ExplorationPolicy& policy, const Snapshot& snapshot) {
  policy.goal_done();  // afresh
  const auto goal = policy.choose(snapshot.state());
  if (!goal) return 0;
  const auto path = goal->path_W.empty() ? snapshot.paths.path_to(goal->cell) : goal->path_W;
  benchmark::DoNotOptimize(path.data());
  return path.size();
}

void decision(benchmark::State& state, const char* planner) {
  const States& s = states();
  auto policy = make_exploration_policy(
      exploration_policy_for("cdos", parse_frontier_planner(planner, "planner")), s.options);
  std::size_t k = 0;
  for (auto _ : state) decide(*policy, *s.all[k++ % s.all.size()]);
  state.counters["states"] = static_cast<double>(s.all.size());
}

// What both planners pay before they decide (for scale): the path-distance field and
// the frontier sets.
void field(benchmark::State& state) {
  const States& s = states();
  std::size_t k = 0;
  for (auto _ : state) {
    Snapshot& snapshot = *s.all[k++ % s.all.size()];
    snapshot.paths.compute(snapshot.grid,
                           snapshot.grid.geometry().cell_at(snapshot.pose.x_m, snapshot.pose.y_m),
                           GridPathPlanner::Traversal::kKnownFree, snapshot.escape_m);
    benchmark::DoNotOptimize(snapshot.tracker.extract(snapshot.paths.distances_m(), snapshot.pose,
                                                      snapshot.sensors.ir_fov_rad,
                                                      snapshot.sensors.ir_range_m));
  }
}

BENCHMARK(field)->Unit(benchmark::kMicrosecond)->Repetitions(15);
BENCHMARK_CAPTURE(decision, grid, "grid")->Unit(benchmark::kMicrosecond)->Repetitions(15);
BENCHMARK_CAPTURE(decision, ompl, "ompl")->Unit(benchmark::kMicrosecond)->Repetitions(15);

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// The CPU time of each single decision (every state, 5 times), median and p90.
void print_single_decisions(const char* planner) {
  const States& s = states();
  auto policy = make_exploration_policy(
      exploration_policy_for("cdos", parse_frontier_planner(planner, "planner")), s.options);
  std::vector<double> us;
  for (int rep = 0; rep < 5; ++rep)
    for (const auto& snapshot : s.all) {
      const double t0 = thread_cpu_s();
      decide(*policy, *snapshot);
      us.push_back(1e6 * (thread_cpu_s() - t0));
    }
  std::sort(us.begin(), us.end());
  std::printf("%s: decision CPU median %.0f us, p90 %.0f us (%zu states x 5)\n", planner,
              us[us.size() / 2], us[us.size() * 9 / 10], s.all.size());
}

}  // namespace
}  // namespace ferret

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  ferret::print_single_decisions("grid");
  ferret::print_single_decisions("ompl");
  benchmark::Shutdown();
  return 0;
}
