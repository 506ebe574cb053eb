#include <gtest/gtest.h>

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

}  // namespace
}  // namespace ferret
