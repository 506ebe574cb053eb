#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

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

}  // namespace
}  // namespace ferret::test
