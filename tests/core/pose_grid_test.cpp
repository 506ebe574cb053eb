#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ferret/core/grid.hpp"
#include "ferret/core/pose.hpp"

namespace ferret {
namespace {
constexpr double kPi = std::numbers::pi;

TEST(Pose2, WrapAngle) {
  EXPECT_NEAR(wrap_angle_rad(3 * kPi), kPi, 1e-12);
  EXPECT_NEAR(wrap_angle_rad(-kPi), kPi, 1e-12);
  EXPECT_NEAR(wrap_angle_rad(-0.5 * kPi - 2 * kPi), -0.5 * kPi, 1e-12);
}

TEST(Pose2, ComposeReadsRightToLeft) {
  const Pose2 X_WB{1.0, 2.0, kPi / 2};
  const Pose2 X_BC{1.0, 0.0, kPi / 2};
  const Pose2 X_WC = X_WB * X_BC;  // one metre ahead of B is +y in W
  EXPECT_NEAR(X_WC.x_m, 1.0, 1e-12);
  EXPECT_NEAR(X_WC.y_m, 3.0, 1e-12);
  EXPECT_NEAR(X_WC.yaw_rad, kPi, 1e-12);
}

TEST(GridGeometry, CellsAndCentres) {
  const GridGeometry g{-1.0, 2.0, 0.5, 4, 3};
  EXPECT_EQ(g.size(), 12u);
  EXPECT_EQ(g.cell_at(-1.0, 2.0), (Cell{0, 0}));
  EXPECT_EQ(g.cell_at(0.99, 3.49), (Cell{3, 2}));
  EXPECT_FALSE(g.contains(g.cell_at(1.0, 2.0)));
  EXPECT_FALSE(g.contains(g.cell_at(-1.01, 2.0)));
  EXPECT_EQ(g.index({3, 2}), 11u);
  EXPECT_EQ(g.cell_of_index(6), (Cell{2, 1}));
  EXPECT_TRUE(g.center({1, 1}).isApprox(Eigen::Vector2d(-0.25, 2.75)));
}

TEST(GridGeometry, AWindowCentredOnAPointHasItsCellsOnTheResolutionsGrid) {
  // 1.02 x 0.5 m at 0.05 m round (0.03, -0.01): 21 x 10 cells (ceil(20.4), 10), the
  // origin on a multiple of 0.05 at or below centre - half the window's cells.
  const GridGeometry g = GridGeometry::centred_on({0.03, -0.01}, 1.02, 0.5, 0.05);
  EXPECT_EQ(g.width, 21);
  EXPECT_EQ(g.height, 10);
  EXPECT_NEAR(g.origin_x_m, -0.50, 1e-12);  // floor((0.03 - 0.525) / 0.05) = -10
  EXPECT_NEAR(g.origin_y_m, -0.30, 1e-12);  // floor((-0.01 - 0.25) / 0.05) = -6
  EXPECT_TRUE(g.contains(g.cell_at(0.03, -0.01)));
  // Another window of the same resolution elsewhere shares its cell edges.
  const GridGeometry h = GridGeometry::centred_on({7.77, 3.14}, 2.0, 2.0, 0.05);
  EXPECT_NEAR(std::remainder(h.origin_x_m - g.origin_x_m, 0.05), 0.0, 1e-9);
  EXPECT_NEAR(std::remainder(h.origin_y_m - g.origin_y_m, 0.05), 0.0, 1e-9);
  // Degenerate sizes still give one cell.
  EXPECT_EQ(GridGeometry::centred_on({0, 0}, 0.0, 0.0, 0.1).size(), 1u);
}

}  // namespace
}  // namespace ferret
