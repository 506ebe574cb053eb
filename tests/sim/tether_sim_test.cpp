#include "ferret/sim/tether_sim.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "ferret/core/error.hpp"
#include "ferret/tether_model/taut_mpc.hpp"
#include "support/cli_runner.hpp"

namespace ferret::sim {
namespace {

using ::testing::HasSubstr;
using TautDefaults = tether::TautTetherMpc::Options;

std::string write(const test::TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir / name;
  std::ofstream(path) << text;
  return path;
}

// Expects InputError from loading `path` whose field contains `field`.
void expect_input_error(const std::string& path, const std::string& field,
                        const std::string& expected = "") {
  try {
    (void)load_tether_scenario(path);
    FAIL() << "expected InputError for " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.source().substr(0, path.size()), path);
    EXPECT_THAT(e.field(), HasSubstr(field));
    if (!expected.empty()) {
      EXPECT_THAT(e.expected(), HasSubstr(expected));
    }
  }
}

TEST(TetherTrajectory, CsvWithPositionsOnlyIsDifferentiated) {
  test::TempDir dir;
  // x = t^2: central differences give v(1) = (4 - 0) / 2 = 2 and v(2) = (9 - 1) / 2 = 4.
  const auto path =
      write(dir, "t.csv", "# a comment\nt,x,y,yaw\n0,0,1,0\n1,1,1,0\n\n2,4,1,0\n3,9,1,0\n");
  const auto s = load_tether_scenario(path);
  ASSERT_EQ(s.samples.size(), 4u);
  EXPECT_EQ(s.name, "t");
  EXPECT_DOUBLE_EQ(s.samples[1].v_WG.x(), 2.0);
  EXPECT_DOUBLE_EQ(s.samples[2].v_WG.x(), 4.0);
  EXPECT_DOUBLE_EQ(s.samples[0].v_WG.x(), 1.0);  // one-sided at the ends
  EXPECT_DOUBLE_EQ(s.samples[1].a_WG.x(), (4.0 - 1.0) / 2.0);
  EXPECT_DOUBLE_EQ(s.samples[1].p_WG.y(), 1.0);
  // Interpolation between samples.
  EXPECT_DOUBLE_EQ(s.at(1.5).p_WG.x(), 2.5);
  EXPECT_DOUBLE_EQ(s.at(-1.0).p_WG.x(), 0.0);
}

TEST(TetherTrajectory, CsvWithDesiredVelocityAndAcceleration) {
  test::TempDir dir;
  const auto path = write(dir, "t.csv",
                          "t, x, y, yaw, vx, vy, ax, "
                          "ay\r\n0,1,2,0.5,0.1,0.2,0.3,0.4\r\n0.5,1.05,2.1,0.5,0.1,0.2,0,0\r\n");
  const auto s = load_tether_scenario(path);
  ASSERT_EQ(s.samples.size(), 2u);
  EXPECT_DOUBLE_EQ(s.samples[0].yaw_rad, 0.5);
  EXPECT_DOUBLE_EQ(s.samples[0].v_WG.y(), 0.2);
  EXPECT_DOUBLE_EQ(s.samples[0].a_WG.y(), 0.4);
}

TEST(TetherTrajectory, BrokenCsvFilesNameLineAndField) {
  test::TempDir dir;
  expect_input_error(write(dir, "a.csv", "time,x,y,yaw\n0,0,0,0\n"), "line 1", "header");
  expect_input_error(write(dir, "b.csv", "t,x,y,yaw\n0,0,0,0\n1,0,north,0\n"), "line 3, field 'y'",
                     "finite number");
  expect_input_error(write(dir, "c.csv", "t,x,y,yaw\n0,0,0,0\n1,0,0\n"), "line 3",
                     "4 comma-separated");
  expect_input_error(write(dir, "d.csv", "t,x,y,yaw\n0,0,0,0\n0,1,0,0\n"), "line 3, field 't'",
                     "greater");
  expect_input_error(write(dir, "e.csv", "t,x,y,yaw\n0,0,0,0\n"), "", "at least two");
  expect_input_error(write(dir, "f.csv", ""), "", "header");
  expect_input_error(write(dir, "g.csv", "t,x,y,yaw\n0,0,0,0\n1,inf,0,0\n"), "line 3, field 'x'");
  expect_input_error(write(dir, "h.txt", "t,x,y,yaw\n"), "", ".csv");
  expect_input_error(dir / "missing.csv", "", "existing");
}

TEST(TetherTrajectory, YamlWithWrapPointsSnagsAndAScript) {
  test::TempDir dir;
  const auto path = write(dir, "s.yaml", R"(name: corner
entry_xy_m: [0.5, 0]
wrap_points:
  - {xy_m: [2, 1], side: left}
  - {xy_m: [3, 1], side: right}
  - {xy_m: [4, 1]}
snags: [{wrap_point: 1, start_s: 2, duration_s: 1.5}]
script: {waypoints_xy_m: [[0, 0], [2, 0]], cruise_mps: 0.5, accel_mps2: 1.0}
)");
  const auto s = load_tether_scenario(path);
  EXPECT_EQ(s.name, "corner");
  EXPECT_DOUBLE_EQ(s.p_WE.x(), 0.5);
  ASSERT_EQ(s.wrap_points.size(), 3u);
  EXPECT_EQ(s.wrap_points[0].side, 1);
  EXPECT_EQ(s.wrap_points[1].side, -1);
  EXPECT_EQ(s.wrap_points[2].side, 0);
  ASSERT_EQ(s.snags.size(), 1u);
  EXPECT_EQ(s.snags[0].wrap_point, 1u);
  EXPECT_DOUBLE_EQ(s.snags[0].duration_s, 1.5);
  EXPECT_NEAR(s.end_s(), 4.5, 1e-9);  // see ScriptedTrajectory
  EXPECT_DOUBLE_EQ(s.samples.back().p_WG.x(), 2.0);
}

TEST(TetherTrajectory, YamlSamplesInlineAndFromACsvBesideIt) {
  test::TempDir dir;
  write(dir, "pts.csv", "t,x,y,yaw\n0,1,0,0\n1,2,0,0\n");
  const auto a = load_tether_scenario(write(dir, "a.yaml", "samples_csv: pts.csv\n"));
  EXPECT_EQ(a.samples.size(), 2u);
  EXPECT_DOUBLE_EQ(a.samples[0].v_WG.x(), 1.0);
  const auto b =
      load_tether_scenario(write(dir, "b.yaml", "samples: [[0, 1, 0, 0], [2, 1, 1, 0]]\n"));
  EXPECT_DOUBLE_EQ(b.samples[1].v_WG.y(), 0.5);
}

TEST(TetherTrajectory, BrokenYamlFilesNameTheField) {
  test::TempDir dir;
  expect_input_error(
      write(dir, "a.yaml",
            "samples: [[0, 1, 0, 0], [1, 1, 0, 0]]\nwrap_points: [{xy_m: [1, 1], side: up}]\n"),
      "wrap_points[0].side", "left, right or always");
  expect_input_error(write(dir, "b.yaml",
                           "samples: [[0, 1, 0, 0], [1, 1, 0, 0]]\nsnags: [{wrap_point: 0, "
                           "start_s: 1, duration_s: 1}]\n"),
                     "snags[0].wrap_point", "index into wrap_points");
  expect_input_error(write(dir, "c.yaml", "samples: [[0, 1, 0, 0], [1, 1, 0]]\n"), "samples[1]");
  expect_input_error(
      write(dir, "d.yaml", "samples: [[0, 1, 0, 0], [1, 1, 0, 0]]\nsamples_csv: x.csv\n"),
      "samples", "exactly one");
  expect_input_error(
      write(dir, "e.yaml",
            "script: {waypoints_xy_m: [[0, 0], [1, 0]], cruise_mps: -1, accel_mps2: 1}\n"),
      "script.cruise_mps");
  expect_input_error(write(dir, "f.yaml", "samples: [[0, 1, 0, 0], [1, 1, 0, 0]]\nspeed: 3\n"),
                     "speed");
  // A missing CSV is named itself.
  write(dir, "g.yaml", "samples_csv: nowhere.csv\n");
  expect_input_error(dir / "nowhere.csv", "", "existing");
  EXPECT_THROW((void)load_tether_scenario(dir / "g.yaml"), InputError);
}

TEST(TetherRunConfig, YamlOverridesTheDefaultsAndRejectsUnknownKeys) {
  test::TempDir dir;
  auto config = TetherRunConfig::for_tether(12.0, 1.5);
  EXPECT_EQ(config.mpc.control.limits.total_length_m, 12.0);

  auto observer = TetherRunConfig::for_tether(12.0, 1.5);
  EXPECT_TRUE(observer.mpc.control.slack_observer.tension_fusion);
  EXPECT_EQ(observer.sim.ugv_preview_s, 0.0);
  apply_tether_run_config(
      write(dir, "o.yaml",
            "control: {tension_fusion: false, observer_pose_noise_m: 0.02, "
            "servo_time_constant_s: 0.01, observer_model_offset_decay_mps: 0.3}\n"
            "mpc: {use_preview: false, rate_penalty_about_tracking_command: false, "
            "give_back_at_stopping_speed: false, give_back_stiffness_factor: 3}\n"
            "baseline: {use_preview: true}\n"
            "sim: {ugv_preview_s: 0.4, ugv_preview_step_s: 0.1}\n"),
      observer);
  EXPECT_FALSE(observer.baseline.control.slack_observer.tension_fusion);
  EXPECT_EQ(observer.mpc.control.slack_observer.pose_noise_m, 0.02);
  EXPECT_EQ(observer.mpc.control.limits.velocity_time_constant_s, 0.01);
  EXPECT_FALSE(observer.mpc.use_preview);
  EXPECT_FALSE(observer.mpc.rate_penalty_about_tracking_command);
  EXPECT_FALSE(observer.mpc.give_back_at_stopping_speed);
  EXPECT_EQ(observer.mpc.give_back_stiffness_factor, 3.0);
  EXPECT_EQ(observer.baseline.control.slack_observer.model_offset_decay_mps, 0.3);
  EXPECT_EQ(observer.mpc.control.slack_observer.model_offset_decay_mps, 0.3);
  EXPECT_TRUE(observer.baseline.use_preview);
  EXPECT_EQ(observer.sim.ugv_preview_s, 0.4);
  EXPECT_EQ(observer.sim.ugv_preview_step_s, 0.1);
  apply_tether_run_config(
      write(dir, "c.yaml",
            R"(control: {slack_reference_m: 0.01, max_speed_mps: 0.8, ugv_velocity_lag_s: 0.1}
mpc: {horizon: 30, weight_slack: 50, weight_soft_linear: 0, weight_soft_quadratic: 500}
baseline: {kp_per_s: 4, ki_per_s2: 2}
sim: {link_latency_s: 0.1, pose_noise_m: 0.0, ugv_velocity_lag_s: 0.15, ugv_slip_noise_mps: 0.02,
      ugv_tracking_time_s: 2}
)"),
      config);
  EXPECT_EQ(config.mpc.horizon, 30);
  EXPECT_EQ(config.mpc.weight_slack, 50.0);
  EXPECT_EQ(config.mpc.weight_command_rate, TautDefaults().weight_command_rate);
  EXPECT_EQ(config.mpc.soft_linear_weight, 0.0);
  EXPECT_EQ(config.mpc.soft_quadratic_weight, 500.0);
  EXPECT_EQ(config.baseline.kp_per_s, 4.0);
  EXPECT_EQ(config.baseline.control.slack_reference_m, 0.01);
  EXPECT_EQ(config.mpc.control.limits.max_speed_mps, 0.8);
  EXPECT_EQ(config.sim.winch.max_speed_mps, 0.8);  // the simulated servo gets the same limit
  EXPECT_EQ(config.sim.link_latency_s, 0.1);
  EXPECT_EQ(config.sim.pose_noise_m, 0.0);
  EXPECT_EQ(config.sim.ugv_velocity_lag_s, 0.15);
  EXPECT_EQ(config.sim.ugv_slip_noise_mps, 0.02);
  EXPECT_EQ(config.sim.ugv_slip_time_s, 0.5);
  EXPECT_EQ(config.sim.ugv_tracking_time_s, 2.0);
  EXPECT_EQ(config.mpc.control.ugv_velocity_lag_s, 0.1);
  EXPECT_EQ(config.baseline.control.ugv_velocity_lag_s, 0.1);
  EXPECT_EQ(config.mpc.control.limits.total_length_m, 12.0);
  // The MPC's velocity-error filter: on by default, its own keys, the baseline's off.
  EXPECT_GT(config.mpc.ugv_velocity_error.sigma_mps, 0.0);
  EXPECT_EQ(config.baseline.control.ugv_velocity_error.sigma_mps, 0.0);
  apply_tether_run_config(
      write(dir, "e.yaml",
            "mpc: {ugv_velocity_error_mps: 0.2, ugv_velocity_error_time_s: 1.5, "
            "ugv_velocity_error_window_s: 2, ugv_velocity_error_prior_log_odds: 0}\n"),
      config);
  EXPECT_EQ(config.mpc.ugv_velocity_error.sigma_mps, 0.2);
  EXPECT_EQ(config.mpc.ugv_velocity_error.time_s, 1.5);
  EXPECT_EQ(config.mpc.ugv_velocity_error.window_s, 2.0);
  EXPECT_EQ(config.mpc.ugv_velocity_error.prior_log_odds, 0.0);
  EXPECT_EQ(config.mpc.horizon, 30);  // the earlier file's settings stay
  // The response identification: on for the MPC by default, off for the baseline
  // unless the control section asks; its keys and the path follower's model.
  EXPECT_TRUE(config.mpc.ugv_response_identification.enabled);
  EXPECT_FALSE(config.baseline.control.ugv_response_identification.enabled);
  apply_tether_run_config(
      write(dir, "id.yaml",
            "mpc: {identify_ugv_response: false, ugv_response_window_s: 5, "
            "ugv_response_prior_log_odds: 2, ugv_velocity_error_prior_log_odds_with_lag: 1.5, "
            "ugv_velocity_error_long_window_s: 8}\n"
            "control: {ugv_tracking_time_s: 0.7, identify_ugv_response: true}\n"),
      config);
  EXPECT_FALSE(config.mpc.ugv_response_identification.enabled);
  EXPECT_EQ(config.mpc.ugv_response_identification.window_s, 5.0);
  EXPECT_EQ(config.mpc.ugv_response_identification.prior_log_odds, 2.0);
  EXPECT_EQ(config.mpc.ugv_velocity_error.prior_log_odds_with_lag, 1.5);
  EXPECT_EQ(config.mpc.ugv_velocity_error.long_window_s, 8.0);
  EXPECT_EQ(config.baseline.control.ugv_tracking_time_s, 0.7);
  EXPECT_TRUE(config.baseline.control.ugv_response_identification.enabled);

  auto check = [&](const std::string& text, const std::string& field) {
    const auto path = write(dir, "bad.yaml", text);
    try {
      apply_tether_run_config(path, config);
      FAIL() << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), field) << text;
    }
  };
  check("mpc: {horizon: 1}\n", "mpc.horizon");
  check("mpc: {horizon: 20.5}\n", "mpc.horizon");
  check("baseline: {kp: 3}\n", "baseline.kp");
  check("control: {pose_filter_gain: 0}\n", "control.pose_filter_gain");
  check("winch: {}\n", "winch");
  check("mpc: {weight_soft_quadratic: 0}\n", "mpc.weight_soft_quadratic");
  check("mpc: {weight_soft_linear: -1}\n", "mpc.weight_soft_linear");
  check("sim: {ugv_slip_time_s: 0}\n", "sim.ugv_slip_time_s");
  check("control: {tension_fusion: 3}\n", "control.tension_fusion");
  check("control: {observer_tension_noise_n: 0}\n", "control.observer_tension_noise_n");
  check("sim: {ugv_preview_step_s: 0}\n", "sim.ugv_preview_step_s");
  check("mpc: {use_preview: maybe}\n", "mpc.use_preview");
  check("mpc: {rate_penalty_about_tracking_command: 2}\n",
        "mpc.rate_penalty_about_tracking_command");
  check("mpc: {give_back_at_stopping_speed: soon}\n", "mpc.give_back_at_stopping_speed");
  for (const char* bad : {".nan", "0.5", ".inf"})
    check(std::string("mpc: {give_back_stiffness_factor: ") + bad + "}\n",
          "mpc.give_back_stiffness_factor");
  for (const char* bad : {".nan", "-0.1", ".inf", "11"})
    check(std::string("control: {observer_model_offset_decay_mps: ") + bad + "}\n",
          "control.observer_model_offset_decay_mps");
  for (const char* key : {"ugv_velocity_error_mps", "ugv_velocity_error_time_s",
                          "ugv_velocity_error_window_s", "ugv_velocity_error_prior_log_odds"}) {
    for (const char* bad : {".nan", "-0.1", ".inf", "fast"})
      check(std::string("mpc: {") + key + ": " + bad + "}\n", std::string("mpc.") + key);
  }
  for (const char* key :
       {"ugv_response_window_s", "ugv_response_prior_log_odds",
        "ugv_velocity_error_prior_log_odds_with_lag", "ugv_velocity_error_long_window_s"}) {
    for (const char* bad : {".nan", "-0.1", ".inf", "fast"})
      check(std::string("mpc: {") + key + ": " + bad + "}\n", std::string("mpc.") + key);
  }
  check("mpc: {identify_ugv_response: maybe}\n", "mpc.identify_ugv_response");
  check("control: {identify_ugv_response: 2}\n", "control.identify_ugv_response");
  check("control: {ugv_tracking_time_s: -1}\n", "control.ugv_tracking_time_s");
  check("mpc: {ugv_response_window_s: 0}\n", "mpc.ugv_response_window_s");
  check("mpc: {ugv_velocity_error_time_s: 0}\n", "mpc.ugv_velocity_error_time_s");
  check("mpc: {ugv_velocity_error_window_s: 0}\n", "mpc.ugv_velocity_error_window_s");
}

