#include "ferret/core/grid_morphology.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

namespace ferret {
namespace {

constexpr int kW = 20, kH = 12;

std::vector<std::uint8_t> empty_mask() { return std::vector<std::uint8_t>(kW * kH, 0); }
void set(std::vector<std::uint8_t>& m, int i0, int j0, int i1, int j1) {  // inclusive box
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) m[static_cast<std::size_t>(j) * kW + i] = 1;
}

TEST(GridMorphology, OpeningKeepsBlocksTheSquareFitsAndDropsSpecksAndThinStrips) {
  auto m = empty_mask();
  set(m, 2, 2, 7, 7);    // 6 x 6: a 5 x 5 square fits everywhere in it
  set(m, 10, 5, 10, 5);  // a speck
  set(m, 12, 0, 19, 1);  // a strip two cells high, along the border
  set(m, 12, 4, 13, 11); // a strip two cells wide
  const auto o = open_square(m, kW, kH, 2);
  auto expected = empty_mask();
  set(expected, 2, 2, 7, 7);
  EXPECT_EQ(o, expected);
}

TEST(GridMorphology, TheBorderDoesNotShaveARegionOffAndRadiusZeroChangesNothing) {
  auto m = empty_mask();
  set(m, 0, 0, 1, 1);    // 2 x 2 in the corner: with the outside, a 3 x 3 square fits
  set(m, 9, 9, 11, 10);  // 3 x 2 inside the grid: a 3 x 3 square does not
  auto expected = empty_mask();
  set(expected, 0, 0, 1, 1);
  EXPECT_EQ(open_square(m, kW, kH, 1), expected);
  EXPECT_EQ(open_square(m, kW, kH, 0), m);
}

}  // namespace
}  // namespace ferret
