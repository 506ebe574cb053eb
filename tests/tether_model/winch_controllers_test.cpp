// The winch controllers' registry and each controller's own options in YAML.
#include "ferret/tether_model/winch_controllers.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/tether_model/required_length.hpp"

namespace ferret::tether {
namespace {

using ::testing::HasSubstr;

WinchControllerOptions parse(const std::string& text, WinchControllerOptions o = {}) {
  const yaml::MapReader r(yaml::load_string(text, "m.yaml"), "m.yaml", "uav.winch_control");
  read_winch_controller_options(r, o);
  return o;
}

std::string error_of(const std::string& text) {
  try {
    (void)parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::shared_ptr<const RequiredLengthModel> straight_tether() {
  return std::make_shared<FixedWrapTether>(1.0, Eigen::Vector2d::Zero());
}

TEST(WinchControllers, TheRegistryBuildsEachControllerWithItsOwnOptions) {
  EXPECT_EQ(tether_controllers().names(), (std::vector<std::string>{"mpc", "baseline"}));
  WinchControllerSetup s;
  s.control.slack_reference_m = 0.07;
  s.own.mpc.horizon = 12;
  s.own.mpc.control.slack_reference_m = 0.5;  // not used: the common options win
  s.own.baseline.kp_per_s = 3.0;
  s.model = straight_tether();
  const auto mpc = tether_controllers().make("mpc", s, "--controller");
  const auto* m = dynamic_cast<const TautTetherMpc*>(mpc.get());
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->options().horizon, 12);
  EXPECT_DOUBLE_EQ(m->options().control.slack_reference_m, 0.07);
  const auto baseline = tether_controllers().make("baseline", s, "--controller");
  const auto* b = dynamic_cast<const FeedForwardPid*>(baseline.get());
  ASSERT_NE(b, nullptr);
  EXPECT_DOUBLE_EQ(b->options().kp_per_s, 3.0);
  EXPECT_DOUBLE_EQ(b->options().control.slack_reference_m, 0.07);
  try {
    (void)tether_controllers().make("bang-bang", s, "m.yaml", "uav.winch_controller");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "m.yaml: uav.winch_controller: expected one of mpc, baseline (got bang-bang)");
  }
}

TEST(WinchControllers, FollowingGivesTheMpcTheCommonEstimationAsTheOldFactoryDid) {
  TautControlOptions control;  // velocity error off, identification off
  const WinchControllerOptions o = WinchControllerOptions::following(control);
  EXPECT_EQ(o.mpc.ugv_velocity_error.sigma_mps, 0.0);
  EXPECT_FALSE(o.mpc.ugv_response_identification.enabled);
  EXPECT_EQ(o.mpc.horizon, TautTetherMpc::Options{}.horizon);
}

TEST(WinchControllers, TheFilesKeysReachTheOptionsAndTheRestKeepTheirValues) {
  const WinchControllerOptions o = parse(
      "mpc: {horizon: 30, weight_slack: 50, use_preview: false, ugv_velocity_error_mps: 0.1}\n"
      "baseline: {kd: 0.2}\n");
  EXPECT_EQ(o.mpc.horizon, 30);
  EXPECT_DOUBLE_EQ(o.mpc.weight_slack, 50.0);
  EXPECT_FALSE(o.mpc.use_preview);
  EXPECT_DOUBLE_EQ(o.mpc.ugv_velocity_error.sigma_mps, 0.1);
  EXPECT_DOUBLE_EQ(o.mpc.weight_terminal, TautTetherMpc::Options{}.weight_terminal);
  EXPECT_DOUBLE_EQ(o.baseline.kd, 0.2);
  EXPECT_DOUBLE_EQ(o.baseline.kp_per_s, FeedForwardPid::Options{}.kp_per_s);
}

TEST(WinchControllers, TheEmitterWritesWhatTheReaderReadsBack) {
  WinchControllerOptions o;
  o.mpc.horizon = 25;
  o.mpc.prediction_dt_s = 0.03;
  o.mpc.give_back_at_stopping_speed = false;
  o.mpc.ugv_response_identification.window_s = 7.5;
  o.baseline.feedforward_gain = 0.8;
  YAML::Emitter e;
  emit_winch_controller_options(e, o);
  const std::string text = e.c_str();
  EXPECT_THAT(text, HasSubstr("horizon: 25"));
  EXPECT_THAT(text, HasSubstr("prediction_dt_s: 0.03"));
  const WinchControllerOptions back = parse(text);
  EXPECT_EQ(back.mpc.horizon, 25);
  EXPECT_DOUBLE_EQ(back.mpc.prediction_dt_s, 0.03);
  EXPECT_FALSE(back.mpc.give_back_at_stopping_speed);
  EXPECT_DOUBLE_EQ(back.mpc.ugv_response_identification.window_s, 7.5);
  EXPECT_DOUBLE_EQ(back.baseline.feedforward_gain, 0.8);
}

TEST(WinchControllers, BadValuesNameTheFileTheFieldAndTheExpectation) {
  EXPECT_THAT(error_of("mpc: {horizon: 1}\n"),
              HasSubstr("m.yaml: uav.winch_control.mpc.horizon: expected"));
  EXPECT_THAT(error_of("mpc: {horizon: 2.5}\n"), HasSubstr("an integer in [2, 200]"));
  EXPECT_THAT(error_of("mpc: {weight_slack: -1}\n"),
              HasSubstr("m.yaml: uav.winch_control.mpc.weight_slack: expected"));
  EXPECT_THAT(error_of("mpc: {use_preview: maybe}\n"),
              HasSubstr("uav.winch_control.mpc.use_preview"));
  EXPECT_THAT(error_of("mpc: {horizn: 20}\n"), HasSubstr("horizn"));
  EXPECT_THAT(error_of("baseline: {kp_per_s: .nan}\n"),
              HasSubstr("m.yaml: uav.winch_control.baseline.kp_per_s"));
  EXPECT_THAT(error_of("pid: {}\n"), HasSubstr("pid"));
  EXPECT_EQ(error_of("mpc: {horizon: 20}\n"), "");
}

}  // namespace
}  // namespace ferret::tether