TEST(TetherRunConfig, TheShippedDiagnosticConfigsLoad) {
  int count = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(FERRET_SOURCE_DIR) + "/examples/tether")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    auto config = TetherRunConfig::for_tether(15.0, 1.0);
    EXPECT_NO_THROW(apply_tether_run_config(entry.path(), config));
    ++count;
  }
  EXPECT_GE(count, 5);
  auto config = TetherRunConfig::for_tether(15.0, 1.0);
  apply_tether_run_config(
      std::string(FERRET_SOURCE_DIR) + "/examples/tether/less_obedient_ugv_lag_model.yaml", config);
  EXPECT_EQ(config.sim.ugv_velocity_lag_s, 0.15);
  EXPECT_EQ(config.baseline.control.ugv_velocity_lag_s, 0.15);
}

TEST(ScriptedTrajectory, TrapezoidalSegmentsByHand) {
  // 2 m at 0.5 m/s and 1 m/s^2: 0.5 s up (0.125 m), 1.75 m in 3.5 s, 0.5 s down; 4.5 s in all.
  const auto s = scripted_trajectory({{0, 0}, {2, 0}}, 0.5, 1.0, 0.0, 0.05);
  ASSERT_NEAR(s.back().t_s, 4.5, 1e-9);
  EXPECT_NEAR(s[5].p_WG.x(), 0.5 * 0.25 * 0.25, 1e-12);  // t = 0.25
  EXPECT_NEAR(s[5].a_WG.x(), 1.0, 1e-12);
  EXPECT_NEAR(s[40].p_WG.x(), 0.125 + 0.5 * 1.5, 1e-12);  // t = 2.0
  EXPECT_NEAR(s[40].v_WG.x(), 0.5, 1e-12);
  EXPECT_NEAR(s.back().p_WG.x(), 2.0, 1e-12);
  EXPECT_NEAR(s.back().v_WG.norm(), 0.0, 1e-12);
  // A short segment is a triangle: 0.1 m at 1 m/s^2 peaks at sqrt(0.1) m/s.
  const auto t = scripted_trajectory({{0, 0}, {0, 0.1}}, 1.0, 1.0, 0.5, 0.01);
  EXPECT_NEAR(t.back().t_s, 2.0 * std::sqrt(0.1) + 0.5, 0.01);
  EXPECT_DOUBLE_EQ(t.back().yaw_rad, std::atan2(1.0, 0.0));
}

