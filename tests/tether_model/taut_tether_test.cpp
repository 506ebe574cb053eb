#include "ferret/tether_model/taut_tether.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ferret/core/random.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"

namespace ferret {
namespace {

using V = Eigen::Vector2d;

// A 10 x 10 m room at 0.1 m with one 2 x 2 m block at [4, 6] x [4, 6].
std::shared_ptr<const TetherCorners> block_world() {
  const GridGeometry g{0.0, 0.0, 0.1, 100, 100};
  return TetherCorners::from_grid(
      g, [](Cell c) { return c.i >= 40 && c.i < 60 && c.j >= 40 && c.j < 60; });
}

TEST(TetherCorners, ConvexCornersOnlyWithTheirObstacleSide) {
  // An L-shaped obstacle: cells (1,1), (2,1), (1,2) at 1 m resolution. Its convex
  // corners are (1,1), (3,1), (3,2), (2,3), (1,3); the concave (2,2) is no corner.
  OccupancyMap2D map;
  map.geometry = {0.0, 0.0, 1.0, 5, 5};
  map.cells.assign(25, CellState::kFree);
  for (Cell c : {Cell{1, 1}, Cell{2, 1}, Cell{1, 2}})
    map.cells[map.geometry.index(c)] = CellState::kOccupied;
  const auto corners = TetherCorners::from_map(map);
  std::vector<V> got;
  for (const auto& c : corners->all()) got.push_back(c.p_W);
  const std::vector<V> want{{1, 1}, {3, 1}, {3, 2}, {2, 3}, {1, 3}};
  ASSERT_EQ(got.size(), want.size());
  for (const V& w : want) {
    EXPECT_TRUE(std::any_of(got.begin(), got.end(), [&](const V& p) {
      return (p - w).norm() < 1e-12;
    })) << w.transpose();
  }
  // (1,1) has the obstacle up and right: quadrant 0 only.
  for (const auto& c : corners->all()) {
    if ((c.p_W - V{1, 1}).norm() < 1e-12) {
      EXPECT_EQ(c.occupied_quadrants, 1);
    }
  }
  // An unknown cell blocks by default (hidden-space policy) and not when asked.
  map.cells[map.geometry.index({3, 3})] = CellState::kUnknown;
  EXPECT_EQ(TetherCorners::from_map(map)->all().size(), 9u);
  EXPECT_EQ(TetherCorners::from_map(map, false)->all().size(), 5u);
}

TEST(TautTether, StraightWithoutObstacles) {
  TautTether t(block_world(), V{1, 1});
  t.move_to({3, 1});
  t.move_to({3, 2});
  EXPECT_TRUE(t.wrap_points().empty());
  EXPECT_NEAR(t.length_m(), std::sqrt(4.0 + 1.0), 1e-12);
}

TEST(TautTether, WrapsAroundTheCornersItIsPulledInto) {
  // Up the left of the block (the tether clears it), then over the top: the tether
  // catches (4,4), then (4,6), both turning clockwise.
  TautTether t(block_world(), V{4.5, 2});
  for (V p : {V{2, 2}, V{2, 9}}) t.move_to(p);
  EXPECT_TRUE(t.wrap_points().empty());
  t.move_to({5, 9});
  ASSERT_EQ(t.wrap_points().size(), 2u);
  EXPECT_TRUE(t.wrap_points()[0].p_W.isApprox(V{4, 4}));
  EXPECT_TRUE(t.wrap_points()[1].p_W.isApprox(V{4, 6}));
  EXPECT_EQ(t.wrap_points()[0].side, -1);
  EXPECT_EQ(t.wrap_points()[1].side, -1);
  const double left = std::sqrt(0.25 + 4.0) + 2.0 + std::sqrt(1.0 + 9.0);
  EXPECT_NEAR(t.length_m(), left, 1e-9);
  EXPECT_EQ(t.polyline().size(), 4u);
  // The same tether rebuilt from its recorded wrap points.
  const TautTether copy(block_world(), V{4.5, 2}, t.wrap_points(), V{5, 9});
  EXPECT_NEAR(copy.length_m(), left, 1e-12);

  // The same goal round the right side is another homotopy class, another length.
  TautTether r(block_world(), V{4.5, 2});
  for (V p : {V{8, 2}, V{8, 9}, V{5, 9}}) r.move_to(p);
  ASSERT_EQ(r.wrap_points().size(), 2u);
  EXPECT_TRUE(r.wrap_points()[0].p_W.isApprox(V{6, 4}));
  EXPECT_TRUE(r.wrap_points()[1].p_W.isApprox(V{6, 6}));
  EXPECT_NEAR(r.length_m(), std::sqrt(2.25 + 4.0) + 2.0 + std::sqrt(1.0 + 9.0), 1e-9);

  // Driving back the way it came releases every wrap point.
  for (V p : {V{2, 9}, V{2, 2}, V{4.5, 2}}) t.move_to(p);
  EXPECT_TRUE(t.wrap_points().empty());
  EXPECT_NEAR(t.length_m(), 0.0, 1e-12);
}

TEST(TautTether, WindsAndUnwindsAroundALoop) {
  TautTether t(block_world(), V{5, 1});
  const std::vector<V> loop{{9, 1}, {9, 9}, {1, 9}, {1, 1}, {5, 0.5}};
  for (const V& p : loop) t.move_to(p);
  ASSERT_EQ(t.wrap_points().size(), 4u);
  EXPECT_NEAR(t.length_m(), std::sqrt(10.0) + 6.0 + std::sqrt(1.0 + 12.25), 1e-9);
  // Half way round again: the tether wraps the first corner a second time.
  t.move_to({9, 1});
  t.move_to({9, 5});
  ASSERT_EQ(t.wrap_points().size(), 5u);
  EXPECT_TRUE(t.wrap_points()[4].p_W.isApprox(V{6, 4}));
  EXPECT_NEAR(t.length_m(), std::sqrt(10.0) + 8.0 + std::sqrt(10.0), 1e-9);
  // Unwind the whole way.
  for (V p : {V{9, 1}, V{5, 0.5}, V{1, 1}, V{1, 9}, V{9, 9}, V{9, 1}, V{5, 1}}) t.move_to(p);
  EXPECT_TRUE(t.wrap_points().empty());
  EXPECT_NEAR(t.length_m(), 0.0, 1e-12);
}

TEST(TautTether, TheWayBackPassesEachWrapPointOutsideItsCornerAndOnlyShortensTheTether) {
  // Wound once round the block from (5, 1): four wrap points, then the way back.
  TautTether t(block_world(), V{5, 1});
  for (const V& p : {V{9, 1}, V{9, 9}, V{1, 9}, V{1, 1}, V{5, 0.5}}) t.move_to(p);
  ASSERT_EQ(t.wrap_points().size(), 4u);
  const double offset = 0.3;
  const auto way = way_back_along_tether(t, offset);
  ASSERT_EQ(way.size(), 4u);
  // In reverse (the corner nearest the robot's end first), each `offset` from its corner
  // along the bisector, so outside the block: the corners (4,4), (4,6), (6,6), (6,4)
  // were wrapped in the order (6,4), (6,6), (4,6), (4,4).
  const std::vector<V> corners{{4, 4}, {4, 6}, {6, 6}, {6, 4}};
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_NEAR((way[k] - corners[k]).norm(), offset, 1e-9) << k;
    const V d = way[k] - V{5, 5};
    EXPECT_GT(std::max(std::abs(d.x()), std::abs(d.y())), 1.0 + 0.2) << "inside the block: " << k;
  }
  // Driving it, the tether never gets longer and ends straight at the entry.
  double before = t.length_m();
  for (const V& p : way) {
    t.move_to(p);
    EXPECT_LE(t.length_m(), before + 1e-9);
    before = t.length_m();
  }
  t.move_to(t.entry());
  EXPECT_TRUE(t.wrap_points().empty());
  // A straight tether has no way back to follow.
  EXPECT_TRUE(way_back_along_tether(t, offset).empty());
}

TEST(TautTether, GrazingAnEdgeWrapsOnlyWhenPushedIntoTheObstacle) {
  // The tether from (2,4) to (8,4) lies along the block's bottom edge y = 4.
  TautTether t(block_world(), V{2, 4}, V{8, 4});
  t.move_to({8, 3});  // away from the block: it stays straight
  EXPECT_TRUE(t.wrap_points().empty());
  EXPECT_NEAR(t.length_m(), std::sqrt(37.0), 1e-12);
  t.move_to({8, 5});  // up past the edge line: it catches the bottom corners
  ASSERT_FALSE(t.wrap_points().empty());
  EXPECT_TRUE(t.wrap_points().back().p_W.isApprox(V{6, 4}));
  EXPECT_NEAR(t.length_m(), 4.0 + std::sqrt(5.0), 1e-9);
  t.move_to({8, 3});
  EXPECT_TRUE(t.wrap_points().empty());
  EXPECT_NEAR(t.length_m(), std::sqrt(37.0), 1e-12);
}

TEST(TautTether, LengthLimit) {
  const TetherParams p{15.0, 1.0};
  EXPECT_TRUE(tether_length_ok(14.0, p));
  EXPECT_FALSE(tether_length_ok(14.0 + 1e-9, p));
}

// Random drives through a cluttered room: the taut tether never passes through an
// obstacle, is never longer than the path driven, and retracing the drive releases it.
TEST(TautTether, RandomDrivesStayTautAndUnwind) {
  const GridGeometry g{0.0, 0.0, 0.1, 120, 80};
  std::vector<char> occ(g.size(), 0);
  Rng rng(7);
  for (int b = 0; b < 10; ++b) {
    const int i0 = static_cast<int>(rng.uniform_int(5, 100)),
              j0 = static_cast<int>(rng.uniform_int(5, 60));
    const int w = static_cast<int>(rng.uniform_int(3, 15)),
              h = static_cast<int>(rng.uniform_int(3, 15));
    for (int j = j0; j < std::min(j0 + h, g.height); ++j)
      for (int i = i0; i < std::min(i0 + w, g.width); ++i) occ[g.index({i, j})] = 1;
  }
  auto blocked = [&](Cell c) { return !g.contains(c) || occ[g.index(c)]; };
  const auto corners = TetherCorners::from_grid(g, [&](Cell c) { return occ[g.index(c)] != 0; });
  // Robot motions: free with a margin, sampled finely.
  auto segment_free = [&](const V& a, const V& b, double margin) {
    const int n = static_cast<int>((b - a).norm() / 0.01) + 1;
    for (int k = 0; k <= n; ++k) {
      const V p = a + (b - a) * (static_cast<double>(k) / n);
      for (double dx : {-margin, margin})
        for (double dy : {-margin, margin})
          if (blocked(g.cell_at(p.x() + dx, p.y() + dy))) return false;
    }
    return true;
  };
  // The tether may lie along an obstacle's edge, never inside it: a point is inside
  // when points a hair away on all four diagonals are blocked.
  auto tether_clear = [&](const V& a, const V& b) {
    const int n = static_cast<int>((b - a).norm() / 0.005) + 1;
    for (int k = 0; k <= n; ++k) {
      const V p = a + (b - a) * (static_cast<double>(k) / n);
      int hits = 0;
      for (double dx : {-1e-6, 1e-6})
        for (double dy : {-1e-6, 1e-6}) hits += blocked(g.cell_at(p.x() + dx, p.y() + dy)) ? 1 : 0;
      if (hits == 4) return false;
    }
    return true;
  };
  int wrapped_runs = 0;
  for (int run = 0; run < 30; ++run) {
    V start;
    do start = {rng.uniform(0.5, 11.5), rng.uniform(0.5, 7.5)};
    while (!segment_free(start, start, 0.1));
    TautTether t(corners, start);
    std::vector<V> path{start};
    double driven = 0.0;
    while (path.size() < 60) {
      const V next = path.back() + V{rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)};
      if (!segment_free(path.back(), next, 0.1)) continue;
      driven += (next - path.back()).norm();
      t.move_to(next);
      path.push_back(next);
      EXPECT_LE(t.length_m(), driven + 1e-9);
      const auto line = t.polyline();
      for (std::size_t k = 0; k + 1 < line.size(); ++k) {
        ASSERT_TRUE(tether_clear(line[k], line[k + 1]))
            << "run " << run << " step " << path.size() << " segment " << line[k].transpose()
            << " -> " << line[k + 1].transpose();
      }
    }
    wrapped_runs += t.wrap_points().empty() ? 0 : 1;
    for (auto it = path.rbegin() + 1; it != path.rend(); ++it) t.move_to(*it);
    EXPECT_TRUE(t.wrap_points().empty()) << "run " << run;
    EXPECT_NEAR(t.length_m(), 0.0, 1e-9);
  }
  EXPECT_GT(wrapped_runs, 5);  // the test exercised wrapping, not only straight tethers
}

}  // namespace
}  // namespace ferret
