#pragma once
// Valid link messages drawn at random (every type, plan previews of every length,
// reasons of every length), and the corruption campaign that damages their frames and
// counts what decode() accepts. Shared by the ctest suite (10^5 corruptions) and
// bench/link_corruption_bench.cpp (10^6, the figure in docs/link.md).

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ferret/core/random.hpp"
#include "ferret/link/codec.hpp"
#include "ferret/link/lossy_channel.hpp"
#include "ferret/link/messages.hpp"

namespace ferret::link::testing {

inline float random_float(Rng& rng, double lo, double hi) {
  return static_cast<float>(rng.uniform(lo, hi));
}

inline UgvTelemetry random_telemetry(Rng& rng) {
  UgvTelemetry t;
  t.t_s = rng.uniform(0, 3600);
  t.x_m = rng.uniform(-30, 30);
  t.y_m = rng.uniform(-30, 30);
  t.yaw_rad = rng.uniform(-3.14, 3.14);
  t.vx_mps = random_float(rng, -2, 2);
  t.vy_mps = random_float(rng, -2, 2);
  t.ax_mps2 = random_float(rng, -5, 5);
  t.ay_mps2 = random_float(rng, -5, 5);
  t.mode = static_cast<UgvMode>(rng.uniform_int(0, 7));
  t.outcome = static_cast<UgvOutcome>(rng.uniform_int(0, 10));
  t.battery_fraction = random_float(rng, 0, 1);
  t.epm_on = rng.bernoulli(0.5);
  t.object_held = rng.bernoulli(0.5);
  t.wants_retraction = rng.bernoulli(0.5);
  t.tether_anchor_x_m = rng.uniform(-30, 30);
  t.tether_anchor_y_m = rng.uniform(-30, 30);
  t.tether_to_anchor_m = rng.uniform(0, 15);
  t.tether_uncertainty_m = random_float(rng, 0, 2);
  t.roll_rad = random_float(rng, -0.5, 0.5);
  t.pitch_rad = random_float(rng, -0.5, 0.5);
  t.last_request_id = static_cast<std::uint32_t>(rng.uniform_int(0, 0xFFFFFFFF));
  const auto n = rng.uniform_int(0, UgvTelemetry::kMaxPlanSamples);
  for (std::int64_t i = 0; i < n; ++i)
    t.plan.push_back({0.05f * static_cast<float>(i + 1), random_float(rng, -30, 30),
                      random_float(rng, -30, 30), random_float(rng, -2, 2),
                      random_float(rng, -2, 2)});
  return t;
}

inline UavRequest random_request(Rng& rng) {
  UavRequest r;
  r.request_id = static_cast<std::uint32_t>(rng.uniform_int(1, 1'000'000));
  r.kind = static_cast<UavRequest::Kind>(rng.uniform_int(1, 5));
  r.entry_x_m = rng.uniform(-500, 500);
  r.entry_y_m = rng.uniform(-500, 500);
  r.entry_z_m = rng.uniform(-10, 10);
  r.entry_yaw_rad = rng.uniform(-3.14, 3.14);
  const auto n = rng.uniform_int(0, UavRequest::kMaxReasonBytes);
  for (std::int64_t i = 0; i < n; ++i)
    r.reason.push_back(static_cast<char>(rng.uniform_int('a', 'z')));
  return r;
}

inline Message random_message(Rng& rng) {
  switch (rng.uniform_int(0, 3)) {
    case 0:
      return random_telemetry(rng);
    case 1:
      return random_request(rng);
    case 2:
      return Ack{static_cast<std::uint32_t>(rng.uniform_int(1, 1'000'000))};
    default:
      return Heartbeat{rng.uniform(0, 3600), rng.uniform(0, 3600)};
  }
}

struct CorruptionCampaign {
  std::uint64_t trials = 0;
  std::uint64_t accepted = 0;  ///< damaged frames decode() took for a message: must stay 0
  std::array<std::uint64_t, kCorruptionKinds> by_kind{};
  std::array<std::uint64_t, Rejection::kReasonCount> by_reason{};
};

/// Encodes `trials` random valid messages, damages each frame once (corrupt(): bit
/// flips, truncation, extension, overwritten fields, sometimes two of them; never
/// resealed with a fresh CRC) and decodes it.
inline CorruptionCampaign run_corruption_campaign(std::uint64_t trials, std::uint64_t seed) {
  CorruptionCampaign c;
  Rng rng(seed);
  for (std::uint64_t i = 0; i < trials; ++i) {
    auto bytes = encode(static_cast<std::uint32_t>(rng.next_u64()), random_message(rng));
    const Corruption kind = corrupt(bytes, rng);
    ++c.trials;
    ++c.by_kind[static_cast<std::size_t>(kind)];
    const DecodeResult r = decode(bytes);
    if (r.ok())
      ++c.accepted;
    else
      ++c.by_reason[static_cast<std::size_t>(r.rejection().reason)];
  }
  return c;
}

}  // namespace ferret::link::testing
