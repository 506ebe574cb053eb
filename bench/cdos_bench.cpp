// One decision cycle of the object search at 0.05 m on the 12 x 8 m sparse hidden
// space: fold one IR scan into G and one camera frame into O, update the frontiers,
// compute the path-distance field, extract F_g and F_v, score and choose. `cdos`
// (with object evidence in O, so the curiosity loss is computed) against `rapid`.
//
//   build/<dir>/bench/ferret_bench_cdos
//
// Then the same cycle on generated sparse hidden spaces of 12 x 8, 24 x 16 and 48 x 32 m
// (ferret world generate-hidden --seed 1 --size W,H), the robot 1.2 m into the space
// and an object seen in zone 2: how the cycle's cost grows with the space.
//
// Prints Google Benchmark's table (15 repetitions, mean/median/stddev) and then the
// median time of each method, the ratio cdos / rapid, and each size's over 12 x 8's.

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>

#include "ferret/mapping/frontier.hpp"
#include "ferret/mapping/ir_grid.hpp"
#include "ferret/mapping/object_map.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/planning/grid_path_planner.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/sim/hidden_space_generator.hpp"
#include "ferret/sim/hidden_space_sim.hpp"

namespace ferret {
namespace {

// The robot mid-search: it has driven from the start (1, 4) to (2.2, 4) and turned a
// little towards an object in zone 2 that its camera has seen from afar.
struct Scene {
  OccupancyMap2D truth;
  Eigen::Vector2d start, object;
  SensorOptions sensors;
  HiddenSpaceSim sim{truth, object, sensors, 1};
  IrGrid grid{truth.geometry, {}};
  ObjectMap objects{truth.geometry,
                    ObjectMap::Options::from(ObjectSearchParams{}, sensors.camera_range_m)};
  FrontierTracker tracker{truth.geometry};
  GridPathPlanner planner{truth.geometry};
  Pose2 pose{start.x() + 1.2, start.y(), 0.3};
  RangeScan scan;
  CameraFrame frame;

