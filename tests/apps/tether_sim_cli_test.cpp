#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_runner.hpp"

namespace ferret::test {
namespace {

using ::testing::HasSubstr;

TEST(TetherSimCli, DefaultTrajectoryWithTheMpcPrintsFiguresAndWritesPlotCsvAndJson) {
  TempDir dir;
  const auto r = run_cli("tether-sim --out '" + dir.path().string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("scenario: default"));
  EXPECT_THAT(r.out, HasSubstr("controller: mpc"));
  EXPECT_THAT(r.out, HasSubstr("slack_rms_m: "));
  EXPECT_THAT(r.out, HasSubstr("reachable_slack_rms_m: "));
  EXPECT_THAT(r.out, HasSubstr("max_slack_m: "));
  EXPECT_THAT(r.out, HasSubstr("over_tension_events: 0"));
  EXPECT_THAT(r.out, HasSubstr("tether_limit_active_s: "));
  ASSERT_TRUE(std::filesystem::exists(dir / "tether_mpc.png"));
  std::ifstream png(dir / "tether_mpc.png", std::ios::binary);
  char magic[4] = {};
  png.read(magic, 4);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
  std::ifstream csv(dir / "tether_mpc.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "t_s,released_m,required_m,slack_m,ugv_tension_n,winch_tension_n,command_mps,speed_mps,"
            "snagged,reachable_slack_m");
  const auto j = nlohmann::json::parse(std::ifstream(dir / "tether_mpc.json"));
  EXPECT_EQ(j["metrics"]["over_tension_events"], 0);
  EXPECT_EQ(j["metrics"]["cycles_above_L"], 0);
  // No snag on the default trajectory: the winch reaches all of the slack.
  EXPECT_EQ(j["metrics"]["reachable_slack_rms_m"], j["metrics"]["slack_rms_m"]);
  EXPECT_EQ(j["total_length_m"], 15.0);
  EXPECT_EQ(dir.count(), 3u);
}

TEST(TetherSimCli, BaselineOnAShippedTrajectoryAndTheMissionsTetherLength) {
  TempDir dir;
  std::ofstream(dir / "mission.yaml") << "tether: {total_length_m: 12.0, entry_offset_m: 1.5}\n";
  const auto r = run_cli(
      "tether-sim --trajectory examples/trajectories/fast_back_and_forth.csv --controller baseline "
      "--seed 3 --mission '" +
      (dir / "mission.yaml") + "' --out '" + (dir / "out") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("controller: baseline"));
  EXPECT_THAT(r.out, HasSubstr("(L = 12.00)"));
  const auto j = nlohmann::json::parse(std::ifstream(dir / "out/tether_baseline.json"));
  EXPECT_EQ(j["seed"], 3);
  EXPECT_EQ(j["entry_offset_m"], 1.5);
}

TEST(TetherSimCli, BadTrajectoryExitsTwoNamingLineAndFieldWithoutOutputs) {
  TempDir dir;
  std::ofstream(dir / "bad.csv") << "t,x,y,yaw\n0,1,0,0\n0.1,1.1,oops,0\n";
  const auto r =
      run_cli("tether-sim --trajectory '" + (dir / "bad.csv") + "' --out '" + (dir / "out") + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("bad.csv"));
  EXPECT_THAT(r.err, HasSubstr("line 3, field 'y'"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

TEST(TetherSimCli, ConfigFileSetsGainsAndABadOneExitsTwo) {
  TempDir dir;
  std::ofstream(dir / "slow.yaml")
      << "baseline: {kp_per_s: 1, ki_per_s2: 0}\nsim: {link_latency_s: 0.2}\n";
  const auto tuned = run_cli("tether-sim --controller baseline --out '" + (dir / "a") + "'");
  const auto detuned = run_cli("tether-sim --controller baseline --sim-config '" +
                               (dir / "slow.yaml") + "' -o '" + (dir / "b") + "'");
  // The old spelling (--config, --output) is a hidden alias of the same options.
  const auto old_spelling = run_cli("tether-sim --controller baseline --config '" +
                                    (dir / "slow.yaml") + "' --output '" + (dir / "old") + "'");
  ASSERT_EQ(tuned.exit_code, 0) << tuned.err;
  ASSERT_EQ(detuned.exit_code, 0) << detuned.err;
  ASSERT_EQ(old_spelling.exit_code, 0) << old_spelling.err;
  const auto a = nlohmann::json::parse(std::ifstream(dir / "a/tether_baseline.json"));
  const auto b = nlohmann::json::parse(std::ifstream(dir / "b/tether_baseline.json"));
  const auto old = nlohmann::json::parse(std::ifstream(dir / "old/tether_baseline.json"));
  EXPECT_EQ(old["metrics"], b["metrics"]);
  EXPECT_EQ(b["link_latency_s"], 0.2);
  EXPECT_GT(b["metrics"]["slack_rms_m"].get<double>(),
            2.0 * a["metrics"]["slack_rms_m"].get<double>());

  std::ofstream(dir / "bad.yaml") << "mpc: {weight_slack: -1}\n";
  const auto bad =
      run_cli("tether-sim --config '" + (dir / "bad.yaml") + "' --out '" + (dir / "c") + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("mpc.weight_slack"));
  EXPECT_FALSE(std::filesystem::exists(dir / "c"));
  // The velocity-error filter's keys: NaN or negative exit 2 naming the field.
  for (const std::string key : {"ugv_velocity_error_mps", "ugv_velocity_error_window_s"}) {
    for (const std::string value : {".nan", "-1"}) {
      std::ofstream(dir / "filter.yaml") << "mpc: {" << key << ": " << value << "}\n";
      const auto r = run_cli("tether-sim --sim-config '" + (dir / "filter.yaml") + "' --out '" +
                             (dir / "f") + "'");
      EXPECT_EQ(r.exit_code, 2) << key << " " << value;
      EXPECT_THAT(r.err, HasSubstr("mpc." + key));
      EXPECT_FALSE(std::filesystem::exists(dir / "f"));
    }
  }
}

TEST(TetherSimCli, BadOptionsExitTwo) {
  TempDir dir;
  auto r = run_cli("tether-sim --controller bang-bang --out '" + dir.path().string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--controller"));
  EXPECT_THAT(r.err, HasSubstr("mpc"));  // the valid choices are listed
  EXPECT_THAT(r.err, HasSubstr("baseline"));
  r = run_cli("tether-sim");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--out"));
  r = run_cli("tether-sim --trajectory examples/trajectories/none.yaml --out '" +
              dir.path().string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("none.yaml"));
  EXPECT_EQ(dir.count(), 0u);
}

}  // namespace
}  // namespace ferret::test