TEST(TetherScenario, TheBuiltInDefaultIsTheShippedDefaultYaml) {
  const auto builtin = default_tether_scenario();
  const auto shipped =
      load_tether_scenario(std::string(FERRET_SOURCE_DIR) + "/examples/trajectories/default.yaml");
  ASSERT_EQ(builtin.samples.size(), shipped.samples.size());
  ASSERT_EQ(builtin.wrap_points.size(), shipped.wrap_points.size());
  for (std::size_t i = 0; i < builtin.wrap_points.size(); ++i)
    EXPECT_EQ(builtin.wrap_points[i].p_W, shipped.wrap_points[i].p_W);
  for (std::size_t i = 0; i < builtin.samples.size(); i += 97)
    EXPECT_EQ(builtin.samples[i].p_WG, shipped.samples[i].p_WG) << i;
}

// Holds the spool at a fixed speed: exposes the tether model without a controller.
class ConstantSpool final : public tether::TetherController {
 public:
  explicit ConstantSpool(double speed) : speed_(speed) {}
  std::string_view name() const override { return "constant"; }
  void reset() override {}
  double step(const tether::TetherObservation&) override { return speed_; }

 private:
  double speed_;
};

TetherScenario straight_out(double from_x, double to_x, double duration_s) {
  TetherScenario s;
  s.name = "straight";
  for (int i = 0; i <= 10; ++i) {
    TrajectorySample p;
    p.t_s = duration_s * i / 10.0;
    p.p_WG = {from_x + (to_x - from_x) * i / 10.0, 0.0};
    s.samples.push_back(p);
  }
  differentiate_trajectory(s.samples);
  return s;
}