  // The shipped sparse space, start (1, 4), the object at (3.6, 5.4).
  Scene()
      : Scene(load_map_server(std::string(FERRET_SOURCE_DIR) + "/examples/maps/sparse.yaml"),
              {1.0, 4.0}, {3.6, 5.4}) {}
  Scene(OccupancyMap2D map, Eigen::Vector2d start_W, Eigen::Vector2d object_W)
      : truth(std::move(map)), start(start_W), object(object_W) {
    grid.mark_free_disk(start, 0.2);
    for (int k = 0; k <= 12; ++k) {
      const Pose2 p{start.x() + 0.1 * k, start.y(), 0.025 * k};
      grid.integrate_scan(sim.ir_scan(p));
      objects.integrate_frame(sim.camera_frame(p, 0.1 * k));
    }
    tracker.update(grid);
    scan = sim.ir_scan(pose);
    frame = sim.camera_frame(pose, 2.0);
  }
};

void run_cycles(benchmark::State& state, const char* method, Scene& scene) {
  const PolicyOptions options =
      PolicyOptions::from(MissionConfig{}, scene.sensors.camera_range_m, 2.0);
  auto policy = make_exploration_policy(method, options);
  std::size_t evidence = 0, visible = 0;
  double t = 2.0;
  const Cell robot = scene.truth.geometry.cell_at(scene.pose.x_m, scene.pose.y_m);
  // The path field and the frontier sets of the maps as they stand.
  const auto refresh = [&] {
    scene.planner.compute(scene.grid, robot, GridPathPlanner::Traversal::kKnownFree, 1.0);
    return scene.tracker.extract(scene.planner.distances_m(), scene.pose, scene.sensors.ir_fov_rad,
                                 scene.sensors.ir_range_m);
  };
  const auto state_of = [&](const FrontierSets& sets) {
    return ExplorationState{scene.grid,
                            scene.objects,
                            scene.tracker,
                            sets,
                            scene.planner,
                            scene.pose,
                            Eigen::Vector2d(1.0, 0.3),  // its velocity
                            scene.sensors.ir_fov_rad,
                            scene.sensors.ir_range_m,
                            std::nullopt};
  };
  FrontierSets sets = refresh();
  for (auto _ : state) {
    // A fresh choice every cycle, as a policy chooses when its goal was reached. A
    // policy lives for the whole search: untimed, a new one chooses on the maps of the
    // last cycle (allocating what it keeps, bayes's per-cell arrays and the views it
    // keeps while their cells do not change) and gives that goal up.
    state.PauseTiming();
    policy = make_exploration_policy(method, options);
    benchmark::DoNotOptimize(policy->choose(state_of(sets)));
    policy->goal_done();
    state.ResumeTiming();
    scene.frame.time_s = (t += 1.0);  // a new frame each cycle: O fuses it
    scene.grid.integrate_scan(scene.scan);
    scene.objects.integrate_frame(scene.frame);
    scene.tracker.update(scene.grid);
    sets = refresh();
    auto goal = policy->choose(state_of(sets));
    benchmark::DoNotOptimize(goal);
    evidence = scene.objects.evidence_cells().size();
    visible = sets.visible.size();
  }
  state.counters["evidence_cells"] = static_cast<double>(evidence);
  state.counters["F_v"] = static_cast<double>(visible);
}

void decision_cycle(benchmark::State& state, const char* method) {
  Scene scene;
  run_cycles(state, method, scene);
}

// A generated sparse space of the benchmark's size (its args: width, height in m), the
// object in the middle of zone `zone` (2: seen from the start, evidence; 5: not seen).
void cycle_in_generated_space(benchmark::State& state, const char* method, int zone) {
  HiddenSpaceGeneratorOptions o;
  o.width_m = static_cast<double>(state.range(0));
  o.height_m = static_cast<double>(state.range(1));
  GeneratedHiddenSpace h = generate_hidden_space(o);
  const ZoneSpec& z = h.zones[static_cast<std::size_t>(zone - 1)];
  Scene scene(std::move(h.map), {h.start.x_m, h.start.y_m},
              {0.5 * (z.xmin_m + z.xmax_m), 0.5 * (z.ymin_m + z.ymax_m)});
  run_cycles(state, method, scene);
  state.counters["cells"] = static_cast<double>(scene.truth.geometry.size());
}
void decision_cycle_size(benchmark::State& state, const char* method) {
  cycle_in_generated_space(state, method, 2);
}
// bayes's own cycle: no evidence, a fresh viewpoint choice every cycle (its worst case:
// it keeps a goal between choices).
void decision_cycle_unseen(benchmark::State& state, const char* method) {
  cycle_in_generated_space(state, method, 5);
}

BENCHMARK_CAPTURE(decision_cycle, cdos, "cdos")->Unit(benchmark::kMicrosecond)->Repetitions(15);
BENCHMARK_CAPTURE(decision_cycle, rapid, "rapid")->Unit(benchmark::kMicrosecond)->Repetitions(15);
// decision_cycle_{size,unseen}/METHOD/W/H, registered in main() for each method.
void register_sizes() {
  for (const char* method : {"cdos", "rapid", "bayes"})
    for (const auto& [name, fn] : {std::pair<const char*, void (*)(benchmark::State&, const char*)>{
                                       "decision_cycle_size/", decision_cycle_size},
                                   std::pair<const char*, void (*)(benchmark::State&, const char*)>{
                                       "decision_cycle_unseen/", decision_cycle_unseen}})
      benchmark::RegisterBenchmark((std::string(name) + method).c_str(), fn, method)
          ->Args({12, 8})
          ->Args({24, 16})
          ->Args({48, 32})
          ->Unit(benchmark::kMicrosecond)
          ->Repetitions(15);
}

// Keeps the medians to print their ratio after the table.
class MedianReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& r : runs)
      if (r.aggregate_name == "median") medians[r.run_name.str()] = r.GetAdjustedRealTime();
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, double> medians;
};

}  // namespace
}  // namespace ferret

int main(int argc, char** argv) {
  ferret::register_sizes();
  benchmark::Initialize(&argc, argv);
  ferret::MedianReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto& m = reporter.medians;
  const auto cdos = m.find("decision_cycle/cdos/repeats:15"),
             rapid = m.find("decision_cycle/rapid/repeats:15");
  if (cdos != m.end() && rapid != m.end())
    std::printf("median decision cycle: cdos %.1f us, rapid %.1f us, ratio cdos/rapid %.2f\n",
                cdos->second, rapid->second, cdos->second / rapid->second);
  for (const char* kind : {"size", "unseen"})
    for (const char* method : {"cdos", "rapid", "bayes"}) {
      const std::string prefix = std::string("decision_cycle_") + kind + "/" + method + "/";
      const auto base = m.find(prefix + "12/8/repeats:15");
      if (base == m.end()) continue;
      for (const char* size : {"12/8", "24/16", "48/32"}) {
        const auto at = m.find(prefix + size + "/repeats:15");
        if (at != m.end())
          std::printf(
              "generated sparse %s m, object %s, %s: median %.1f us, %.2fx the 12 x 8 m space's\n",
              size, std::string(kind) == "size" ? "seen" : "unseen", method, at->second,
              at->second / base->second);
      }
    }
  benchmark::Shutdown();
  return 0;
}
