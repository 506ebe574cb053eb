#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/cli_runner.hpp"
#include "support/test_maps.hpp"

namespace ferret::test {
namespace {

using ::testing::HasSubstr;

struct Room {
  TempDir dir;
  std::string map;
  Room() : map(dir / "room.yaml") { save_map_server(small_hidden_space(), map); }
};

TEST(ExploreCli, FindsTheObjectAndWritesTheFigureAndLog) {
  Room room;
  const std::string out = room.dir / "out";
  const auto r = run_cli("explore --map " + room.map +
                         " --start 0.5,1,0 --object 3.2,0.8 --method cdos --seed 1 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("found: yes"));
  EXPECT_THAT(r.out, HasSubstr("path_m: "));
  EXPECT_THAT(r.out, HasSubstr("decisions: "));
  for (const char* f : {"G.png", "O.png", "G_O.png", "log.json"})
    EXPECT_TRUE(std::filesystem::is_regular_file(std::filesystem::path(out) / f)) << f;
  std::ifstream in(std::filesystem::path(out) / "log.json");
  const auto log = nlohmann::json::parse(in);
  EXPECT_EQ(log["method"], "cdos");
  EXPECT_TRUE(log["result"]["found"].get<bool>());
  EXPECT_FALSE(log["decisions"].empty());
  EXPECT_FALSE(log["trajectory"].empty());
  // Same seed, same run.
  const auto again = run_cli("explore --map " + room.map +
                             " --start 0.5,1,0 --object 3.2,0.8 --method cdos --seed 1");
  EXPECT_EQ(again.out.substr(0, again.out.find("wrote")), r.out.substr(0, r.out.find("wrote")));
}

TEST(ExploreCli, BadInputExitsTwoNamingTheOption) {
  Room room;
  const std::string base = "explore --map " + room.map + " ";
  auto r = run_cli(base + "--start 2.2,0.5,0 --object 3.2,0.8 --out " +
                   (room.dir / "o"));  // in the partition
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--start"));
  EXPECT_FALSE(std::filesystem::exists(room.dir / "o"));
  r = run_cli(base + "--start 0.5,1 --object 3.2,0.8");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--start"));
  r = run_cli(base + "--start 0.5,1,0 --object 3.2,0.8 --method random");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--method"));
  r = run_cli("explore --map " + (room.dir / "missing.yaml") + " --start 0.5,1,0 --object 3.2,0.8");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("missing.yaml"));
}

const std::string kRover = std::string(FERRET_SOURCE_DIR) + "/tests/data/robots/rover.urdf";

TEST(ExploreCli, ListMethodsPrintsEveryRegisteredMethodAndNeedsNoMap) {
  const auto r = run_cli("explore --list-methods");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream in(r.out);
  std::vector<std::string> names;
  for (std::string line; std::getline(in, line);) names.push_back(line);
  // The same names --method accepts, in the same order.
  Room room;
  const auto bad =
      run_cli("explore --map " + room.map + " --start 0.5,1,0 --object 4,1 --method bogus");
  EXPECT_EQ(bad.exit_code, 2);
  std::string joined;
  for (const auto& n : names) joined += (joined.empty() ? "" : ", ") + n;
  EXPECT_THAT(bad.err, HasSubstr("one of " + joined)) << bad.err;
  for (const char* m : {"cdos", "cdos-literal", "rapid", "oracle"})
    EXPECT_NE(std::find(names.begin(), names.end(), m), names.end()) << m;
}

TEST(ExploreCli, TheRobotsUrdfGivesTheSensorsAndTheSpeed) {
  Room room;
  const std::string out = room.dir / "out";
  const auto r = run_cli("explore --map " + room.map + " --start 0.5,1,0 --object 3.2,0.8" +
                         " --method cdos --seed 1 --robot " + kRover + " -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(std::filesystem::path(out) / "log.json");
  const auto log = nlohmann::json::parse(in);
  // The rover's values, none of them the miniUGV's (90 deg, 640 px, 30 deg, 4 m, 2 m/s).
  EXPECT_NEAR(log["sensors"]["camera_fov_deg"].get<double>(), 68.754935, 1e-5);
  EXPECT_EQ(log["sensors"]["image_width_px"].get<int>(), 320);
  EXPECT_DOUBLE_EQ(log["sensors"]["camera_range_m"].get<double>(), 3.0);
  EXPECT_NEAR(log["sensors"]["ir_fov_deg"].get<double>(), 50.0, 1e-9);
  EXPECT_DOUBLE_EQ(log["sensors"]["ir_range_m"].get<double>(), 2.5);
  EXPECT_EQ(log["sensors"]["ir_beams"].get<int>(), 10);
  EXPECT_DOUBLE_EQ(log["robot"]["max_velocity_mps"].get<double>(), 0.5);
  EXPECT_EQ(log["robot"]["urdf"].get<std::string>(), kRover);
  // The speed: consecutive logged poses (every 2 steps of dt_s) never 0.5 m/s apart.
  const double dt = 2 * log["dt_s"].get<double>();
  const auto& t = log["trajectory"];
  ASSERT_GT(t.size(), 10u);
  double fastest = 0.0;
  for (std::size_t k = 1; k < t.size(); ++k)
    fastest = std::max(fastest, std::hypot(t[k][0].get<double>() - t[k - 1][0].get<double>(),
                                           t[k][1].get<double>() - t[k - 1][1].get<double>()) /
                                    dt);
  EXPECT_LE(fastest, 0.5 + 1e-6);
  EXPECT_GT(fastest, 0.25);
}

TEST(ExploreCli, OptionsOverrideTheUrdfAndOldSpellingsStillWork) {
  Room room;
  const std::string out = room.dir / "out";
  const auto r = run_cli("explore --map " + room.map + " --start 0.5,1,0 --object 3.2,0.8" +
                         " --robot " + kRover + " --camera-fov-deg 100 --ir-range 1.5" +
                         " --max-velocity-mps 0.3 --time-limit 5 --output " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(std::filesystem::path(out) / "log.json");
  const auto log = nlohmann::json::parse(in);
  EXPECT_DOUBLE_EQ(log["sensors"]["camera_fov_deg"].get<double>(), 100.0);
  EXPECT_DOUBLE_EQ(log["sensors"]["ir_range_m"].get<double>(), 1.5);
  EXPECT_EQ(log["sensors"]["image_width_px"].get<int>(), 320);  // still the rover's
  EXPECT_DOUBLE_EQ(log["robot"]["max_velocity_mps"].get<double>(), 0.3);
}

TEST(ExploreCli, ARobotWithoutTheSensorRolesIsBadInputNamingTheRole) {
  Room room;
  const std::string urdf = room.dir / "bare.urdf";
  std::ofstream(urdf) << "<robot name=\"bare\"><link name=\"b\"><collision><geometry>"
                         "<box size=\"0.2 0.2 0.1\"/></geometry></collision></link></robot>\n";
  const std::string out = room.dir / "out";
  const auto r = run_cli("explore --map " + room.map + " --start 0.5,1,0 --object 3.2,0.8" +
                         " --robot " + urdf + " -o " + out);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr(urdf));
  EXPECT_THAT(r.err, HasSubstr("role[object_camera]"));
  EXPECT_THAT(r.err, HasSubstr("<ferret role=\"object_camera\"/>"));
  EXPECT_FALSE(std::filesystem::exists(out));
}

}  // namespace
}  // namespace ferret::test

namespace ferret::test {
namespace {

TEST(ExploreCli, RetrieveRunsTheWholeMissionAndLogsEveryTransition) {
  Room room;
  const std::string out = room.dir / "mission";
  const auto r = run_cli("explore --map " + room.map +
                         " --start 0.5,1,0 --object 3.2,0.8 --retrieve --seed 5 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("ugv  explore -> track"));
  EXPECT_THAT(r.out, HasSubstr("ugv  grasp -> return"));
  EXPECT_THAT(r.out, HasSubstr("outcome: object_retrieved"));
  std::ifstream in(std::filesystem::path(out) / "log.json");
  const auto log = nlohmann::json::parse(in);
  EXPECT_EQ(log["result"]["outcome"], "object_retrieved");
  EXPECT_EQ(log["result"]["final_state"], "done");
  ASSERT_GE(log["transitions"].size(), 7u);
  EXPECT_EQ(log["transitions"].back()["to"], "done");
  EXPECT_TRUE(std::filesystem::is_regular_file(std::filesystem::path(out) / "G_O.png"));
  // The MCAP log (read whole by Foxglove's reader in mission_mcap_reader.js).
  std::ifstream mcap(std::filesystem::path(out) / "mission.mcap", std::ios::binary);
  std::string head(8, '\0');
  mcap.read(head.data(), 8);
  EXPECT_EQ(head, std::string("\x89MCAP0\r\n", 8));
}

TEST(ExploreCli, RetrieveInAnEmptySpaceReportsNoObject) {
  Room room;
  const auto r =
      run_cli("explore --map " + room.map + " --start 0.5,1,0 --object none --retrieve --seed 3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("outcome: no_object"));
  // "none" is a mission's word: the plain search needs an object.
  const auto bad = run_cli("explore --map " + room.map + " --start 0.5,1,0 --object none");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("--object"));
}

}  // namespace
}  // namespace ferret::test
