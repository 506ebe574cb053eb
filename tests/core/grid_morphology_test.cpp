#include "ferret/core/grid_morphology.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
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
  set(m, 2, 2, 7, 7);     // 6 x 6: a 5 x 5 square fits everywhere in it
  set(m, 10, 5, 10, 5);   // a speck
  set(m, 12, 0, 19, 1);   // a strip two cells high, along the border
  set(m, 12, 4, 13, 11);  // a strip two cells wide
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

// The opening by its definition, cell by cell: a cell stays when some r-square of
// in-grid cells (the outside counting as set) that holds it is all set.
std::vector<std::uint8_t> open_by_definition(const std::vector<std::uint8_t>& m, int w, int h,
                                             int r) {
  const auto set_at = [&](int i, int j) {
    return i < 0 || j < 0 || i >= w || j >= h || m[static_cast<std::size_t>(j) * w + i] != 0;
  };
  std::vector<std::uint8_t> out(m.size(), 0);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      if (!set_at(i, j)) continue;
      bool kept = false;
      for (int cj = j - r; cj <= j + r && !kept; ++cj)
        for (int ci = i - r; ci <= i + r && !kept; ++ci) {
          if (ci < 0 || cj < 0 || ci >= w || cj >= h) continue;  // squares centred in the grid
          bool full = true;
          for (int y = cj - r; y <= cj + r && full; ++y)
            for (int x = ci - r; x <= ci + r && full; ++x) full = set_at(x, y);
          kept = full;
        }
      out[static_cast<std::size_t>(j) * w + i] = kept;
    }
  return out;
}

TEST(GridMorphology, RandomMasksOpenAsTheDefinitionSays) {
  std::uint64_t state = 12345;
  const auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<std::uint32_t>(state >> 33);
  };
  for (const auto& [w, h] :
       {std::pair{17, 9}, std::pair{5, 23}, std::pair{1, 1}, std::pair{30, 30}}) {
    for (int trial = 0; trial < 6; ++trial) {
      std::vector<std::uint8_t> m(static_cast<std::size_t>(w) * h);
      const std::uint32_t density = 40 + 10 * static_cast<std::uint32_t>(trial);  // percent set
      for (auto& c : m) c = static_cast<std::uint8_t>(next() % 100 < density ? 1 + next() % 3 : 0);
      for (const int r : {0, 1, 2, 4, 40}) {
        if (r > 4 && w * h > 300) continue;  // the definition is slow; 40 > either side already
        EXPECT_EQ(open_square(m, w, h, r), open_by_definition(m, w, h, r))
            << w << "x" << h << " r " << r << " trial " << trial;
      }
    }
  }
}

// grow_within: the room within the radius of a seed, reached through room only.
TEST(GridMorphology, GrowingReachesRoomWithinTheRadiusOfItsSeedAndNoFurther) {
  auto seeds = empty_mask(), room = empty_mask();
  set(seeds, 5, 5, 5, 5);
  set(room, 0, 0, kW - 1, kH - 1);
  const auto g = grow_within(seeds, room, kW, kH, 2.0);
  const auto at = [&](int i, int j) { return g[static_cast<std::size_t>(j) * kW + i]; };
  EXPECT_EQ(at(5, 5), 0);  // the seed is not in it
  EXPECT_EQ(at(7, 5), 1);  // 2 cells
  EXPECT_EQ(at(5, 3), 1);
  EXPECT_EQ(at(6, 6), 1);  // sqrt 2
  EXPECT_EQ(at(8, 5), 0);  // 3 cells
  EXPECT_EQ(at(7, 6), 0);  // sqrt 5 > 2
  EXPECT_EQ(at(7, 7), 0);  // sqrt 8
  // By hand: the 13 cells of the disc of radius 2 round a cell, less the seed.
  int n = 0;
  for (const auto c : g) n += c;
  EXPECT_EQ(n, 12);
}

TEST(GridMorphology, GrowingDoesNotJumpAGapInTheRoom) {
  auto seeds = empty_mask(), room = empty_mask();
  set(seeds, 2, 0, 2, kH - 1);  // a face along a column
  set(room, 3, 0, 5, kH - 1);   // three columns of room behind it...
  set(room, 7, 0, 9, kH - 1);   // ...a column that is not, then room again
  const auto g = grow_within(seeds, room, kW, kH, 6.0);
  auto expected = empty_mask();
  set(expected, 3, 0, 5, kH - 1);
  EXPECT_EQ(g, expected);
  // Radius 0: nothing grows; no seeds: nothing either.
  EXPECT_EQ(grow_within(seeds, room, kW, kH, 0.0), empty_mask());
  EXPECT_EQ(grow_within(empty_mask(), room, kW, kH, 6.0), empty_mask());
  EXPECT_EQ(grow_within(seeds, room, kW, kH, std::numeric_limits<double>::quiet_NaN()),
            empty_mask());
}

}  // namespace
}  // namespace ferret
