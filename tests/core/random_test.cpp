#include "ferret/core/random.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ferret {
namespace {

TEST(Random, SameSeedSameSequence) {
  Rng a(42), b(42), c(43);
  int same_as_other_seed = 0;
  for (int i = 0; i < 100; ++i) {
    const auto x = a.next_u64();
    EXPECT_EQ(x, b.next_u64());
    same_as_other_seed += x == c.next_u64();
  }
  EXPECT_EQ(same_as_other_seed, 0);  // a neighbouring seed gives an unrelated sequence
}

TEST(Random, KnownFirstValuesArePlatformIndependent) {
  // Pinned values: a change here changes every simulated result in docs/results.md.
  Rng rng(1);
  EXPECT_EQ(rng.next_u64(), 0xb3f2af6d0fc710c5ULL);
  // derive_seed and stable_hash pinned to values computed independently (a Python
  // transcription of SplitMix64 mixing and FNV-1a, in the commit that pinned them).
  EXPECT_EQ(derive_seed(1, {}), 0x910a2dec89025cc1ULL);
  EXPECT_EQ(derive_seed(1, {2, 3}), 0x6bcdaec1fe6ef69aULL);
  EXPECT_EQ(derive_seed(1, {3, 2}), 0x0407a12cc91caab1ULL);  // order matters
  EXPECT_EQ(stable_hash("cdos"), 0xce6cde90f666f36cULL);
}

TEST(Random, UniformAndNormalMoments) {
  Rng rng(7);
  const int n = 200000;
  double sum = 0, sum2 = 0, nsum = 0, nsum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double u = rng.uniform01();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
    const double z = rng.normal(2.0, 3.0);
    nsum += z;
    nsum2 += z * z;
  }
  EXPECT_NEAR(sum / n, 0.5, 0.005);
  EXPECT_NEAR(sum2 / n - std::pow(sum / n, 2), 1.0 / 12.0, 0.002);
  EXPECT_NEAR(nsum / n, 2.0, 0.03);
  EXPECT_NEAR(std::sqrt(nsum2 / n - std::pow(nsum / n, 2)), 3.0, 0.03);
}

TEST(Random, UniformIntCoversInclusiveRange) {
  Rng rng(3);
  int counts[5] = {};
  for (int i = 0; i < 5000; ++i) {
    const auto v = rng.uniform_int(-2, 2);
    ASSERT_GE(v, -2);
    ASSERT_LE(v, 2);
    ++counts[v + 2];
  }
  for (int c : counts) EXPECT_GT(c, 800);
}

}  // namespace
}  // namespace ferret
