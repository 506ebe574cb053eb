#include "ferret/sim/hidden_space_generator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <limits>
#include <numbers>

#include "ferret/core/error.hpp"
#include "ferret/mission/experiment.hpp"  // the experiment samples objects in the zones

namespace ferret {
namespace {

// Cells a disc of `radius_m` can stand on (no occupied cell within the square of
// half-side radius_m around it, the generator's rule), 4-connected from `from`.
std::vector<char> reachable(const OccupancyMap2D& map, Cell from, double radius_m) {
  const GridGeometry& g = map.geometry;
  const int k = static_cast<int>(std::ceil(radius_m / g.resolution_m));
  std::vector<char> stand(g.size(), 1);
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i)
      if (map.at({i, j}) != CellState::kFree)
        for (int dj = -k; dj <= k; ++dj)
          for (int di = -k; di <= k; ++di)
            if (g.contains({i + di, j + dj})) stand[g.index({i + di, j + dj})] = 0;
  std::vector<char> seen(g.size(), 0);
  if (!stand[g.index(from)]) return seen;
  std::deque<Cell> q{from};
  seen[g.index(from)] = 1;
  while (!q.empty()) {
    const Cell c = q.front();
    q.pop_front();
    for (const Cell d :
         {Cell{c.i + 1, c.j}, Cell{c.i - 1, c.j}, Cell{c.i, c.j + 1}, Cell{c.i, c.j - 1}}) {
      if (!g.contains(d) || !stand[g.index(d)] || seen[g.index(d)]) continue;
      seen[g.index(d)] = 1;
      q.push_back(d);
    }
  }
  // Every cell the disc could stand on must have been reached.
  for (std::size_t c = 0; c < g.size(); ++c)
    if (stand[c] && !seen[c]) return {};
  return seen;
}

// Bearing (rad, from the heading) and range of p seen from the start.
std::pair<double, double> polar(const Pose2& s, double x, double y) {
  return {std::abs(std::atan2(y - s.y_m, x - s.x_m) - s.yaw_rad), std::hypot(x - s.x_m, y - s.y_m)};
}

class Generated : public ::testing::TestWithParam<std::tuple<HiddenSpaceClutter, std::uint64_t>> {};

TEST_P(Generated, FreeSpaceIsOneConnectedPieceAndTheZonesAreThePapers) {
  HiddenSpaceGeneratorOptions o;
  o.clutter = std::get<0>(GetParam());
  o.seed = std::get<1>(GetParam());
  const GeneratedHiddenSpace h = generate_hidden_space(o);
  const OccupancyMap2D& m = h.map;
  ASSERT_EQ(m.geometry.width, 240);
  ASSERT_EQ(m.geometry.height, 160);
  // Walled all round; nothing unknown.
  for (int i = 0; i < m.geometry.width; ++i) {
    EXPECT_EQ(m.at({i, 0}), CellState::kOccupied);
    EXPECT_EQ(m.at({i, m.geometry.height - 1}), CellState::kOccupied);
  }
  EXPECT_EQ(m.count(CellState::kUnknown), 0u);
  // Every place the robot fits is reachable from the start.
  const Cell start = m.geometry.cell_at(h.start.x_m, h.start.y_m);
  EXPECT_FALSE(reachable(m, start, o.robot_radius_m).empty()) << "a pocket the robot cannot reach";
  // The zones by their definition, for the paper's sensors (camera 90 deg, IR 30 deg, 4 m).
  ASSERT_EQ(h.zones.size(), 5u);
  const double ir_half = 15.0 * std::numbers::pi / 180, cam_half = 45.0 * std::numbers::pi / 180;
  for (const ZoneSpec& z : h.zones) {
    for (const double x : {z.xmin_m, z.xmax_m})
      for (const double y : {z.ymin_m, z.ymax_m}) {
        const auto [bearing, range] = polar(h.start, x, y);
        if (z.id == 1) {
          EXPECT_LT(bearing, ir_half);
          EXPECT_LT(range, 4.0);
        } else if (z.id == 2 || z.id == 4) {
          EXPECT_GT(bearing, ir_half) << z.id;
          EXPECT_LT(bearing, cam_half) << z.id;
          EXPECT_LT(range, 4.0) << z.id;
        } else {
          EXPECT_GT(range, 4.0) << z.id;
        }
      }
    // Zone 2 left of the heading, 4 right, 3 left, 5 right.
    const double mid_y = 0.5 * (z.ymin_m + z.ymax_m);
    if (z.id == 2 || z.id == 3) {
      EXPECT_GT(mid_y, h.start.y_m);
    } else if (z.id == 4 || z.id == 5) {
      EXPECT_LT(mid_y, h.start.y_m);
    }
    // Objects can be placed in every zone: free cells 0.25 m from anything.
    EXPECT_FALSE(sample_zone_objects(m, z, 3, 0.25, 1).empty()) << "zone " << z.id;
  }
  // Zones 1, 2 and 4 in full view: nothing occupied inside them.
  for (const ZoneSpec& z : h.zones) {
    if (z.id == 3 || z.id == 5) continue;
    for (int j = m.geometry.cell_at(0, z.ymin_m).j; j <= m.geometry.cell_at(0, z.ymax_m).j; ++j)
      for (int i = m.geometry.cell_at(z.xmin_m, 0).i; i <= m.geometry.cell_at(z.xmax_m, 0).i; ++i)
        EXPECT_NE(m.at({i, j}), CellState::kOccupied) << "zone " << z.id;
  }
}

INSTANTIATE_TEST_SUITE_P(SeedsAndClutter, Generated,
                         ::testing::Combine(::testing::Values(HiddenSpaceClutter::kSparse,
                                                              HiddenSpaceClutter::kDense),
                                            ::testing::Values(1u, 2u, 3u, 17u, 4242u)));

TEST(GeneratedHiddenSpace, TheSameSeedGivesTheSameSpaceAndAnotherSeedAnother) {
  HiddenSpaceGeneratorOptions o;
  o.seed = 7;
  const auto a = generate_hidden_space(o), b = generate_hidden_space(o);
  EXPECT_EQ(a.map, b.map);
  EXPECT_EQ(a.search_yaml(), b.search_yaml());
  o.seed = 8;
  EXPECT_FALSE(generate_hidden_space(o).map == a.map);
}

TEST(GeneratedHiddenSpace, DenseHasMoreInItThanSparse) {
  // Over ten seeds each: clutter is a setting that means something.
  std::size_t sparse = 0, dense = 0;
  for (std::uint64_t s = 1; s <= 10; ++s) {
    HiddenSpaceGeneratorOptions o;
    o.seed = s;
    sparse += generate_hidden_space(o).map.count(CellState::kOccupied);
    o.clutter = HiddenSpaceClutter::kDense;
    dense += generate_hidden_space(o).map.count(CellState::kOccupied);
  }
  EXPECT_GT(dense, sparse + sparse / 4);
}

TEST(GeneratedHiddenSpace, OtherSizesKeepTheRules) {
  HiddenSpaceGeneratorOptions o;
  o.clutter = HiddenSpaceClutter::kDense;
  o.width_m = 8.0;
  o.height_m = 5.0;
  const auto small = generate_hidden_space(o);
  EXPECT_EQ(small.map.geometry.width, 160);
  EXPECT_FALSE(
      reachable(small.map, small.map.geometry.cell_at(small.start.x_m, small.start.y_m), 0.1)
          .empty());
  o.width_m = 24.0;
  o.height_m = 16.0;
  o.resolution_m = 0.1;
  const auto large = generate_hidden_space(o);
  EXPECT_EQ(large.map.geometry.width, 240);
  EXPECT_EQ(large.map.geometry.height, 160);
  EXPECT_FALSE(
      reachable(large.map, large.map.geometry.cell_at(large.start.x_m, large.start.y_m), 0.1)
          .empty());
  EXPECT_NEAR(large.zones[2].xmax_m, 23.5, 1e-9);  // zone 3 reaches 0.5 m short of the far wall
}

TEST(GeneratedHiddenSpace, SizesOutsideTheRangeAreRefusedNamingTheOption) {
  HiddenSpaceGeneratorOptions o;
  for (const double w : {7.9, 65.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    o.width_m = w;
    try {
      (void)generate_hidden_space(o);
      ADD_FAILURE() << w;
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), "--size") << e.what();
    }
  }
  o.width_m = 12;
  o.resolution_m = 0.0;
  EXPECT_THROW((void)generate_hidden_space(o), InputError);
}

TEST(GeneratedHiddenSpace, TheSearchSectionSaysWhereAndHow) {
  HiddenSpaceGeneratorOptions o;
  o.seed = 3;
  o.clutter = HiddenSpaceClutter::kDense;
  const auto h = generate_hidden_space(o);
  const std::string y = h.search_yaml();
  EXPECT_EQ(y.rfind("search:\n  start: [1, ", 0), 0u) << y;
  EXPECT_NE(y.find("    5: ["), std::string::npos) << y;
  EXPECT_NE(y.find("generator: {seed: 3, size_m: [12, 8], resolution_m: 0.05, clutter: dense}"),
            std::string::npos)
      << y;
}

}  // namespace
}  // namespace ferret
