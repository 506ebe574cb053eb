// The search's coverage pattern: its legs, its passes and how far the search got.

#include "ferret/uav/coverage_pattern.hpp"

#include <gtest/gtest.h>

namespace ferret {
namespace {

TEST(CoveragePattern, LegsAlongXThenAlongYEachWayInTurnInsideTheArea) {
  const CoveragePattern p({-10.0, -4.0, 10.0, 4.0}, 5.0, 2, 2.0);
  // 8 m across at 2 m: 4 legs along x; 20 m across: 10 legs along y; 2 waypoints a leg.
  ASSERT_EQ(p.first_pass_waypoints(), 8u);
  ASSERT_EQ(p.waypoints().size(), 28u);
  EXPECT_DOUBLE_EQ(p.leg_spacing_m(), 2.0);
  EXPECT_EQ(p.waypoints()[0], Eigen::Vector3d(-10.0, -3.0, 5.0));  // half a leg in
  EXPECT_EQ(p.waypoints()[1], Eigen::Vector3d(10.0, -3.0, 5.0));
  EXPECT_EQ(p.waypoints()[2], Eigen::Vector3d(10.0, -1.0, 5.0));  // back the other way
  EXPECT_EQ(p.waypoints()[8], Eigen::Vector3d(-9.0, -4.0, 5.0));  // the second pass
  EXPECT_EQ(p.waypoints()[9], Eigen::Vector3d(-9.0, 4.0, 5.0));
  for (const Eigen::Vector3d& w : p.waypoints()) {
    EXPECT_TRUE(w.x() >= -10.0 && w.x() <= 10.0 && w.y() >= -4.0 && w.y() <= 4.0) << w.transpose();
    EXPECT_DOUBLE_EQ(w.z(), 5.0);
  }
  EXPECT_EQ(CoveragePattern({-10.0, -4.0, 10.0, 4.0}, 5.0, 1, 2.0).waypoints().size(), 8u);
}

TEST(CoveragePattern, AnAreaNarrowerThanTheSpacingStillHasALeg) {
  const CoveragePattern p({0.0, 0.0, 3.0, 1.0}, 4.0, 1, 10.0);
  ASSERT_EQ(p.waypoints().size(), 2u);
  EXPECT_EQ(p.waypoints()[0], Eigen::Vector3d(0.0, 0.5, 4.0));
}

TEST(CoveragePattern, TheSearchAdvancesWaypointByWaypointToTheEnd) {
  CoveragePattern p({0.0, 0.0, 4.0, 4.0}, 4.0, 1, 2.0);
  ASSERT_EQ(p.waypoints().size(), 4u);
  EXPECT_EQ(p.next_index(), 0u);
  EXPECT_EQ(p.next_waypoint(), p.waypoints()[0]);
  for (int i = 0; i < 4; ++i) {
    EXPECT_FALSE(p.done());
    p.advance();
  }
  EXPECT_TRUE(p.done());
  EXPECT_EQ(p.next_index(), 4u);
  EXPECT_TRUE(CoveragePattern().done());
}

}  // namespace
}  // namespace ferret
