// World YAML -> OctoMap build, 2D slice, and .bt load, on the shipped worlds.
//   build/<preset>/bench/ferret_bench_world

#include <benchmark/benchmark.h>

#include <filesystem>

#include "ferret/mapping/world_octree.hpp"

namespace {

const std::string kWorlds = std::string(FERRET_SOURCE_DIR) + "/examples/worlds/";

void BM_BuildWorld(benchmark::State& state, const std::string& file) {
  const ferret::WorldSpec world = ferret::load_world(kWorlds + file);
  std::size_t leaves = 0;
  for (auto _ : state) {
    const auto tree = ferret::build_world_octree(world);
    leaves = tree->getNumLeafNodes();
    benchmark::DoNotOptimize(leaves);
  }
  state.counters["leaves"] = static_cast<double>(leaves);
}
BENCHMARK_CAPTURE(BM_BuildWorld, small, std::string("small.yaml"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_BuildWorld, default, std::string("default.yaml"))
    ->Unit(benchmark::kMillisecond);

void BM_SliceDefault(benchmark::State& state) {
  const auto tree = ferret::build_world_octree(ferret::load_world(kWorlds + "default.yaml"));
  ferret::SliceOptions options;
  options.z_m = 0.03;
  for (auto _ : state) benchmark::DoNotOptimize(ferret::slice_octree(*tree, options).cells.data());
}
BENCHMARK(BM_SliceDefault)->Unit(benchmark::kMillisecond);

void BM_LoadDefaultBt(benchmark::State& state) {
  const auto path = std::filesystem::temp_directory_path() / "ferret_bench_world_default.bt";
  ferret::save_octree(*ferret::build_world_octree(ferret::load_world(kWorlds + "default.yaml")),
                      path);
  for (auto _ : state) benchmark::DoNotOptimize(ferret::load_octree(path)->size());
  std::filesystem::remove(path);
}
BENCHMARK(BM_LoadDefaultBt)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
