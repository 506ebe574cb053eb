#include "ferret/mapping/frontier.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace ferret {
namespace {

GridGeometry geometry() { return {0.0, 0.0, 0.1, 20, 10}; }

// Columns 0..9 known free, the rest unknown: column 9 is the frontier.
IrGrid half_known() {
  IrGrid g(geometry(), {});
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) g.update_cell({i, j}, false);
  return g;
}

std::vector<float> all_reachable() { return std::vector<float>(geometry().size(), 1.0f); }

TEST(Frontier, FreeCellsNextToUnknownAreFrontier) {
  IrGrid g = half_known();
  FrontierTracker t(geometry());
  t.update(g);
  EXPECT_EQ(t.frontier_count(), 10u);
  for (int j = 0; j < 10; ++j) {
    EXPECT_TRUE(t.is_frontier({9, j}));
    EXPECT_FALSE(t.is_frontier({8, j}));
  }
}

TEST(Frontier, IncrementalUpdateMatchesRebuild) {
  IrGrid g = half_known();
  FrontierTracker inc(geometry());
  inc.update(g);
  for (int j = 2; j < 6; ++j) g.update_cell({10, j}, false);  // push part of the frontier out
  g.update_cell({10, 7}, true);
  inc.update(g);
  FrontierTracker full(geometry());
  full.rebuild(g);
  EXPECT_EQ(inc.frontier_count(), full.frontier_count());
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 20; ++i)
      EXPECT_EQ(inc.is_frontier({i, j}), full.is_frontier({i, j})) << i << "," << j;
  EXPECT_TRUE(inc.is_frontier({10, 3}));
  EXPECT_FALSE(inc.is_frontier({9, 4}));
}

TEST(Frontier, VisibleSetIsTheGlobalSetInsideTheFieldOfView) {
  IrGrid g = half_known();
  FrontierTracker t(geometry());
  t.update(g);
  const auto reach = all_reachable();
  // Sensor at (0.05, 0.55) facing +x, 30 degree fov: frontier x = 0.95, |dy| <= 0.88 tan(15) ~
  // 0.24.
  const auto sets = t.extract(reach, {0.05, 0.55, 0.0}, deg_to_rad(30), 4.0);
  EXPECT_EQ(sets.global.size(), 10u);
  ASSERT_EQ(sets.visible.size(), 5u);
  for (const Cell& c : sets.visible) EXPECT_LE(std::abs(c.j - 5), 2);
  // Out of range: none visible.
  EXPECT_TRUE(t.extract(reach, {0.05, 0.55, 0.0}, deg_to_rad(30), 0.5).visible.empty());
}

TEST(Frontier, UnreachableAndBlacklistedCellsAreLeftOut) {
  IrGrid g = half_known();
  FrontierTracker t(geometry(), {0.05});
  t.update(g);
  auto reach = all_reachable();
  reach[geometry().index({9, 0})] = kUnreachable;
  t.blacklist({9, 9});
  const auto sets = t.extract(reach, {0.05, 0.55, 0.0}, deg_to_rad(30), 4.0);
  EXPECT_EQ(sets.global.size(), 8u);
  EXPECT_TRUE(t.blacklisted({9, 9}));
  EXPECT_FALSE(t.blacklisted({9, 8}));
}

TEST(Frontier, OneKindOfBlacklistMarkCanBeLiftedAndLeavesTheOthers) {
  IrGrid g = half_known();
  FrontierTracker t(geometry(), {0.05});
  t.update(g);
  t.blacklist({9, 3});     // kind 1: a goal reached
  t.blacklist({9, 3}, 2);  // already marked: keeps kind 1
  t.blacklist({9, 6}, 2);  // kind 2: out of the tether's reach
  EXPECT_TRUE(t.blacklisted({9, 6}));
  t.clear_blacklist(2);
  EXPECT_FALSE(t.blacklisted({9, 6}));
  EXPECT_TRUE(t.blacklisted({9, 3}));
  const auto sets = t.extract(all_reachable(), {0.05, 0.55, 0.0}, deg_to_rad(30), 4.0);
  EXPECT_EQ(sets.global.size(), 9u);
}

TEST(Frontier, ClustersAreEightConnectedGroups) {
  IrGrid g = half_known();
  FrontierTracker t(geometry());
  t.update(g);
  auto reach = all_reachable();
  for (int j = 4; j < 6; ++j) reach[geometry().index({9, j})] = kUnreachable;  // split the column
  const auto sets = t.extract(reach, {0.05, 0.55, 0.0}, deg_to_rad(30), 4.0);
  ASSERT_EQ(sets.clusters.size(), 2u);
  std::vector<std::size_t> sizes{sets.clusters[0].cells.size(), sets.clusters[1].cells.size()};
  std::sort(sizes.begin(), sizes.end());
  EXPECT_EQ(sizes, (std::vector<std::size_t>{4, 4}));
  for (const auto& cl : sets.clusters) {
    EXPECT_NEAR(cl.centroid_W.x(), 0.95, 1e-9);
    EXPECT_EQ(cl.representative.i, 9);
  }
}

}  // namespace
}  // namespace ferret