TEST(TetherSim, ElasticTensionWhenTheMiniUgvPullsAHeldTether) {
  const auto scn = straight_out(3.0, 3.1, 2.0);
  auto options = TetherSimOptions::for_tether(15.0, 1.0);
  ConstantSpool hold(0.0);
  const auto r = run_tether_sim(scn, options, hold);
  const auto& last = r.log.back();
  // The spool barely moves (its I term holds); the stretch is ~0.1 - 0.005 m on ~4 m.
  EXPECT_LT(last.slack_m, -0.05);
  EXPECT_NEAR(last.ugv_tension_n, 1500.0 / last.released_m * -last.slack_m, 1e-9);
  EXPECT_DOUBLE_EQ(last.winch_tension_n, last.ugv_tension_n);
  EXPECT_GE(r.metrics.over_tension_events, 1);
  EXPECT_GT(r.metrics.over_tension_time_s, 0.0);
  EXPECT_NEAR(r.metrics.min_slack_m, last.slack_m, 0.01);
}

TEST(TetherSim, ASnagLoadsTheWinchSideOnlyAndReleases) {
  // The miniUGV drives from (3, 0) back towards a wrap point at (2, 0) while the
  // winch reels in; the line is pinned at the wrap point from t = 1 s to 3 s.
  TetherScenario scn = straight_out(3.0, 2.5, 4.0);
  scn.wrap_points = {{{2.0, 0.0}, 0}};
  scn.snags = {{0, 1.0, 2.0}};
  auto options = TetherSimOptions::for_tether(15.0, 1.0);
  ConstantSpool reel_in(-0.1);
  const auto r = run_tether_sim(scn, options, reel_in);
  bool saw_snag = false;
  for (const auto& s : r.log) {
    if (!s.snagged) continue;
    saw_snag = true;
    EXPECT_EQ(s.ugv_tension_n, 0.0) << "t = " << s.t_s;  // the miniUGV's side goes slack
  }
  EXPECT_TRUE(saw_snag);
  // Reeling in 0.1 m/s against a fixed 3 m of line: ~500 N/m of stretch rate until the
  // servo stalls at its 40 N force limit.
  const auto during =
      *std::find_if(r.log.rbegin(), r.log.rend(), [](const auto& s) { return s.snagged; });
  EXPECT_GT(during.winch_tension_n, 35.0);
  EXPECT_LT(r.metrics.max_tension_n, 41.0);
  EXPECT_NEAR(during.speed_mps, 0.0, 0.01);
  const auto& after = r.log.back();
  EXPECT_FALSE(after.snagged);
  EXPECT_DOUBLE_EQ(after.winch_tension_n, after.ugv_tension_n);
}

