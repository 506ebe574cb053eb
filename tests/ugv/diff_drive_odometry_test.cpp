// Differential-drive odometry against poses computed by hand from the geometry.
#include "ferret/ugv/diff_drive_odometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace ferret::ugv {
namespace {

constexpr double kPi = std::numbers::pi;

// 1 count = 2 pi 0.02 / 360 m; 0.1 m track.
DiffDriveParams params() { return {0.02, 360.0, 0.1, 0.1, 10.0}; }
double metres(int ticks) { return ticks * 2.0 * kPi * 0.02 / 360.0; }

TEST(UgvDiffDriveOdometry, StraightTurnStraightMatchesTheHandComputedPose) {
  DiffDriveOdometry odo(params(), {1.0, 2.0, 0.0});
  odo.update(0, 0, 0);           // baseline
  odo.update(1000, 1000, 2000);  // straight: 0.3491 m along x
  EXPECT_NEAR(odo.pose().x_m, 1.0 + metres(1000), 1e-12);
  EXPECT_NEAR(odo.pose().y_m, 2.0, 1e-12);
  // On the spot: each wheel 125 counts, opposite: dtheta = 2 * metres(125) / 0.1.
  odo.update(875, 1125, 3000);
  const double turn = 2.0 * metres(125) / 0.1;
  EXPECT_NEAR(odo.pose().x_m, 1.0 + metres(1000), 1e-12);
  EXPECT_NEAR(odo.pose().yaw_rad, turn, 1e-12);
  odo.update(1375, 1625, 4000);  // straight again, along the new heading
  EXPECT_NEAR(odo.pose().x_m, 1.0 + metres(1000) + metres(500) * std::cos(turn), 1e-12);
  EXPECT_NEAR(odo.pose().y_m, 2.0 + metres(500) * std::sin(turn), 1e-12);
  EXPECT_NEAR(odo.pose().yaw_rad, turn, 1e-12);
}

TEST(UgvDiffDriveOdometry, AnArcEndsOnItsCircle) {
  // Left 300, right 600 counts in one step: ds = metres(450), dtheta = metres(300) / 0.1,
  // radius ds / dtheta = 0.15 m; from the origin facing x, the arc ends at
  // (R sin dtheta, R (1 - cos dtheta)).
  DiffDriveOdometry odo(params(), {});
  odo.update(0, 0, 0);
  odo.update(300, 600, 1000);
  const double dtheta = metres(300) / 0.1, radius = 0.15;
  EXPECT_NEAR(odo.pose().x_m, radius * std::sin(dtheta), 1e-12);
  EXPECT_NEAR(odo.pose().y_m, radius * (1 - std::cos(dtheta)), 1e-12);
  EXPECT_NEAR(odo.pose().yaw_rad, dtheta, 1e-12);
}

TEST(UgvDiffDriveOdometry, CountersThatWrapStillGiveTheSmallStep) {
  DiffDriveOdometry odo(params(), {});
  const std::int32_t near_max = std::numeric_limits<std::int32_t>::max() - 5;
  odo.update(near_max, near_max, 4294967290u);  // the clock wraps too
  odo.update(near_max, near_max, 4294967295u);
  odo.update(static_cast<std::int32_t>(static_cast<std::uint32_t>(near_max) + 20u),
             static_cast<std::int32_t>(static_cast<std::uint32_t>(near_max) + 20u), 200u);
  EXPECT_NEAR(odo.pose().x_m, metres(20), 1e-12);
  EXPECT_EQ(odo.rebaselines(), 0u);
}

TEST(UgvDiffDriveOdometry, ARestartOrAGlitchIsANewBaselineNotAJump) {
  DiffDriveOdometry odo(params(), {});
  odo.update(0, 0, 1000);
  odo.update(100, 100, 1100);
  const double x = odo.pose().x_m;
  odo.update(0, 0, 5);  // the MCU restarted: time went back
  EXPECT_NEAR(odo.pose().x_m, x, 1e-12);
  odo.update(100000, 100000, 25);  // 35 m in 20 ms: no wheel does that
  EXPECT_NEAR(odo.pose().x_m, x, 1e-12);
  odo.update(100010, 100010, 45);
  EXPECT_NEAR(odo.pose().x_m, x + metres(10), 1e-12);
  EXPECT_EQ(odo.rebaselines(), 2u);
}

TEST(UgvDiffDriveOdometry, SpeedIsAveragedOverTheWindowOfMcuTime) {
  DiffDriveOdometry odo(params(), {});
  odo.update(0, 0, 0);
  // 20 ms steps of 10 counts: metres(10) / 0.02 s.
  for (int k = 1; k <= 10; ++k) odo.update(10 * k, 10 * k, static_cast<std::uint32_t>(20 * k));
  EXPECT_NEAR(odo.speed_mps(), metres(10) / 0.02, 1e-9);
  for (int k = 11; k <= 20; ++k) odo.update(100, 100, static_cast<std::uint32_t>(20 * k));
  EXPECT_NEAR(odo.speed_mps(), 0.0, 1e-12);  // stopped for longer than the window
}

}  // namespace
}  // namespace ferret::ugv
