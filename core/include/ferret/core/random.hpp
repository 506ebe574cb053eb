#pragma once
// Seeded randomness that gives the same numbers on every machine. The standard
// library's distributions are implementation-defined (libstdc++ and libc++ differ),
// so ferret draws from its own: SplitMix64-seeded xoshiro256** bits, uniform
// doubles from the top 53 bits, normals by Box-Muller.

#include <array>
#include <cstdint>
#include <initializer_list>

namespace ferret {

/// Mixes a seed with further integers (map id, zone, object index, ...) into a new
/// seed, so that runs can be addressed independently and still be reproducible.
[[nodiscard]] std::uint64_t derive_seed(std::uint64_t seed,
                                        std::initializer_list<std::uint64_t> parts);

/// Stable 64-bit hash of a string (FNV-1a), for deriving seeds from names.
[[nodiscard]] std::uint64_t stable_hash(const char* text);

class Rng {
 public:
  explicit Rng(std::uint64_t seed);

  /// 64 random bits.
  [[nodiscard]] std::uint64_t next_u64();
  /// Uniform in [0, 1).
  [[nodiscard]] double uniform01();
  /// Uniform in [lo, hi).
  [[nodiscard]] double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  /// Uniform integer in [lo, hi] (inclusive). @pre lo <= hi.
  [[nodiscard]] std::int64_t uniform_int(std::int64_t lo, std::int64_t hi);
  /// Normal with mean `mean` and standard deviation `stddev`.
  [[nodiscard]] double normal(double mean, double stddev);
  /// True with probability p.
  [[nodiscard]] bool bernoulli(double p) { return uniform01() < p; }

 private:
  std::array<std::uint64_t, 4> s_{};
  bool has_spare_normal_ = false;
  double spare_normal_ = 0.0;
};

}  // namespace ferret
