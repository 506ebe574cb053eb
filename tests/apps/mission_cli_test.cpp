// `ferret mission`'s bad input: one message naming the file or option and the field,
// exit 2, nothing written. (The missions themselves: tests/mission.)

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/cli_runner.hpp"

namespace {

using ferret::test::run_cli;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("ferret_mission_cli_" + name);
  fs::remove_all(d);
  return d;
}

TEST(MissionCli, AWorldWithoutHiddenSpacesExits2AndWritesNothing) {
  const fs::path world = fs::temp_directory_path() / "ferret_mission_cli_empty_world.yaml";
  std::ofstream(world)
      << "name: empty\nresolution_m: 0.1\nbounds_m: {min: [-5, -5, -0.5], max: [5, 5, 5]}\n";
  const fs::path out = fresh_dir("empty");
  const auto r = run_cli("mission --world " + world.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("hidden_spaces"));
  EXPECT_FALSE(fs::exists(out));
}

TEST(MissionCli, ABadMissionFileExits2NamingTheField) {
  const fs::path mission = fs::temp_directory_path() / "ferret_mission_cli_bad_mission.yaml";
  std::ofstream(mission) << "tether:\n  total_length_m: .nan\n";
  const fs::path out = fresh_dir("bad_mission");
  const auto r = run_cli("mission --mission " + mission.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("tether.total_length_m"));
  EXPECT_FALSE(fs::exists(out));
  // The UAV mission's keys in the uav section are checked before anything runs.
  std::ofstream(mission) << "uav:\n  release: parachute\n";
  const auto u = run_cli("mission --mission " + mission.string() + " -o " + out.string());
  EXPECT_EQ(u.exit_code, 2) << u.err;
  EXPECT_THAT(u.err, HasSubstr("uav.release"));
  EXPECT_FALSE(fs::exists(out));
  // A tether the miniUGV's commands take but the UAV's mission cannot fly (the winch at
  // the entry leaves no hover release), named in the file that set it.
  std::ofstream(mission) << "tether: {total_length_m: 15, entry_offset_m: 0}\n";
  const auto t = run_cli("mission --mission " + mission.string() + " -o " + out.string());
  EXPECT_EQ(t.exit_code, 2) << t.err;
  EXPECT_THAT(t.err, HasSubstr(mission.string() + ": tether.entry_offset_m"));
  EXPECT_FALSE(fs::exists(out));
}

TEST(MissionCli, AMiniUgvWiderThanAnOpeningExits2NamingTheHiddenSpace) {
  // The shipped miniUGV with its chassis 0.17 m wide: the default world's openings are
  // 0.15 m wide, so it would be lowered to spaces it cannot enter.
  std::ifstream in(fs::path(FERRET_SOURCE_DIR) / "urdf/models/miniugv.urdf");
  std::string xml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string chassis = "<box size=\"0.130 0.090 0.040\"/>";
  ASSERT_NE(xml.find(chassis), std::string::npos);
  for (std::size_t at; (at = xml.find(chassis)) != std::string::npos;)
    xml.replace(at, chassis.size(), "<box size=\"0.130 0.170 0.040\"/>");
  const fs::path urdf = fs::temp_directory_path() / "ferret_mission_cli_wide_ugv.urdf";
  std::ofstream(urdf) << xml;
  const fs::path out = fresh_dir("wide_ugv");
  const auto r = run_cli("mission --robot-ugv " + urdf.string() + " -o " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("default.yaml: hidden_spaces[0].opening (house_void)"));
  EXPECT_THAT(r.err, HasSubstr("at least 0.170 m wide"));
  EXPECT_THAT(r.err, HasSubstr("got 0.150 m wide, 0.070 m high"));
  EXPECT_FALSE(fs::exists(out));
}

TEST(MissionCli, AnUnknownChoiceExits2) {
  const auto r = run_cli("mission --no-landing-zone crash");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--no-landing-zone"));
  const auto m = run_cli("mission --world /nonexistent/world.yaml");
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_THAT(m.err, HasSubstr("/nonexistent/world.yaml"));
  // The robot link: a way it cannot run, a loss it cannot have, a loss with no messages.
  for (const auto& [args, named] :
       {std::pair{"--link carrier-pigeon", "--link: expected in-process or messages"},
        std::pair{"--link messages --link-loss 1.5", "--link-loss: expected a fraction"},
        std::pair{"--link messages --link-reorder nan", "--link-reorder"},
        std::pair{"--link-loss 0.1", "--link-loss: expected --link messages"}}) {
    const auto l = run_cli(std::string("mission -q ") + args);
    EXPECT_EQ(l.exit_code, 2) << args;
    EXPECT_THAT(l.err, HasSubstr(named)) << args;
  }
}

}  // namespace
