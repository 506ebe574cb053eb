// `ferret sim-world`, `ferret uav` and `ferret ugv`: the mission with each robot in its
// own process, the world in a third, all on loopback (docs/robots.md, "One process a
// robot"), against `ferret mission --link messages` in one process; and each process's
// record of the run (-o).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
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
// system picks, the two robots connecting to it, each writing its record into
// sw/, uav/ and ugv/. Exit codes in `codes`. `then`: shell run after the robots started
// (e.g. to stop one).
void run_three(const TempDir& dir, const std::string& world, const std::string& world_args,
               const std::string& then = "") {
  const std::string d = dir.path().string();
  const std::string script =
      "F='" + std::string(FERRET_CLI) + "'; D='" + d + "'; W='" + world +
      "'\n"
      "timeout 900 \"$F\" sim-world --world \"$W\" --seed 1 --listen 127.0.0.1:0 -o \"$D/sw\" " +
      world_args +
      " >\"$D/sw.out\" 2>\"$D/sw.err\" & SW=$!\n"
      "for i in $(seq 1200); do grep -q 'listening on' \"$D/sw.err\" && break; sleep 0.1; done\n"
      "P=$(sed -n 's/.*listening on 127.0.0.1:\\([0-9]*\\).*/\\1/p' \"$D/sw.err\")\n"
      "timeout 900 \"$F\" ugv --world \"$W\" --seed 1 --sim-world 127.0.0.1:$P -o \"$D/ugv\" "
      ">\"$D/ugv.out\" 2>\"$D/ugv.err\" & UGV=$!\n"
      "timeout 900 \"$F\" uav --world \"$W\" --seed 1 --sim-world 127.0.0.1:$P -o \"$D/uav\" "
      ">\"$D/uav.out\" 2>\"$D/uav.err\" & UAV=$!\n" +
      then +
      "wait $UAV; U=$?\n"
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

  // Each process's record: its own side, agreeing with the others'.
  const auto report = [&](const char* side) {
    return nlohmann::json::parse(slurp(dir.path() / side / "report.json"));
  };
  const nlohmann::json w = report("sw"), a = report("uav"), g = report("ugv");
  EXPECT_EQ(w.at("side"), "world");
  EXPECT_EQ(a.at("side"), "uav");
  EXPECT_EQ(g.at("side"), "ugv");
  for (const nlohmann::json* j : {&w, &a, &g}) {
    EXPECT_TRUE(j->at("ended_early").is_null()) << j->at("ended_early");
    EXPECT_EQ(j->at("seed"), 1);
  }
  EXPECT_FALSE(a.at("transitions").empty());
  EXPECT_FALSE(g.at("transitions").empty());
  // The UAV's outcome and finds as the world heard them at the end and as one process ran.
  EXPECT_EQ(a.at("outcome"), expect.at("outcome"));
  EXPECT_EQ(w.at("robot_summaries").at("uav").at("outcome"), a.at("outcome"));
  EXPECT_EQ(a.at("summary").at("hidden_spaces_found"), a.at("hidden_spaces").size());
  EXPECT_EQ(std::to_string(a.at("summary").at("objects_retrieved").get<int>()),
            expect.at("objects_retrieved"));
  // What only the world knows is in its record, absent from the UAV's (not zero).
  for (const char* truth : {"objects_dropped", "uav_collisions", "tether_over_tension_events",
                            "tether_required_over_length_steps", "hidden_spaces_in_world"}) {
    EXPECT_TRUE(w.at("summary").contains(truth)) << truth;
    EXPECT_FALSE(a.at("summary").contains(truth)) << truth;
  }
  EXPECT_EQ(std::to_string(w.at("summary").at("objects_dropped").get<int>()),
            expect.at("objects_dropped"));
  EXPECT_FALSE(w.contains("outcome"));
  EXPECT_FALSE(a.contains("ugv_deployments"));
  // The UAV's flight from its own readings, the world's from the truth: the same flight.
  const double flown_uav = a.at("summary").at("flown_m"), flown_w = w.at("summary").at("flown_m");
  EXPECT_GT(flown_uav, 100.0);
  EXPECT_NEAR(flown_uav, flown_w, 0.05 * flown_w);
  EXPECT_NEAR(a.at("summary").at("battery_left").get<double>(),
              w.at("summary").at("battery_left").get<double>(), 0.02);
  EXPECT_GT(a.at("summary").at("tether_max_released_m").get<double>(), 0.0);
  EXPECT_EQ(a.at("samples_columns").size(), 9u);
  EXPECT_EQ(a.at("samples").at(0).size(), 9u);
  EXPECT_NEAR(a.at("samples").size(), w.at("samples").size(), 2.0);
  // The miniUGV searched once each time the UAV lowered it, as the world counted.
  std::size_t lowered = 0;
  for (const auto& v : a.at("hidden_spaces")) lowered += v.at("deployed_s") >= 0.0 ? 1 : 0;
  EXPECT_GT(lowered, 0u);
  EXPECT_EQ(g.at("ugv_deployments").size(), lowered);
  EXPECT_EQ(g.at("summary").at("searches"), lowered);
  EXPECT_EQ(w.at("ugv_deployments").size(), lowered);
  std::size_t k = 0;
  for (const auto& v : a.at("hidden_spaces")) {
    if (v.at("deployed_s") < 0.0) continue;
    const auto& d = g.at("ugv_deployments").at(k++);
    EXPECT_EQ(d.at("outcome"), v.at("ugv_outcome"));  // the UAV heard the miniUGV's outcome
    EXPECT_NEAR(d.at("deployed_s").get<double>(), v.at("deployed_s").get<double>(), 5.0);
    EXPECT_FALSE(d.contains("hidden_space"));  // the world's name for it
    EXPECT_FALSE(d.contains("body_contacts"));
  }
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "uav" / "mission.mcap"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "uav" / "battery.png"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "uav" / "aerial.png"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "ugv" / "mission.mcap"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "sw" / "aerial.png"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "sw" / "tether.png"));
}

