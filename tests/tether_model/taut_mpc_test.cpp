#include "ferret/tether_model/taut_mpc.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ferret/tether_model/simulated_winch.hpp"

namespace ferret::tether {
namespace {

std::shared_ptr<FixedWrapTether> straight_tether() {
  return std::make_shared<FixedWrapTether>(1.0, Eigen::Vector2d::Zero());
}

TautTetherMpc::Options raw_options(int horizon = 20) {
  TautTetherMpc::Options o;
  o.horizon = horizon;
  o.control.pose_filter_gain = 1.0;  // use positions as given
  // The control law alone: the geometric slack, without the tension-fusing observer.
  o.control.slack_observer.tension_fusion = false;
  return o;
}

TetherObservation at_rest(double x_m, double released_m) {
  TetherObservation obs;
  obs.released_m = released_m;
  obs.winch_tension_n = 0.5;  // the hanging weight only
  obs.ugv.p_WG = {x_m, 0.0};
  return obs;
}

TEST(TautTetherMpc, HoldsStillWhenTheSlackIsAtItsReference) {
  TautTetherMpc mpc(raw_options(), straight_tether());
  const double ref = mpc.options().control.slack_reference_m;
  const double command = mpc.step(at_rest(3.0, 4.0 + ref));
  EXPECT_EQ(mpc.last_solution().status, QpResult::Status::kOptimal);
  EXPECT_NEAR(command, 0.0, 1e-9);
}

TEST(TautTetherMpc, HoldsTheSlackMarginTheMiniUgvAsksForUpToItsCap) {
  TautTetherMpc mpc(raw_options(), straight_tether());
  const auto& ctl = mpc.options().control;
  const double ref = ctl.slack_reference_m;
  // 4 m required; the miniUGV says its tether may be 0.3 m longer than it reports.
  TetherObservation obs = at_rest(3.0, 4.0 + ref + 0.3);
  obs.slack_margin_m = 0.3;
  EXPECT_NEAR(mpc.step(obs), 0.0, 1e-9);  // at reference + margin: hold
  mpc.reset();
  obs.released_m = 4.0 + ref;  // at the bare reference: pay out the margin
  EXPECT_GT(mpc.step(obs), 0.0);
  // A larger doubt is honoured only up to max_slack_margin_m; NaN or negative as none.
  mpc.reset();
  obs.slack_margin_m = 10.0;
  obs.released_m = 4.0 + ref + ctl.max_slack_margin_m;
  EXPECT_NEAR(mpc.step(obs), 0.0, 1e-9);
  for (const double bad : {std::nan(""), -1.0}) {
    mpc.reset();
    obs.slack_margin_m = bad;
    obs.released_m = 4.0 + ref;
    EXPECT_NEAR(mpc.step(obs), 0.0, 1e-9) << bad;
  }
}

TEST(TautTetherMpc, ReelsInSlackAndPaysOutAStretch) {
  TautTetherMpc mpc(raw_options(), straight_tether());
  EXPECT_LT(mpc.step(at_rest(3.0, 4.1)), 0.0);  // 10 cm slack
  mpc.reset();
  EXPECT_GT(mpc.step(at_rest(3.0, 3.98)), 0.0);  // 2 cm stretched
}

TEST(TautTetherMpc, PredictsTheRequiredLengthFromDesiredVelocityAndAcceleration) {
  TautTetherMpc::Options o = raw_options();
  o.acceleration_time_s = 0.1;
  TautTetherMpc mpc(o, straight_tether());
  TetherObservation obs = at_rest(2.0, 3.0);
  obs.ugv.v_WG = {0.5, 0.0};
  obs.ugv.a_WG = {1.0, 0.0};
  obs.ugv_age_s = 0.06;
  (void)mpc.step(obs);
  const Eigen::VectorXd& r = mpc.predicted_required_m();
  ASSERT_EQ(r.size(), 20);
  // t = age + (k + 1) dt; the acceleration acts for the first 0.1 s, then 0.6 m/s.
  auto expected = [](double t) {
    return t <= 0.1 ? 3.0 + 0.5 * t + 0.5 * t * t : 3.0 + 0.05 + 0.005 + 0.6 * (t - 0.1);
  };
  EXPECT_NEAR(r[0], expected(0.08), 1e-9);
  EXPECT_NEAR(r[1], expected(0.10), 1e-9);
  EXPECT_NEAR(r[19], expected(0.46), 1e-9);
}

TEST(TautTetherMpc, CommandsRampAtTheAccelerationLimitAndSaturateAtTheSpeedLimit) {
  for (const int horizon : {20, 40}) {
    TautTetherMpc mpc(raw_options(horizon), straight_tether());
    const auto& limits = mpc.options().control.limits;
    const double dt = mpc.options().control.control_period_s;
    // The miniUGV leaves at 1.5 m/s, beyond the winch's 0.6 m/s; the spool follows the command
    // exactly.
    double x = 3.0, released = 4.0, speed = 0.0, previous = 0.0;
    bool reached_limit = false;
    for (int k = 0; k < 60; ++k) {
      TetherObservation obs = at_rest(x, released);
      obs.spool_speed_mps = speed;
      obs.ugv.v_WG = {1.5, 0.0};
      const double command = mpc.step(obs);
      ASSERT_EQ(mpc.last_solution().status, QpResult::Status::kOptimal);
      EXPECT_LE(std::abs(command), limits.max_speed_mps + 1e-9);
      EXPECT_LE(std::abs(command - previous), limits.max_acceleration_mps2 * dt + 1e-9)
          << "cycle " << k;
      reached_limit = reached_limit || command > limits.max_speed_mps - 1e-9;
      previous = speed = command;
      released += command * dt;
      x += 1.5 * dt;
    }
    EXPECT_TRUE(reached_limit) << "horizon " << horizon;
  }
}

TEST(TautTetherMpc, NeverPlansPastTheTetherLength) {
  TautTetherMpc mpc(raw_options(), straight_tether());
  const double L = mpc.options().control.limits.total_length_m;
  TetherObservation obs = at_rest(L - 1.0, L - 0.05);  // required = L: wants L + reference
  obs.spool_speed_mps = 0.3;
  obs.ugv.v_WG = {0.5, 0.0};
  (void)mpc.step(obs);
  ASSERT_EQ(mpc.last_solution().status, QpResult::Status::kOptimal);
  const Eigen::VectorXd l = mpc.predicted_released_m();
  ASSERT_EQ(l.size(), 20);
  for (Eigen::Index k = 0; k < l.size(); ++k) EXPECT_LE(l[k], L + 1e-9) << "step " << k;
  EXPECT_GT(l.maxCoeff(), L - 0.01);  // and it does go up to the limit
}

TEST(TautTetherMpc, AMeasuredTensionOverridesGeometricSlack) {
  // 30 cm of geometric slack would be reeled in, but 5 N on the winch says the line
  // is caught somewhere (a snag): the MPC must not reel in against it.
  TautTetherMpc mpc(raw_options(), straight_tether());
  TetherObservation obs = at_rest(3.0, 4.3);
  EXPECT_LT(mpc.step(obs), 0.0);
  mpc.reset();
  obs.winch_tension_n = 0.5 + 5.0;
  EXPECT_GE(mpc.step(obs), 0.0);
}

TEST(TautTetherMpc, KeepsATautTetherBehindAMiniUgvDrivingAway) {
  TautTetherMpc mpc(TautTetherMpc::Options{}, straight_tether());
  SimulatedWinch::Options wo;
  wo.initial_released_m = 3.005;
  SimulatedWinch winch(wo);
  const double dt = mpc.options().control.control_period_s;
  double x = 2.0, t = 0.0;
  for (int k = 0; k < 200; ++k, t += dt) {
    TetherObservation obs = at_rest(x, winch.released_m());
    obs.t_s = t;
    obs.spool_speed_mps = winch.speed_mps();
    obs.ugv.v_WG = {0.3, 0.0};
    winch.command_velocity_mps(mpc.step(obs));
    for (int i = 0; i < 20; ++i) winch.advance(dt / 20, 0.5);
    x += 0.3 * dt;
    if (k > 100) {
      const double slack = winch.released_m() - (1.0 + x);
      EXPECT_GT(slack, -0.01) << "t = " << t;
      EXPECT_LT(slack, 0.02) << "t = " << t;
    }
  }
  EXPECT_NEAR(winch.speed_mps(), 0.3, 0.01);
}

TEST(TautTetherMpc, GivesASnagsLengthBackAtItsStoppingSpeedOnlyWhereTheRobotHasNoDoubt) {
  // 8 m out, 7.3 m required, 5 N at the winch: the observer holds the 0.727 m the
  // model is short by. Relieved, the MPC gives it back at the speed from which the spool
  // stops within 8 N on a line twice as stiff as modelled: 375 N/m on 8 m, 21.3 mm,
  // r = 1.8 (sqrt(0.065^2 + 2 * 0.021333 / 1.8) - 0.065) = 0.18381 m/s.
  const auto rate_after_a_snag = [](double slack_margin_m, bool on = true) {
    TautTetherMpc::Options o;
    o.give_back_at_stopping_speed = on;
    TautTetherMpc mpc(o, straight_tether());
    TetherObservation obs = at_rest(6.3, 8.0);
    obs.slack_margin_m = slack_margin_m;
    obs.winch_tension_n = 0.5 + 5.0;
    (void)mpc.step(obs);
    const double held = mpc.estimator().slack_observer.model_offset_m();
    EXPECT_GT(held, 0.7);
    obs.winch_tension_n = 0.5;
    obs.t_s = 0.02;
    (void)mpc.step(obs);
    const auto& observer = mpc.estimator().slack_observer;
    EXPECT_NEAR(held - observer.model_offset_m(), observer.give_back_mps() * 0.02, 1e-12);
    return observer.give_back_mps();
  };
  EXPECT_NEAR(rate_after_a_snag(0.0), 0.18381, 1e-5);
  // A doubt under that stretch is no doubt; above it the line may be round a corner
  // the robot has not seen, and the offset real: the observer's 0.1 m/s.
  EXPECT_NEAR(rate_after_a_snag(0.02), 0.18381, 1e-5);
  EXPECT_EQ(rate_after_a_snag(0.03), 0.1);
  EXPECT_EQ(rate_after_a_snag(std::nan("")), 0.1);
  EXPECT_EQ(rate_after_a_snag(0.0, false), 0.1);
}

TEST(TautTetherMpc, RejectsBadOptions) {
  TautTetherMpc::Options o;
  o.horizon = 1;
  EXPECT_THROW(TautTetherMpc(o, straight_tether()), std::invalid_argument);
  o = {};
  for (const double bad : {0.5, std::nan(""), std::numeric_limits<double>::infinity()}) {
    o.give_back_stiffness_factor = bad;
    EXPECT_THROW(TautTetherMpc(o, straight_tether()), std::invalid_argument) << bad;
  }
  EXPECT_THROW(TautTetherMpc(TautTetherMpc::Options{}, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace ferret::tether
