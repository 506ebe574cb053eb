#include "ferret/core/random.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ferret {
namespace {

TEST(Random, SameSeedSameSequence) {
  Rng a(42), b(42), c(43);
  for (int i = 0; i < 100; ++i) {
    const auto x = a.next_u64();
    EXPECT_EQ(x, b.next_u64());
    (void)c;
  }
  EXPECT_NE(Rng(42).next_u64(), Rng(43).next_u64());
}

TEST(Random, KnownFirstValuesArePlatformIndependent) {
  // Pinned values: a change here changes every simulated result in docs/results.md.
  Rng rng(1);
  EXPECT_EQ(rng.next_u64(), 0xb3f2af6d0fc710c5ULL);
  EXPECT_EQ(derive_seed(1, {2, 3}), derive_seed(1, {2, 3}));
  EXPECT_NE(derive_seed(1, {2, 3}), derive_seed(1, {3, 2}));
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
