#include "ferret/planning/plan_overlay.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "waypoints.hpp"

namespace ferret {
namespace {

using test::ugv_at;
using ::testing::HasSubstr;

bool same(Rgb a, Rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

// 6 x 4 m at 0.1 m from the origin, a box on cells i 20..29, j 0..24: x [2, 3], y [0, 2.5].
OccupancyMap2D boxed_room() {
  OccupancyMap2D m = OccupancyMap2D::filled(GridGeometry{0.0, 0.0, 0.1, 60, 40}, CellState::kFree);
  for (int j = 0; j < 25; ++j)
    for (int i = 20; i < 30; ++i) m.at({i, j}) = CellState::kOccupied;
  return m;
}

// A miniUGV plan that drives over the box and down its far side, its tether entering at
// (0.5, 2): the tether wraps the box's corners (2, 2.5) and (3, 2.5).
PlanFile round_the_box() {
  PlanFile p;
  p.robot = PlanRobot::kUgv;
  p.states = {ugv_at(0, 1.0, 3.5, 0.0), ugv_at(3, 4.0, 3.5, 0.0), ugv_at(6, 4.0, 1.0, -M_PI / 2)};
  p.tether = PlanTether{};
  p.tether->p_WE = {0.5, 2.0};
  return p;
}

TEST(PlanOverlay, PathTetherAndMarkersLandWhereThePosesProject) {
  const OccupancyMap2D map = boxed_room();
  RenderOptions o;
  o.pixels_per_cell = 5;  // 50 px a metre
  o.scale_bar = false;
  MapCanvas canvas(map, o);
  const PlanOverlayStyle style;
  const PlanOverlaySummary s = draw_plan(canvas, round_the_box(), map, style);
  EXPECT_EQ(s.states, 3u);
  EXPECT_EQ(s.outside, 0u);
  EXPECT_EQ(s.wraps, 2u);
  EXPECT_EQ(s.goal_wraps, 2u);
  // E -> (2, 2.5) -> (3, 2.5) -> (4, 1): sqrt(1.5^2 + 0.5^2) + 1 + sqrt(1 + 1.5^2).
  EXPECT_NEAR(s.tether_taut_m, std::sqrt(2.5) + 1.0 + std::sqrt(3.25), 1e-9);
  EXPECT_THAT(s.describe(), HasSubstr("tether 4.38 m taut at the goal, 2 wrap points"));
  EXPECT_NEAR(s.length_m, 5.5, 1e-12);  // 3 m east, 2.5 m south
  const RgbImage img = canvas.image();
  const PixelRect m = canvas.map_area();
  // World (x, y) is at column m.x + 50 x, row m.y + 50 (4 - y), by hand.
  const auto at_m = [&](double x, double y) {
    return ferret::pixel(img, m.x + static_cast<int>(std::lround(50 * x)),
                         m.y + static_cast<int>(std::lround(50 * (4.0 - y))));
  };
  EXPECT_TRUE(same(at_m(2.5, 3.5), style.path));   // mid first leg
  EXPECT_TRUE(same(at_m(4.0, 2.25), style.path));  // mid second leg
  EXPECT_TRUE(same(at_m(1.0, 3.5), style.start));
  EXPECT_TRUE(same(at_m(4.0, 1.0), style.goal));
  EXPECT_TRUE(same(at_m(0.5, 2.0), style.entry));
  EXPECT_TRUE(same(at_m(2.5, 2.5), style.tether));  // over the box, from corner to corner
  // A wrap point's ring: 6 px round the corner (3, 2.5), i.e. 0.12 m to its left.
  EXPECT_TRUE(same(at_m(3.0 - 0.12, 2.5), style.wrap));
  // Every overlay has its legend entry.
  const PixelRect l = canvas.legend_area();
  for (const Rgb c : {style.path, style.start, style.goal, style.entry, style.tether, style.wrap}) {
    int n = 0;
    for (int r = l.y; r < l.y + l.height; ++r)
      for (int col = l.x; col < l.x + l.width; ++col) n += same(pixel(img, col, r), c);
    EXPECT_GT(n, 10) << int(c.r) << "," << int(c.g) << "," << int(c.b);
  }
}

TEST(PlanOverlay, APlanPartlyOutsideTheMapIsClippedAndCounted) {
  const OccupancyMap2D map = boxed_room();
  PlanFile p;
  p.robot = PlanRobot::kUav;
  p.states = {ugv_at(0, 1.0, 3.5, 0), ugv_at(1, 5.0, 3.5, 0), ugv_at(2, 8.0, 3.5, 0),
              ugv_at(3, 9.0, 5.0, 0)};
  RenderOptions o;
  o.pixels_per_cell = 5;
  MapCanvas canvas(map, o);
  const PlanOverlaySummary s = draw_plan(canvas, p, map);
  EXPECT_EQ(s.outside, 2u);
  EXPECT_EQ(s.wraps, 0u);  // a UAV plan has no tether on the floor
  EXPECT_THAT(s.describe(), HasSubstr("2 of 4 states outside the map"));
  // The part inside is drawn up to the map's right edge (x = 6 m).
  const RgbImage img = canvas.image();
  const PixelRect m = canvas.map_area();
  EXPECT_TRUE(same(pixel(img, m.x + 295, m.y + 25), PlanOverlayStyle{}.path));
}

}  // namespace
}  // namespace ferret

namespace ferret {
namespace {

// A segment from 1e5 m west to 1e5 m east of a 6 m map is drawn where it crosses the map
// (clipped to the picture: its cost no longer grows with its length), and a segment that
// never crosses it draws nothing on it.
TEST(PlanOverlay, FarSegmentsAreClippedToWhatIsSeen) {
  const OccupancyMap2D map =
      OccupancyMap2D::filled(GridGeometry{0.0, 0.0, 0.1, 60, 40}, CellState::kFree);
  RenderOptions o;
  o.pixels_per_cell = 5;  // 50 px a metre
  o.scale_bar = false;
  MapCanvas canvas(map, o);
  const PlanOverlayStyle style;
  PlanFile p;
  p.states = {test::ugv_at(0, -1e5, 1.0, 0.0), test::ugv_at(1, 1e5, 1.0, 0.0),
              test::ugv_at(2, 1e5, 1e5, 0.0), test::ugv_at(3, -1e5, 1e5, 0.0)};
  const PlanOverlaySummary s = draw_plan(canvas, p, map, style);
  EXPECT_EQ(s.outside, 4u);
  EXPECT_NEAR(s.length_m, 2e5 + (1e5 - 1.0) + 2e5, 1e-6);
  const RgbImage img = canvas.image();
  const PixelRect m = canvas.map_area();
  const auto at_m = [&](double x, double y) {
    return ferret::pixel(img, m.x + static_cast<int>(std::lround(50 * x)),
                         m.y + static_cast<int>(std::lround(50 * (4.0 - y))));
  };
  for (const double x : {0.2, 3.0, 5.8}) EXPECT_TRUE(same(at_m(x, 1.0), style.path)) << x;
  EXPECT_FALSE(same(at_m(3.0, 3.0), style.path));  // the far legs stay off the map
}

}  // namespace
}  // namespace ferret
