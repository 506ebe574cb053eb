// `ferret sim-world`, `ferret uav` and `ferret ugv`: the mission with each robot in its
// own process, the world in a third, all on loopback (docs/robots.md, "One process a
// robot"), against `ferret mission --link messages` in one process.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "support/cli_runner.hpp"

namespace ferret {
namespace {

using test::run_cli;
using test::TempDir;

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// "key: value ..." lines of a summary, the value's first word.
std::map<std::string, std::string> summary(const std::string& text) {
  std::map<std::string, std::string> out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto colon = line.find(": ");
    if (colon == std::string::npos || line.starts_with(" ")) continue;
    std::istringstream value(line.substr(colon + 2));
    std::string first;
    value >> first;
    out[line.substr(0, colon)] = first;
  }
  return out;
}

// The three processes of a mission run on one world and seed: sim-world on a port the
// system picks, the two robots connecting to it. Exit codes in `codes`.
void run_three(const TempDir& dir, const std::string& world, const std::string& world_args) {
  const std::string d = dir.path().string();
  const std::string script =
      "F='" + std::string(FERRET_CLI) + "'; D='" + d + "'; W='" + world +
      "'\n"
      "timeout 900 \"$F\" sim-world --world \"$W\" --seed 1 --listen 127.0.0.1:0 " +
      world_args +
      " >\"$D/sw.out\" 2>\"$D/sw.err\" & SW=$!\n"
      "for i in $(seq 1200); do grep -q 'listening on' \"$D/sw.err\" && break; sleep 0.1; done\n"
      "P=$(sed -n 's/.*listening on 127.0.0.1:\\([0-9]*\\).*/\\1/p' \"$D/sw.err\")\n"
      "timeout 900 \"$F\" ugv --world \"$W\" --seed 1 --sim-world 127.0.0.1:$P >\"$D/ugv.out\" "
      "2>\"$D/ugv.err\" & UGV=$!\n"
      "timeout 900 \"$F\" uav --world \"$W\" --seed 1 --sim-world 127.0.0.1:$P >\"$D/uav.out\" "
      "2>\"$D/uav.err\"; U=$?\n"
      "wait $UGV; G=$?; wait $SW; S=$?\n"
      "echo \"$S $U $G\" >\"$D/codes\"\n";
  std::ofstream(dir.path() / "run.sh") << script;
  ASSERT_EQ(std::system(("bash '" + (dir.path() / "run.sh").string() + "'").c_str()), 0);
}

TEST(RobotProcesses, ThreeProcessesOnLoopbackEndAsOneProcessDoesWithATenthLostAndReordered) {
  TempDir dir;
  const std::string world = std::string(FERRET_SOURCE_DIR) + "/examples/worlds/two_sites.yaml";
  const std::string faults = "--link-loss 0.1 --link-reorder 0.1";
  run_three(dir, world, faults);
  EXPECT_EQ(slurp(dir.path() / "codes"), "0 0 0\n")
      << slurp(dir.path() / "sw.err") << slurp(dir.path() / "uav.err")
      << slurp(dir.path() / "ugv.err");
  const auto one =
      run_cli("mission --world " + world + " --seed 1 --link messages " + faults + " -q");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const auto expect = summary(one.out);
  const auto uav = summary(slurp(dir.path() / "uav.out"));
  const auto world_said = summary(slurp(dir.path() / "sw.out"));
  // The UAV's mission: the same outcome at the same time, the same finds.
  for (const char* key :
       {"outcome", "time_s", "hidden_spaces_found", "objects_retrieved", "objects_dropped"})
    EXPECT_EQ(uav.at(key), expect.at(key)) << key;
  EXPECT_EQ(expect.at("outcome"), "search_complete");
  EXPECT_EQ(expect.at("objects_dropped"), "1");
  // The world's truth: the same flight, tether and collisions.
  for (const char* key : {"time_s", "flown_m", "battery_left", "tether_max_m",
                          "tether_over_tension_events", "uav_collisions"})
    EXPECT_EQ(world_said.at(key), expect.at(key)) << key;
  // The link's datagrams: lost and held back alike, so both ends counted the same.
  const std::string uav_link = slurp(dir.path() / "uav.out");
  const auto at = one.out.find("link: UAV end: ");
  ASSERT_NE(at, std::string::npos);
  const std::string counters = one.out.substr(at + 15, one.out.find(';', at) - at - 15);
  EXPECT_NE(uav_link.find("link: UAV end: " + counters + "\n"), std::string::npos)
      << counters << "\n"
      << uav_link;
  EXPECT_NE(slurp(dir.path() / "ugv.out").find("object_retrieved"), std::string::npos);
}

TEST(RobotProcesses, BadAddressesAndFaultsAreBadInput) {
  const auto a = run_cli("uav --sim-world nowhere");
  EXPECT_EQ(a.exit_code, 2);
  EXPECT_NE(a.err.find("--sim-world"), std::string::npos) << a.err;
  const auto b = run_cli("sim-world --link-loss 2");
  EXPECT_EQ(b.exit_code, 2);
  EXPECT_NE(b.err.find("--link-loss"), std::string::npos) << b.err;
  const auto c = run_cli("sim-world --listen 127.0.0.1:99999");
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_NE(c.err.find("--listen"), std::string::npos) << c.err;
  const auto d = run_cli("ugv --method no_such_search");
  EXPECT_EQ(d.exit_code, 2);
  EXPECT_NE(d.err.find("--method"), std::string::npos) << d.err;
}

}  // namespace
}  // namespace ferret
