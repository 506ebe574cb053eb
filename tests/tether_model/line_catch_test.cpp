#include "ferret/tether_model/line_catch.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ferret/tether_model/taut_control_options.hpp"

namespace ferret::tether {
namespace {

TEST(LineCatchLimit, TheStretchWhileTheSpoolCatchesUpPullsTheBudgetOnThatLine) {
  const LineCatchLimit c{8.0, 1500.0, 0.065, 1.8};
  // 7.5 m of line: 8 N is 8 * 7.5 / 1500 = 0.04 m of stretch, and
  // r^2 / 3.6 + 0.065 r = 0.04 gives r = 1.8 (sqrt(0.065^2 + 0.08 / 1.8) - 0.065).
  EXPECT_NEAR(c.speed_mps(7.5), 0.28010, 1e-5);
  // 2 m: 0.010667 m of stretch; r = 1.8 (sqrt(0.004225 + 0.011852) - 0.065) = 0.11123.
  EXPECT_NEAR(c.speed_mps(2.0), 0.11123, 1e-5);
  // At that speed the line indeed stretches by the budget's length, whatever the line.
  for (const double line_m : {0.5, 3.0, 15.0, 40.0}) {
    const double r = c.speed_mps(line_m);
    const double stretch_m = r * c.reaction_s + r * r / (2.0 * c.spool_acceleration_mps2);
    EXPECT_NEAR(c.axial_stiffness_n * stretch_m / line_m, c.pull_budget_n, 1e-9) << line_m;
  }
  // A longer line is softer: faster. A few cm of line is not a rigid rod.
  EXPECT_LT(c.speed_mps(5.0), c.speed_mps(10.0));
  EXPECT_EQ(c.speed_mps(0.0), c.speed_mps(0.1));
  EXPECT_GT(c.speed_mps(0.0), 0.0);
}

TEST(LineCatchLimit, OffWithoutABudgetAndInstantForAWinchWithoutLag) {
  EXPECT_FALSE(LineCatchLimit{}.on());
  EXPECT_TRUE(std::isinf(LineCatchLimit{}.speed_mps(5.0)));
  // No reaction time: only the spool's acceleration, r = sqrt(2 a x).
  const LineCatchLimit instant{8.0, 1500.0, 0.0, 2.0};
  EXPECT_NEAR(instant.speed_mps(7.5), std::sqrt(2.0 * 2.0 * 0.04), 1e-12);
}

TEST(LineCatchLimit, TheWinchsLimitComesFromItsTensionLimitGuardAndServo) {
  TautControlOptions w;
  // 10 N less the 0.5 N hanging weight and the 1.5 N guard; two 20 ms periods and the
  // servo's 25 ms; 0.9 of 2 m/s^2.
  LineCatchLimit c = LineCatchLimit::for_winch(w);
  EXPECT_DOUBLE_EQ(c.pull_budget_n, 8.0);
  EXPECT_DOUBLE_EQ(c.axial_stiffness_n, 1500.0);
  EXPECT_DOUBLE_EQ(c.reaction_s, 0.065);
  EXPECT_DOUBLE_EQ(c.spool_acceleration_mps2, 1.8);
  w.slack_estimator.tension.max_tension_n = 1.0;  // below the guard: no budget, no limit
  EXPECT_FALSE(LineCatchLimit::for_winch(w).on());
}

}  // namespace
}  // namespace ferret::tether