// The same snag with the spool held: the line is pinned at (2, 0) from t = 1 s, the
// miniUGV at x = 3 - 0.125 = 2.875 m, the tether (l_0 = 1 m, straight to the corner,
// on to the robot) needs 3.875 m of the 4 m released: 0.125 m slack, shared by length,
// 3 / 3.875 of it on the winch's 3 m side. While pinned the robot drives on to x =
// 2.625 m, the total slack grows to 0.375 m, but what the winch can take in stays
// 0.125 * 3 / 3.875 = 96.8 mm: the rest lies beyond the pin.
TEST(TetherSim, ReachableSlackStopsAtThePinnedCorner) {
  TetherScenario scn = straight_out(3.0, 2.5, 4.0);
  scn.wrap_points = {{{2.0, 0.0}, 0}};
  scn.snags = {{0, 1.0, 2.0}};
  auto options = TetherSimOptions::for_tether(15.0, 1.0);
  ConstantSpool hold(0.0);
  const auto r = run_tether_sim(scn, options, hold);
  int pinned = 0;
  double last_pinned_slack = 0.0;
  for (const auto& s : r.log) {
    if (s.snagged) {
      ++pinned;
      EXPECT_NEAR(s.reachable_slack_m, 0.125 * 3.0 / 3.875, 1e-3) << "t = " << s.t_s;
      last_pinned_slack = s.slack_m;
    } else {
      EXPECT_EQ(s.reachable_slack_m, s.slack_m) << "t = " << s.t_s;
    }
  }
  EXPECT_NEAR(pinned, 100, 1);  // 2 s at 50 Hz
  EXPECT_NEAR(last_pinned_slack, 0.375, 2e-3);
  // After the pin the robot drives on with the spool held: all of that slack counts.
  EXPECT_LT(r.metrics.reachable_slack_rms_m, r.metrics.slack_rms_m - 1e-3);
  // Without the snag the two figures are one.
  scn.snags.clear();
  const auto free = run_tether_sim(scn, options, hold);
  EXPECT_EQ(free.metrics.reachable_slack_rms_m, free.metrics.slack_rms_m);
}

TEST(TetherSim, DeterministicForASeed) {
  const auto scn = default_tether_scenario();
  auto options = TetherSimOptions::for_tether(15.0, 1.0);
  auto model = std::make_shared<tether::FixedWrapTether>(1.0, scn.p_WE, scn.wrap_points);
  auto run_with = [&](std::uint64_t seed) {
    options.seed = seed;
    tether::TautTetherMpc mpc(tether::TautTetherMpc::Options{}, model);
    return run_tether_sim(scn, options, mpc);
  };
  const auto a = run_with(7), b = run_with(7), c = run_with(8);
  ASSERT_EQ(a.log.size(), b.log.size());
  for (std::size_t i = 0; i < a.log.size(); i += 50)
    EXPECT_EQ(a.log[i].released_m, b.log[i].released_m);
  EXPECT_EQ(a.metrics.slack_rms_m, b.metrics.slack_rms_m);
  EXPECT_NE(a.metrics.slack_rms_m, c.metrics.slack_rms_m);
}

TEST(TetherSim, TheMpcMeetsTheTargetsOnEveryShippedTrajectory) {
  for (const char* file :
       {"default.yaml", "corner_snag.yaml", "fast_back_and_forth.csv", "reach_limit.csv"}) {
    SCOPED_TRACE(file);
    const auto scn =
        load_tether_scenario(std::string(FERRET_SOURCE_DIR) + "/examples/trajectories/" + file);
    const auto options = TetherSimOptions::for_tether(15.0, 1.0);
    auto model = std::make_shared<tether::FixedWrapTether>(1.0, scn.p_WE, scn.wrap_points);
    tether::TautTetherMpc::Options mpc_options;
    mpc_options.control = options.control;
    tether::TautTetherMpc mpc(mpc_options, model);
    const auto r = run_tether_sim(scn, options, mpc);
    EXPECT_EQ(r.metrics.over_tension_events, 0);
    EXPECT_EQ(r.metrics.released_over_limit, 0);
    EXPECT_LE(r.metrics.max_released_m, 15.0);
    EXPECT_GT(r.metrics.min_slack_m, -0.03);
  }
}

