// Winch controller cost per control cycle: the taut-tether MPC (condensed QP solved by
// DenseQpSolver) at horizons 20 and 40, and the feed-forward + PID baseline. Each
// benchmark replays the observations of a closed-loop run of the shipped
// fast back-and-forth trajectory, so the QP sees realistic active sets.
//   build/<dir>/bench/ferret_bench_mpc --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include "ferret/sim/tether_sim.hpp"
#include "ferret/tether_model/feedforward_pid.hpp"
#include "ferret/tether_model/taut_mpc.hpp"

namespace {

using namespace ferret;

// Records what a controller saw during a closed-loop run, to replay it.
class Recorder final : public tether::TetherController {
 public:
  explicit Recorder(std::unique_ptr<tether::TetherController> inner) : inner_(std::move(inner)) {}
  std::string_view name() const override { return inner_->name(); }
  void reset() override { inner_->reset(); }
  double step(const tether::TetherObservation& obs) override {
    seen.push_back(obs);
    return inner_->step(obs);
  }
  std::vector<tether::TetherObservation> seen;

 private:
  std::unique_ptr<tether::TetherController> inner_;
};

struct Replay {
  std::shared_ptr<tether::FixedWrapTether> model;
  std::vector<tether::TetherObservation> observations;
};

const Replay& replay() {
  static const Replay r = [] {
    const auto scn = sim::load_tether_scenario(std::string(FERRET_SOURCE_DIR) +
                                               "/examples/trajectories/fast_back_and_forth.csv");
    const auto options = sim::TetherSimOptions::for_tether(15.0, 1.0);
    Replay out;
    out.model = std::make_shared<tether::FixedWrapTether>(1.0, scn.p_WE, scn.wrap_points);
    tether::TautTetherMpc::Options mpc;
    mpc.control = options.control;
    Recorder rec(std::make_unique<tether::TautTetherMpc>(mpc, out.model));
    (void)sim::run_tether_sim(scn, options, rec);
    out.observations = std::move(rec.seen);
    return out;
  }();
  return r;
}

void BM_TautTetherMpc(benchmark::State& state) {
  const Replay& r = replay();
  tether::TautTetherMpc::Options o;
  o.horizon = static_cast<int>(state.range(0));
  tether::TautTetherMpc mpc(o, r.model);
  std::size_t i = 0;
  long active = 0, iterations = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(mpc.step(r.observations[i]));
    active += mpc.last_solution().active_constraints;
    iterations += mpc.last_solution().iterations;
    if (++i == r.observations.size()) i = 0;
  }
  state.counters["active_mean"] =
      benchmark::Counter(static_cast<double>(active), benchmark::Counter::kAvgIterations);
  state.counters["qp_iterations_mean"] =
      benchmark::Counter(static_cast<double>(iterations), benchmark::Counter::kAvgIterations);
  state.counters["variables"] = o.horizon + 3;
  state.counters["constraint_rows"] = 6 * o.horizon + 3;
}
BENCHMARK(BM_TautTetherMpc)->Arg(20)->Arg(40)->Unit(benchmark::kMicrosecond);

// The median and the worst cycle over one pass of the recorded run (the mean above
// hides the tail that matters for a 50 Hz loop).
void BM_TautTetherMpcMedian(benchmark::State& state) {
  const Replay& r = replay();
  tether::TautTetherMpc::Options o;
  o.horizon = static_cast<int>(state.range(0));
  std::vector<double> times_us;
  for (auto _ : state) {
    tether::TautTetherMpc mpc(o, r.model);
    times_us.clear();
    for (const auto& obs : r.observations) {
      const auto t0 = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(mpc.step(obs));
      times_us.push_back(
          std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count());
    }
  }
  std::sort(times_us.begin(), times_us.end());
  state.counters["median_us"] = times_us[times_us.size() / 2];
  state.counters["p99_us"] = times_us[times_us.size() * 99 / 100];
  state.counters["max_us"] = times_us.back();
  state.counters["cycles"] = static_cast<double>(times_us.size());
}
BENCHMARK(BM_TautTetherMpcMedian)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_FeedForwardPid(benchmark::State& state) {
  const Replay& r = replay();
  tether::FeedForwardPid pid(tether::FeedForwardPid::Options{}, r.model);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(pid.step(r.observations[i]));
    if (++i == r.observations.size()) i = 0;
  }
}
BENCHMARK(BM_FeedForwardPid)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
