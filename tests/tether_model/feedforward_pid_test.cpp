#include "ferret/tether_model/feedforward_pid.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ferret/core/error.hpp"
#include "ferret/tether_model/winch_controllers.hpp"

namespace ferret::tether {
namespace {

FeedForwardPid::Options gains(double kp, double ki, double kd) {
  FeedForwardPid::Options o;
  o.kp_per_s = kp;
  o.ki_per_s2 = ki;
  o.kd = kd;
  o.control.pose_filter_gain = 1.0;
  o.control.slack_observer.tension_fusion = false;  // the control law on geometric slack
  o.control.limits.max_acceleration_mps2 = 100.0;   // no rate limit unless a test wants one
  o.control.slack_reference_m = 0.005;
  return o;
}

TetherObservation moving(double released_m, double vx) {
  TetherObservation obs;
  obs.released_m = released_m;
  obs.winch_tension_n = 0.5;
  obs.ugv.p_WG = {3.0, 0.0};
  obs.ugv.v_WG = {vx, 0.0};
  return obs;
}

auto tether() { return std::make_shared<FixedWrapTether>(1.0, Eigen::Vector2d::Zero()); }

TEST(FeedForwardPid, FeedForwardPlusProportionalByHand) {
  FeedForwardPid pid(gains(2.0, 0.0, 0.0), tether());
  // Required 4 m, slack 0, reference 0.005: 0.2 + 2 * 0.005.
  EXPECT_NEAR(pid.step(moving(4.0, 0.2)), 0.21, 1e-9);
}

TEST(FeedForwardPid, TheSlackMarginRaisesTheReferenceUpToItsCap) {
  FeedForwardPid pid(gains(0.5, 0.0, 0.0), tether());
  // Required 4 m, slack 0, reference 0.005 + margin 0.2: 0.2 + 0.5 * 0.205.
  TetherObservation obs = moving(4.0, 0.2);
  obs.slack_margin_m = 0.2;
  EXPECT_NEAR(pid.step(obs), 0.3025, 1e-9);
  pid.reset();
  obs.slack_margin_m = 10.0;  // capped at max_slack_margin_m (0.5): 0.2 + 0.5 * 0.505
  EXPECT_NEAR(pid.step(obs), 0.4525, 1e-9);
}

TEST(FeedForwardPid, IntegralAndDerivativeTermsByHand) {
  FeedForwardPid pid(gains(2.0, 1.0, 0.1), tether());
  EXPECT_NEAR(pid.step(moving(4.0, 0.0)), 2.0 * 0.005, 1e-9);  // no derivative on the first step
  // Error 0.005 -> 0.015: integral 0.005 * 0.02, derivative 0.01 / 0.02.
  EXPECT_NEAR(pid.step(moving(3.99, 0.0)), 2.0 * 0.015 + 1.0 * 0.0001 + 0.1 * 0.5, 1e-9);
}

TEST(FeedForwardPid, SaturatesWithoutWindingUp) {
  FeedForwardPid pid(gains(1.0, 10.0, 0.0), tether());
  const double vmax = pid.options().control.limits.max_speed_mps;
  for (int k = 0; k < 100; ++k)
    EXPECT_NEAR(pid.step(moving(3.0, 0.0)), vmax, 1e-12);  // 1 m stretched
  // The error flips sign: without wind-up the command follows at once.
  EXPECT_NEAR(pid.step(moving(4.006, 0.0)), -0.001, 1e-9);
}

TEST(FeedForwardPid, RateLimitAndBrakingDistanceToTheTetherEnd) {
  FeedForwardPid::Options o = gains(5.0, 0.0, 0.0);
  o.control.limits.max_acceleration_mps2 = 2.0;
  FeedForwardPid pid(o, tether());
  EXPECT_NEAR(pid.step(moving(3.0, 0.0)), 2.0 * 0.02, 1e-12);  // one cycle of 2 m/s^2
  FeedForwardPid near_end(gains(5.0, 0.0, 0.0), tether());
  const double L = o.control.limits.total_length_m;
  TetherObservation obs = moving(L - 0.0004, 0.5);
  obs.ugv.p_WG = {L, 0.0};
  // 0.4 mm before L at 100 m/s^2: at most sqrt(2 * 100 * 0.0004) = 0.283 m/s.
  EXPECT_NEAR(near_end.step(obs), std::sqrt(2.0 * 100.0 * 0.0004), 1e-9);
}

TEST(TetherControllerFactory, NamesBothControllers) {
  TautControlOptions o;
  EXPECT_EQ(make_tether_controller("mpc", o, tether())->name(), "mpc");
  EXPECT_EQ(make_tether_controller("baseline", o, tether())->name(), "baseline");
  EXPECT_THROW((void)make_tether_controller("bang-bang", o, tether()), InputError);
  EXPECT_EQ(tether_controller_names(), (std::vector<std::string>{"mpc", "baseline"}));
}

TEST(SlackEstimator, TensionAboveTheGuardOverridesGeometry) {
  SlackEstimator e;  // EA 1500 N, hanging 0.5 N, guard 1.5 N
  EXPECT_NEAR(e.estimate_m(5.2, 5.0, 0.5 + 1.0), 0.2, 1e-12);  // below the guard: geometry
  // 3 N pull on 5.2 m of line (1500 / 5.2 N/m) is 1.04 cm of stretch.
  EXPECT_NEAR(e.estimate_m(5.2, 5.0, 0.5 + 3.0), -0.0104, 1e-12);
  EXPECT_NEAR(e.tension.tension_n(5.0, -0.01), 3.0, 1e-12);
  EXPECT_EQ(e.tension.tension_n(5.0, 0.02), 0.0);
}

}  // namespace
}  // namespace ferret::tether