// A robot that loses its world writes what it recorded and says why the run ended early;
// its exit says the run failed.
TEST(RobotProcesses, ARobotThatLosesItsPeerWritesItsRecordOfTheRunSoFar) {
  TempDir dir;
  const std::string world = std::string(FERRET_SOURCE_DIR) + "/examples/worlds/two_sites.yaml";
  // The miniUGV's process killed (under its `timeout`) while it searches the first hidden
  // space: the world loses it, then the UAV loses the world.
  run_three(dir, world, "",
            "for i in $(seq 3000); do grep -q 'ugv_ops' \"$D/uav.err\" && break; sleep 0.1; done\n"
            "pkill -9 -P $UGV\n");
  EXPECT_EQ(slurp(dir.path() / "codes").substr(0, 3), "1 1")
      << slurp(dir.path() / "sw.err") << slurp(dir.path() / "uav.err");
  EXPECT_NE(slurp(dir.path() / "uav.err").find("ferret: check failed"), std::string::npos);
  const auto a = nlohmann::json::parse(slurp(dir.path() / "uav" / "report.json"));
  EXPECT_EQ(a.at("side"), "uav");
  ASSERT_TRUE(a.at("ended_early").is_string()) << a.at("ended_early");
  EXPECT_FALSE(a.at("ended_early").get<std::string>().empty());
  EXPECT_FALSE(a.at("samples").empty());
  EXPECT_GT(a.at("time_s").get<double>(), 0.0);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "ugv" / "report.json"));  // killed
  // The world's truth up to where it lost the miniUGV, the deployment under way in it.
  const auto w = nlohmann::json::parse(slurp(dir.path() / "sw" / "report.json"));
  ASSERT_TRUE(w.at("ended_early").is_string()) << w.at("ended_early");
  EXPECT_NE(w.at("ended_early").get<std::string>().find("miniUGV"), std::string::npos)
      << w.at("ended_early");
  EXPECT_GT(w.at("time_s").get<double>(), 0.0);
  EXPECT_GT(w.at("summary").at("flown_m").get<double>(), 0.0);
  EXPECT_EQ(w.at("ugv_deployments").size(), 1u);
  EXPECT_TRUE(w.at("robot_summaries").at("uav").is_null());
  EXPECT_LE(a.at("time_s").get<double>(), w.at("time_s").get<double>() + 0.1);
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

// An output path that cannot be a directory is bad input before the run: nothing listens,
// nothing connects, nothing is written.
TEST(RobotProcesses, AnOutputThatCannotBeADirectoryFailsBeforeTheRun) {
  TempDir dir;
  const std::string file = (dir.path() / "a_file").string();
  std::ofstream(file) << "not a directory\n";
  for (const std::string command : {"sim-world --listen 127.0.0.1:0", "uav --sim-world 127.0.0.1:1",
                                    "ugv --sim-world 127.0.0.1:1"})
    for (const std::string& out : {file, file + "/under_a_file"}) {
      const auto r = run_cli(command + " -o '" + out + "'");
      EXPECT_EQ(r.exit_code, 2) << command << " -o " << out << "\n" << r.err;
      EXPECT_NE(r.err.find("--out"), std::string::npos) << r.err;
      EXPECT_EQ(r.err.find("listening"), std::string::npos) << r.err;
    }
  EXPECT_EQ(slurp(file), "not a directory\n");
}

}  // namespace
}  // namespace ferret