TEST(ActualUgvMotion, AnObedientRobotIsItsDesiredMotion) {
  const auto scn = default_tether_scenario();
  const auto actual = actual_ugv_motion(scn, {0.0, 0.0, 0.5, 1.0}, 0.001, 1);
  ASSERT_EQ(actual.size(), static_cast<std::size_t>(std::lround(scn.end_s() / 0.001)) + 1);
  for (std::size_t i = 0; i < actual.size(); i += 997)
    EXPECT_NEAR((actual[i].p_WG - scn.at(actual[i].t_s).p_WG).norm(), 0.0, 1e-6) << i;
}

TEST(ActualUgvMotion, AVelocityLagTrailsByLagTimesSpeedAndCatchesUp) {
  // One leg of 4 m at 0.4 m/s (1 m/s^2): cruising, a first-order velocity lag tau
  // without path tracking trails the desired position by tau * v = 0.2 * 0.4 =
  // 0.08 m; path tracking (time constant T) removes the trail; at rest it arrives.
  TetherScenario scn;
  scn.samples = scripted_trajectory({{0.0, 0.0}, {4.0, 0.0}}, 0.4, 1.0, 3.0);
  const auto open_loop = actual_ugv_motion(scn, {0.2, 0.0, 0.5, 0.0}, 0.001, 1);
  const auto tracking = actual_ugv_motion(scn, {0.2, 0.0, 0.5, 0.5}, 0.001, 1);
  const auto index = [](double t) { return static_cast<std::size_t>(std::lround(t / 0.001)); };
  EXPECT_NEAR(scn.at(5.0).p_WG.x() - open_loop[index(5.0)].p_WG.x(), 0.08,
              3e-4);  // +- half a 1 ms step
  EXPECT_NEAR(open_loop[index(5.0)].v_WG.x(), 0.4, 1e-6);
  EXPECT_NEAR(scn.at(5.0).p_WG.x() - tracking[index(5.0)].p_WG.x(), 0.0, 1e-4);
  EXPECT_GT(scn.at(0.5).p_WG.x() - tracking[index(0.5)].p_WG.x(), 0.01);  // lags while accelerating
  for (const auto* actual : {&open_loop, &tracking}) {
    EXPECT_NEAR(actual->back().p_WG.x(), 4.0, 1e-3);
    EXPECT_NEAR(actual->back().p_WG.y(), 0.0, 1e-12);
  }
}

TEST(ActualUgvMotion, SlipIsARandomVelocityOfTheGivenSpreadAndSeeded) {
  TetherScenario scn;
  scn.samples.resize(2);  // standing still at (1, 0) for 400 s
  scn.samples[0].p_WG = scn.samples[1].p_WG = Eigen::Vector2d(1.0, 0.0);
  scn.samples[1].t_s = 400.0;
  const UgvObedience slipping{0.0, 0.05, 0.5, 0.0};
  const auto a = actual_ugv_motion(scn, slipping, 0.01, 3);
  const auto b = actual_ugv_motion(scn, slipping, 0.01, 3);
  const auto c = actual_ugv_motion(scn, slipping, 0.01, 4);
  double sum_sq = 0.0;
  for (const auto& s : a) sum_sq += s.v_WG.squaredNorm();
  EXPECT_NEAR(std::sqrt(sum_sq / (2.0 * static_cast<double>(a.size()))), 0.05, 0.005);
  EXPECT_EQ(a.back().p_WG, b.back().p_WG);
  EXPECT_NE(a.back().p_WG, c.back().p_WG);
  // Position is the integral of the slip velocity (trapezoidal).
  double x = a.front().p_WG.x();
  for (std::size_t i = 1; i < a.size(); ++i) x += 0.5 * (a[i - 1].v_WG.x() + a[i].v_WG.x()) * 0.01;
  EXPECT_NEAR(x, a.back().p_WG.x(), 1e-9);
  EXPECT_GT(std::abs(x - 1.0), 1e-3);  // it wandered off
  // Path tracking (1 s) holds it near its place: the offset stays bounded, with a
  // spread of about slip * sqrt(tc T / (tc + T)) = 0.05 * 0.58 = 0.029 m per axis.
  const auto held = actual_ugv_motion(scn, {0.0, 0.05, 0.5, 1.0}, 0.01, 3);
  double offset_sq = 0.0;
  for (const auto& s : held) offset_sq += (s.p_WG - Eigen::Vector2d(1.0, 0.0)).squaredNorm();
  EXPECT_NEAR(std::sqrt(offset_sq / (2.0 * static_cast<double>(held.size()))), 0.029, 0.008);
}

TetherScenario fast_back_and_forth() {
  return load_tether_scenario(std::string(FERRET_SOURCE_DIR) +
                              "/examples/trajectories/fast_back_and_forth.csv");
}

// An exact penalty on slack < 0 sits where the pose noise crosses the bound every
// cycle: the MPC then pays out harder for a noisy "stretched" than it reels in for
// a noisy "slack", and the line runs loose by about a millimetre on average. The
// default (no linear term on that side) is unbiased and tighter, at the same
// minimum slack and without over-tension.
TEST(TetherSim, NoExactPenaltyOnStretchKeepsTheMpcUnbiased) {
  const auto scn = fast_back_and_forth();
  auto model = std::make_shared<tether::FixedWrapTether>(1.0, scn.p_WE, scn.wrap_points);
  auto run = [&](double stretch_linear_weight, double quadratic_weight) {
    auto config = TetherRunConfig::for_tether(15.0, 1.0);
    config.mpc.control.slack_observer.tension_fusion = false;  // the noisy geometric estimate
    config.mpc.stretch_linear_weight = stretch_linear_weight;
    config.mpc.soft_quadratic_weight = quadratic_weight;
    tether::TautTetherMpc mpc(config.mpc, model);
    const auto r = run_tether_sim(scn, config.sim, mpc);
    double mean = 0.0;
    for (const auto& row : r.log) mean += row.slack_m;
    return std::make_pair(r.metrics, mean / static_cast<double>(r.log.size()));
  };
  const auto [exact, exact_mean] = run(2000.0, 20000.0);
  const auto [quadratic, quadratic_mean] = run(0.0, 2000.0);
  EXPECT_GT(exact_mean, 0.0008);
  EXPECT_LT(std::abs(quadratic_mean), 0.0006);
  EXPECT_LT(quadratic.slack_rms_m, 0.85 * exact.slack_rms_m);
  EXPECT_EQ(quadratic.over_tension_events, 0);
  EXPECT_GT(quadratic.min_slack_m, exact.min_slack_m - 0.002);
}

