// The winch's reel-in guard: the slack a miniUGV driving off takes from a spool that is
// still reeling in, against hand-computed areas, and both controllers in a closed loop
// where a stopped miniUGV drives off while the winch takes in its slack (the mission
// pulled 22.9 N that way: docs/mission.md).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include "ferret/tether_model/simulated_winch.hpp"
#include "ferret/tether_model/taut_control_options.hpp"
#include "ferret/tether_model/winch_controllers.hpp"

namespace ferret::tether {
namespace {

ReelInGuard instant_guard(double reaction_s) {
  ReelInGuard g;
  g.ugv_speed_mps = 0.5;
  g.ugv_acceleration_mps2 = 1e9;  // at full speed at once
  g.reaction_s = reaction_s;
  g.spool_acceleration_fraction = 1.0;
  return g;
}

TEST(ReelInGuard, TheWorstLossIsTheAreaBetweenTheTwoSpeedProfiles) {
  const WinchLimits limits;  // 0.6 m/s, 2 m/s^2
  // A spool at rest behind a miniUGV at 0.5 m/s at once: 0.5^2 / (2 * 2) = 0.0625 m.
  EXPECT_NEAR(instant_guard(0.0).worst_loss_m(0.0, 0.0, limits), 0.0625, 0.003);
  // Answering 0.1 s late adds 0.5 m/s * 0.1 s.
  EXPECT_NEAR(instant_guard(0.1).worst_loss_m(0.0, 0.0, limits), 0.1125, 0.003);
  // Reeling in at 0.2 m/s behind a miniUGV accelerating at 1 m/s^2: the gap 0.2 - t
  // closes at t = 0.2 s, a triangle of 0.02 m.
  ReelInGuard g = instant_guard(0.0);
  g.ugv_acceleration_mps2 = 1.0;
  EXPECT_NEAR(g.worst_loss_m(-0.2, 0.0, limits), 0.02, 0.002);
  // A spool already paying out faster than the miniUGV can drive loses nothing.
  EXPECT_NEAR(g.worst_loss_m(0.6, 0.0, limits), 0.0, 1e-12);
  // The loss falls as the command rises.
  EXPECT_GT(g.worst_loss_m(-0.6, 0.0, limits), g.worst_loss_m(-0.3, 0.0, limits));
}

TEST(ReelInGuard, RaisesAReelInThatWouldLeaveTooLittleSlack) {
  const WinchLimits limits;
  const ReelInGuard g = instant_guard(0.05);
  // 10 cm of slack, a stopped miniUGV, the controller asking for full reel-in.
  const double u = g.limit(-0.6, 0.10, 0.0, limits, -0.6, 0.6);
  EXPECT_GT(u, -0.6);
  EXPECT_NEAR(g.worst_loss_m(u, 0.0, limits), 0.10 - g.min_slack_m, 1e-3);
  // The command's rate limit wins over the guard.
  EXPECT_DOUBLE_EQ(g.limit(-0.6, 0.10, 0.0, limits, -0.64, -0.56), -0.56);
  // A safe command, a guard that is off and a slack that is not a number are left alone.
  EXPECT_DOUBLE_EQ(g.limit(0.1, 0.10, 0.0, limits, -0.6, 0.6), 0.1);
  EXPECT_DOUBLE_EQ(g.limit(-0.05, 1.0, 0.0, limits, -0.6, 0.6), -0.05);
  EXPECT_DOUBLE_EQ(ReelInGuard{}.limit(-0.6, 0.10, 0.0, limits, -0.6, 0.6), -0.6);
  EXPECT_DOUBLE_EQ(g.limit(-0.6, std::numeric_limits<double>::quiet_NaN(), 0.0, limits, -0.6, 0.6),
                   -0.6);
  // Below min_slack_m of slack even a stop is too little: it pays out as fast as allowed.
  EXPECT_DOUBLE_EQ(g.limit(0.3, 0.0, 0.0, limits, -0.6, 0.6), 0.6);
}

// A miniUGV 3 m out on a straight tether, stopped, with `slack0` of line out too much;
// at `restart_s` it drives off at 2 m/s^2 to 0.48 m/s (the mission's tethered limits).
// Returns the peak tension over 3 s.
double peak_tension_n(const std::string& controller, bool guard, double slack0, double restart_s) {
  TautControlOptions c;
  c.slack_reference_m = 0.10;  // as the mission runs it
  if (guard) c.reel_in_guard.ugv_speed_mps = 0.48;
  auto model = std::make_shared<FixedWrapTether>(1.0, Eigen::Vector2d::Zero());
  auto ctl = make_tether_controller(controller, c, model);
  SimulatedWinch::Options wo;
  wo.initial_released_m = 4.0 + slack0;
  SimulatedWinch winch(wo);
  const TensionModel tension;
  const double dt = c.control_period_s;
  double x = 3.0, v = 0.0, peak = 0.0, pull = 0.0;
  for (double t = 0.0; t < 3.0; t += dt) {
    TetherObservation obs;
    obs.t_s = t;
    obs.released_m = winch.released_m();
    obs.spool_speed_mps = winch.speed_mps();
    obs.winch_tension_n = tension.hanging_weight_n + pull;
    obs.ugv.p_WG = {x, 0.0};
    obs.ugv.v_WG = {v, 0.0};
    winch.command_velocity_mps(ctl->step(obs));
    for (int i = 0; i < 20; ++i) {
      const double h = dt / 20;
      if (t >= restart_s) v = std::min(0.48, v + 2.0 * h);
      x += v * h;
      const double required = 1.0 + x;
      pull = tension.tension_n(required, winch.released_m() - required);
      peak = std::max(peak, pull + tension.hanging_weight_n);
      winch.advance(h, pull + tension.hanging_weight_n);
    }
  }
  return peak;
}

TEST(ReelInGuard, AMiniUgvDrivingOffWhileTheWinchReelsInNeverPullsTheLineOverItsLimit) {
  const double limit_n = TensionModel{}.max_tension_n;
  for (const char* controller : {"mpc", "baseline"}) {
    double worst_guarded = 0.0, worst_unguarded = 0.0;
    for (double restart_s = 0.0; restart_s <= 1.5; restart_s += 0.04) {
      worst_guarded = std::max(worst_guarded, peak_tension_n(controller, true, 0.5, restart_s));
      worst_unguarded =
          std::max(worst_unguarded, peak_tension_n(controller, false, 0.5, restart_s));
    }
    EXPECT_LT(worst_guarded, limit_n) << controller;
    // Without the guard the same restarts overload the line (what the mission saw).
    if (std::string(controller) == "mpc") {
      EXPECT_GT(worst_unguarded, limit_n) << controller;
    }
    RecordProperty(std::string(controller) + "_peak_guarded_n", std::to_string(worst_guarded));
    RecordProperty(std::string(controller) + "_peak_unguarded_n", std::to_string(worst_unguarded));
  }
}

}  // namespace
}  // namespace ferret::tether
