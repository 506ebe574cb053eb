// The robot link's corruption campaign at 10^6 frames (docs/link.md, "Corruption"):
// random valid messages of every type, each frame damaged once by bit flips,
// truncation, extension or an overwritten field (sometimes two of these), never
// resealed with a fresh CRC; counts how many decode() accepts, which must be none.
// ctest runs the same campaign at 10^5 (LinkCodecCorruption.*). Also the cost of
// encoding and decoding a full telemetry frame.
//   build/release/bench/ferret_bench_link_corruption --benchmark_counters_tabular=true

#include <benchmark/benchmark.h>

#include "ferret/link/codec.hpp"
#include "link/random_messages.hpp"

namespace {

using namespace ferret;
using namespace ferret::link;

void BM_CorruptionCampaign(benchmark::State& state) {
  const auto trials = static_cast<std::uint64_t>(state.range(0));
  testing::CorruptionCampaign c;
  for (auto _ : state) c = testing::run_corruption_campaign(trials, 2024);
  state.counters["trials"] = static_cast<double>(c.trials);
  state.counters["accepted"] = static_cast<double>(c.accepted);
  for (std::size_t k = 0; k < kCorruptionKinds; ++k)
    state.counters[std::string(to_string(static_cast<Corruption>(k)))] =
        static_cast<double>(c.by_kind[k]);
  for (std::size_t r = 0; r < Rejection::kReasonCount; ++r)
    if (c.by_reason[r] > 0)
      state.counters[std::string(to_string(static_cast<Rejection::Reason>(r)))] =
          static_cast<double>(c.by_reason[r]);
  if (c.accepted > 0) state.SkipWithError("a damaged frame was accepted");
}
BENCHMARK(BM_CorruptionCampaign)->Arg(1'000'000)->Iterations(1)->Unit(benchmark::kMillisecond);

UgvTelemetry full_telemetry() {
  Rng rng(1);
  UgvTelemetry t = testing::random_telemetry(rng);
  t.plan.clear();
  for (std::size_t i = 0; i < UgvTelemetry::kMaxPlanSamples; ++i)
    t.plan.push_back({0.05f * static_cast<float>(i + 1), 1.0f, 2.0f, 0.5f, 0.5f});
  return t;
}

void BM_EncodeFullTelemetry(benchmark::State& state) {
  const Message m = full_telemetry();
  std::uint32_t sequence = 0;
  for (auto _ : state) benchmark::DoNotOptimize(encode(++sequence, m));
}
BENCHMARK(BM_EncodeFullTelemetry)->Unit(benchmark::kMicrosecond);

void BM_DecodeFullTelemetry(benchmark::State& state) {
  const auto bytes = encode(1, full_telemetry());
  for (auto _ : state) benchmark::DoNotOptimize(decode(bytes));
}
BENCHMARK(BM_DecodeFullTelemetry)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