// The MPC's command-rate penalty damps its corrections, not its feed-forward. Penalising
// the command's change alone, the MPC handed the miniUGV's exact plan (a preview, no pose
// noise) smoothed the known future symmetrically: its slack followed the required length's
// acceleration (0.7 ms^2 of it) and the preview made it worse than no preview (0.80 against
// 0.51 mm on the fast trajectory). About the tracking command, the preview helps.
TEST(TetherSim, ThePlanPreviewHelpsTheMpcItsRatePenaltyDampsOnlyCorrections) {
  const auto scn = fast_back_and_forth();
  auto model = std::make_shared<tether::FixedWrapTether>(1.0, scn.p_WE, scn.wrap_points);
  struct Run {
    double rms_m, acceleration_coefficient_s2;
  };
  auto run = [&](bool preview, bool about_tracking_command) {
    auto config = TetherRunConfig::for_tether(15.0, 1.0);
    config.sim.pose_noise_m = 0.0;
    config.sim.ugv_preview_s = preview ? 0.5 : 0.0;
    config.mpc.rate_penalty_about_tracking_command = about_tracking_command;
    tether::TautTetherMpc mpc(config.mpc, model);
    const auto r = run_tether_sim(scn, config.sim, mpc);
    // Least squares of the slack on the required length's acceleration (and a constant)
    // after the first 2 s, the acceleration by central differences of the logged length.
    double sa = 0, saa = 0, ss = 0, ssa = 0, n = 0;
    const auto& log = r.log;
    for (std::size_t i = 1; i + 1 < log.size(); ++i) {
      if (log[i].t_s < 2.0) continue;
      const double h = log[i + 1].t_s - log[i].t_s;
      const double a =
          (log[i + 1].required_m - 2.0 * log[i].required_m + log[i - 1].required_m) / (h * h);
      sa += a, saa += a * a, ss += log[i].slack_m, ssa += log[i].slack_m * a, n += 1;
    }
    return Run{r.metrics.slack_rms_m, (ssa - sa * ss / n) / (saa - sa * sa / n)};
  };
  const Run with_preview = run(true, true), without = run(false, true), smoothed = run(true, false);
  EXPECT_LE(with_preview.rms_m, without.rms_m);
  EXPECT_LT(std::abs(with_preview.acceleration_coefficient_s2), 4e-4);
  // The penalty on the command's change alone: the bias, and the preview a loss.
  EXPECT_GT(smoothed.acceleration_coefficient_s2, 5e-4);
  EXPECT_GT(smoothed.rms_m, 1.3 * with_preview.rms_m);
  EXPECT_GT(smoothed.rms_m, without.rms_m);
}

// docs/results.md, "Why slack RMS does not halve": with the geometric slack alone
// (no tension fusion) the reported pose's noise sets a floor shared by both
// controllers. Without it the MPC's own tracking error is well under half the
// baseline's on the fast trajectory; with it, it is not.
TEST(TetherSim, PoseNoiseSetsTheSlackFloorOfBothControllers) {
  const auto scn = fast_back_and_forth();
  auto model = std::make_shared<tether::FixedWrapTether>(1.0, scn.p_WE, scn.wrap_points);
  auto rms = [&](double pose_noise_m, bool mpc) {
    auto config = TetherRunConfig::for_tether(15.0, 1.0);
    config.sim.pose_noise_m = pose_noise_m;
    config.mpc.control.slack_observer.tension_fusion = false;
    config.baseline.control.slack_observer.tension_fusion = false;
    auto controller = mpc ? std::unique_ptr<tether::TetherController>(
                                std::make_unique<tether::TautTetherMpc>(config.mpc, model))
                          : std::make_unique<tether::FeedForwardPid>(config.baseline, model);
    return run_tether_sim(scn, config.sim, *controller).metrics.slack_rms_m;
  };
  const double mpc_clean = rms(0.0, true), baseline_clean = rms(0.0, false);
  const double mpc_noisy = rms(0.01, true), baseline_noisy = rms(0.01, false);
  EXPECT_LT(mpc_clean, 0.5 * baseline_clean);
  // Noise raises both; it is not a limit on how good the MPC may become.
  EXPECT_GT(mpc_noisy, mpc_clean);
  EXPECT_GT(baseline_noisy, baseline_clean);
  // The noise adds about the same to both: the filtered pose error, ~1.6 mm along the line.
  const double mpc_added = std::sqrt(mpc_noisy * mpc_noisy - mpc_clean * mpc_clean);
  const double baseline_added =
      std::sqrt(baseline_noisy * baseline_noisy - baseline_clean * baseline_clean);
  EXPECT_NEAR(mpc_added, 0.002, 0.0006);
  EXPECT_NEAR(baseline_added, 0.002, 0.0008);
}

std::unique_ptr<tether::TetherController> make_controller(const TetherRunConfig& config, bool mpc,
                                                          const TetherScenario& scn) {
  auto model = std::make_shared<tether::FixedWrapTether>(1.0, scn.p_WE, scn.wrap_points);
  if (mpc) return std::make_unique<tether::TautTetherMpc>(config.mpc, model);
  return std::make_unique<tether::FeedForwardPid>(config.baseline, model);
}

