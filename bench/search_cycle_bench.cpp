// The decision cycle as the miniUGV meets it: whole simulated searches on generated
// sparse hidden spaces of 12 x 8, 24 x 16 and 48 x 32 m (seeds 1-3, one object in each
// of zones 2-5, the paper's sensors), every step that runs a decision cycle timed: the
// IR scan and camera frame folded into G and O, the frontiers, the path field and the
// policy's choice (ExplorationSettings::time_decision_cycles). ferret_bench_cdos times
// one cycle of a fixed scene; this is the distribution over the cycles of real
// searches, where `bayes` chooses a viewpoint afresh only when its goal is reached or
// has lost its mass, and CDOS only when its goal is no longer a frontier.
//
//   build/<dir>/bench/ferret_bench_search_cycle
//
// One iteration a benchmark (12 searches); counters: cycles timed, the median, 90th
// and 99th percentiles and the longest cycle in us, and the searches that found the
// object. After the table, each method's median at each size over its 12 x 8 m median.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "ferret/core/random.hpp"
#include "ferret/mission/experiment.hpp"
#include "ferret/mission/exploration_run.hpp"
#include "ferret/sim/hidden_space_generator.hpp"

namespace ferret {
namespace {

double percentile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1) + 0.5);
  return sorted[std::min(k, sorted.size() - 1)];
}

void searches(benchmark::State& state, const char* method) {
  std::vector<double> cycles_s;
  int found = 0, runs = 0;
  for (auto _ : state) {
    cycles_s.clear();
    found = runs = 0;
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      HiddenSpaceGeneratorOptions o;
      o.seed = seed;
      o.width_m = static_cast<double>(state.range(0));
      o.height_m = static_cast<double>(state.range(1));
      const GeneratedHiddenSpace h = generate_hidden_space(o);
      for (int zone = 2; zone <= 5; ++zone) {
        const auto objects =
            sample_zone_objects(h.map, h.zones[static_cast<std::size_t>(zone - 1)], 1, 0.25,
                                derive_seed(seed, {static_cast<std::uint64_t>(zone)}));
        if (objects.empty()) continue;
        ExplorationSettings settings;
        settings.method = method;
        settings.time_decision_cycles = true;
        const EpisodeResult r = run_exploration(h.map, h.start, objects.front(), settings, seed);
        cycles_s.insert(cycles_s.end(), r.decision_cycle_s.begin(), r.decision_cycle_s.end());
        found += r.found ? 1 : 0;
        ++runs;
        if (!r.found)
          std::fprintf(stderr,
                       "%s, %g x %g m, seed %llu, zone %d, object (%.3f, %.3f): %s after %.1f s\n",
                       method, o.width_m, o.height_m, static_cast<unsigned long long>(seed), zone,
                       objects.front().x(), objects.front().y(), r.end_reason.c_str(), r.time_s);
      }
    }
  }
  std::sort(cycles_s.begin(), cycles_s.end());
  state.counters["cycles"] = static_cast<double>(cycles_s.size());
  state.counters["median_us"] = 1e6 * percentile(cycles_s, 0.5);
  state.counters["p90_us"] = 1e6 * percentile(cycles_s, 0.9);
  state.counters["p99_us"] = 1e6 * percentile(cycles_s, 0.99);
  state.counters["max_us"] = 1e6 * (cycles_s.empty() ? 0.0 : cycles_s.back());
  state.counters["found"] = found;
  state.counters["runs"] = runs;
}

void register_searches() {
  for (const char* method : {"cdos", "rapid", "bayes"})
    benchmark::RegisterBenchmark((std::string("searches/") + method).c_str(), searches, method)
        ->Args({12, 8})
        ->Args({24, 16})
        ->Args({48, 32})
        ->Iterations(1)
        ->Unit(benchmark::kSecond);
}

// Keeps each run's median cycle to print the size ratios after the table.
class MedianReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const auto& r : runs) {
      const auto it = r.counters.find("median_us");
      if (it != r.counters.end()) medians[r.run_name.str()] = it->second.value;
    }
    ConsoleReporter::ReportRuns(runs);
  }
  std::map<std::string, double> medians;
};

}  // namespace
}  // namespace ferret

int main(int argc, char** argv) {
  ferret::register_searches();
  benchmark::Initialize(&argc, argv);
  ferret::MedianReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  for (const char* method : {"cdos", "rapid", "bayes"}) {
    const std::string prefix = std::string("searches/") + method + "/";
    const auto base = reporter.medians.find(prefix + "12/8/iterations:1");
    if (base == reporter.medians.end()) continue;
    for (const char* size : {"12/8", "24/16", "48/32"}) {
      const auto at = reporter.medians.find(prefix + size + "/iterations:1");
      if (at != reporter.medians.end())
        std::printf("%s, %s m: median decision cycle %.0f us, %.2fx the 12 x 8 m median\n", method,
                    size, at->second, at->second / base->second);
    }
  }
  benchmark::Shutdown();
  return 0;
}