// The winch tension measures the stretch now (no link latency) whenever the line
// is taut; fusing it with the geometric slack (SlackObserver) takes both
// controllers well below the pose estimate's floor, without over-tension.
TEST(TetherSim, TensionFusionLowersBothControllersSlack) {
  for (const auto& scn : {default_tether_scenario(), fast_back_and_forth()}) {
    for (const bool mpc : {true, false}) {
      auto run = [&](bool fusion) {
        auto config = TetherRunConfig::for_tether(15.0, 1.0);
        config.mpc.control.slack_observer.tension_fusion = fusion;
        config.baseline.control.slack_observer.tension_fusion = fusion;
        return run_tether_sim(scn, config.sim, *make_controller(config, mpc, scn)).metrics;
      };
      const auto fused = run(true), geometric = run(false);
      EXPECT_LT(fused.slack_rms_m, 0.75 * geometric.slack_rms_m) << scn.name << " mpc " << mpc;
      EXPECT_EQ(fused.over_tension_events, 0) << scn.name << " mpc " << mpc;
      EXPECT_EQ(fused.released_over_limit, 0);
    }
  }
}

// With the miniUGV's plan ahead in each message, the MPC predicts the steps of the
// trapezoidal speed profile instead of learning of them a latency late. The
// default baseline ignores the preview (the classic feed-forward); with
// use_preview it latency-compensates with it, and gains too.
TEST(TetherSim, APlanPreviewHelpsOnTrapezoidalProfiles) {
  const auto scn = default_tether_scenario();
  auto rms = [&](bool mpc, double preview_s, bool baseline_uses_it) {
    auto config = TetherRunConfig::for_tether(15.0, 1.0);
    config.sim.ugv_preview_s = preview_s;
    config.baseline.use_preview = baseline_uses_it;
    return run_tether_sim(scn, config.sim, *make_controller(config, mpc, scn)).metrics.slack_rms_m;
  };
  EXPECT_LT(rms(true, 0.5, false), 0.85 * rms(true, 0.0, false));
  EXPECT_EQ(rms(false, 0.5, false), rms(false, 0.0, false));
  EXPECT_LT(rms(false, 0.5, true), 0.85 * rms(false, 0.0, false));
}

// The less obedient miniUGV of examples/tether/less_obedient_ugv.yaml (0.15 s velocity
// lag, 2 cm/s slip, 1 s path tracking) on the fast back-and-forth trajectory, seed 1:
// the MPC that trusts the desired motion is worse than the baseline (the finding these
// options answer); with its velocity-error filter and response identification (the
// defaults) it beats it, and on the obedient robot they change the MPC's slack by less
// than 3 %.
TEST(TetherSim, TheVelocityErrorFilterMakesTheMpcRobustToALaggingMiniUgv) {
  const auto scn = fast_back_and_forth();
  auto run = [&](bool mpc, bool robust, bool obedient) {
    auto config = TetherRunConfig::for_tether(15.0, 1.0);
    if (!obedient) {
      config.sim.ugv_velocity_lag_s = 0.15;
      config.sim.ugv_slip_noise_mps = 0.02;
      config.sim.ugv_slip_time_s = 0.5;
      config.sim.ugv_tracking_time_s = 1.0;
    }
    if (!robust) {
      config.mpc.ugv_velocity_error.sigma_mps = 0.0;
      config.mpc.ugv_response_identification.enabled = false;
    }
    return run_tether_sim(scn, config.sim, *make_controller(config, mpc, scn)).metrics;
  };
  const auto trusting = run(true, false, false), robust = run(true, true, false);
  const auto baseline = run(false, false, false);
  EXPECT_GT(trusting.reachable_slack_rms_m, baseline.reachable_slack_rms_m);
  EXPECT_LT(robust.reachable_slack_rms_m, 0.8 * baseline.reachable_slack_rms_m);
  EXPECT_EQ(robust.over_tension_events, 0);
  EXPECT_EQ(robust.released_over_limit, 0);
  const double obedient_robust = run(true, true, true).reachable_slack_rms_m;
  const double obedient_trusting = run(true, false, true).reachable_slack_rms_m;
  EXPECT_LT(obedient_robust, 1.03 * obedient_trusting);
}

// The same robot on the built-in scenario's rest-to-rest legs, where the velocity-error
// filter alone left the MPC 20 % behind the baseline: with the robot's response
// identified from its messages (the default) the MPC is ahead, seeds 1 and 2. On an
// obedient robot the identification keeps the obedient model, so the MPC's run is the
// same to the bit with it and without it.
TEST(TetherSim, TheIdentifiedResponseModelPutsTheMpcAheadOnRestToRestLegs) {
  const auto scn = default_tether_scenario();
  auto run = [&](bool mpc, bool identify, bool obedient, std::uint64_t seed) {
    auto config = TetherRunConfig::for_tether(15.0, 1.0);
    config.sim.seed = seed;
    if (!obedient) {
      config.sim.ugv_velocity_lag_s = 0.15;
      config.sim.ugv_slip_noise_mps = 0.02;
      config.sim.ugv_slip_time_s = 0.5;
      config.sim.ugv_tracking_time_s = 1.0;
    }
    config.mpc.ugv_response_identification.enabled = identify;
    return run_tether_sim(scn, config.sim, *make_controller(config, mpc, scn)).metrics;
  };
  for (const std::uint64_t seed : {1, 2}) {
    const double baseline = run(false, false, false, seed).reachable_slack_rms_m;
    const auto identified = run(true, true, false, seed);
    EXPECT_LT(identified.reachable_slack_rms_m, baseline) << seed;
    EXPECT_GT(run(true, false, false, seed).reachable_slack_rms_m, baseline) << seed;
    EXPECT_EQ(identified.over_tension_events, 0);
    EXPECT_EQ(identified.released_over_limit, 0);
  }
  EXPECT_EQ(run(true, true, true, 1).reachable_slack_rms_m,
            run(true, false, true, 1).reachable_slack_rms_m);
}

}  // namespace
}  // namespace ferret::sim
