// The ferret-plannerd executable: options by docs/cli.md (bad input exit 2, one line
// naming the option), --check-config, and the real process serving and draining on
// SIGTERM. The systemd unit it ships with is checked too.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <string>
#include <thread>

#include "support/cli_runner.hpp"

// clang-format off: httplib after every header that includes Eigen
#include <httplib.h>
// clang-format on

namespace ferret {
namespace {

using test::run_program;
using test::TempDir;

test::CliResult plannerd(const std::string& args) { return run_program(FERRET_PLANNERD, args); }

void write_file(const std::string& path, const std::string& text, mode_t mode) {
  std::ofstream(path) << text;
  ::chmod(path.c_str(), mode);
}

TEST(PlannerdCli, CheckConfigLoadsEverythingAndSaysWhatItWouldServe) {
  TempDir dir;
  write_file(dir / "token", "0123456789abcdef0123\n", 0600);
  const auto r = plannerd(
      "--check-config --listen 127.0.0.1:9999 --workers 3 --token-file " + (dir / "token") +
      " --map site=examples/scenarios/tether_detour.yaml --mission config/mission.yaml");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("listen 127.0.0.1:9999, 3 workers"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("auth bearer token, 1 map(s) preloaded"), std::string::npos) << r.out;
}

TEST(PlannerdCli, BadOptionsExitTwoNamingTheOption) {
  TempDir dir;
  write_file(dir / "open_token", "0123456789abcdef0123\n", 0644);
  write_file(dir / "short_token", "abc\n", 0600);
  write_file(dir / "junk.bt", "# Octomap OcTree binary file\nres 0.1\n", 0600);
  const struct {
    std::string args, names;
  } cases[] = {
      {"--listen 127.0.0.1", "--listen"},
      {"--listen 127.0.0.1:70000", "--listen"},
      {"--workers 0", "--workers"},
      {"--deadline 60", "--deadline"},
      {"--deadline nan", "--deadline"},
      {"--robot-ugv no_such_robot", "--robot-ugv"},
      {"--robot-uav urdf/models/miniugv.urdf", "--robot-uav"},  // a ground robot as the UAV
      {"--token-file " + (dir / "open_token"), "--token-file"},
      {"--token-file " + (dir / "short_token"), "--token-file"},
      {"--token-file " + (dir / "missing"), "--token-file"},
      {"--map site", "--map"},
      {"--map site=" + (dir / "missing.bt"), "--map"},
      {"--map site=" + (dir / "junk.bt"), "junk.bt"},
      {"--map 'bad name=examples/scenarios/tether_detour.yaml'", "name"},
      {"--frobnicate", "frobnicate"},
  };
  for (const auto& c : cases) {
    const auto r = plannerd("--check-config " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.names), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("ferret-plannerd: error: ", 0), 0u) << r.err;
  }
}

TEST(PlannerdCli, TheProcessServesAndDrainsOnSigterm) {
  TempDir dir;
  const std::string err = dir / "stderr", rc = dir / "rc", pid = dir / "pid";
  const std::string cmd =
      std::string("cd '") + FERRET_SOURCE_DIR + "' && ( ( '" + FERRET_PLANNERD +
      "' --listen 127.0.0.1:0 --map detour=examples/scenarios/tether_detour.yaml 2>'" + err +
      "' & echo $! > '" + pid + "'; wait $!; echo $? > '" + rc + "' ) & )";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  // The port it bound is on its first line.
  int port = 0;
  for (int k = 0; k < 3000 && port == 0; ++k) {
    std::ifstream in(err);
    std::string line;
    std::getline(in, line);
    std::smatch m;
    if (std::regex_search(line, m, std::regex("serving on 127\\.0\\.0\\.1:([0-9]+)")))
      port = std::stoi(m[1]);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_GT(port, 0) << "never served";
  httplib::Client c("127.0.0.1", port);
  const auto maps = c.Get("/v1/maps/detour");
  ASSERT_TRUE(maps);
  EXPECT_EQ(maps->status, 200);
  const auto plan = c.Post("/v1/plan/ugv",
                           R"({"map":"detour","start":[10,4.5,-1.57],"goal":[10,1.5,-1.57],)"
                           R"("driven":[[1,6.5],[10,6.5]],"tether_budget_m":12.5,"deadline_s":5})",
                           "application/json");
  ASSERT_TRUE(plan);
  EXPECT_EQ(plan->status, 200) << plan->body;
  int p = 0;
  std::ifstream(pid) >> p;
  ASSERT_GT(p, 0);
  ::kill(p, SIGTERM);
  int code = -1;
  for (int k = 0; k < 3000 && code < 0; ++k) {
    std::ifstream in(rc);
    if (!(in >> code)) code = -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(code, 0);
  std::ifstream in(err);
  const std::string log((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(log.find("SIGTERM received, draining"), std::string::npos) << log;
  EXPECT_NE(log.find("stopped"), std::string::npos) << log;
}

TEST(PlannerdCli, TheSystemdUnitIsLockedDown) {
  std::ifstream in(FERRET_SOURCE_DIR "/deploy/ferret-plannerd.service");
  const std::string unit((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* line :
       {"DynamicUser=yes", "ProtectSystem=strict", "Restart=on-failure", "NoNewPrivileges=yes",
        "LoadCredential=token:", "--check-config", "--listen 127.0.0.1:"})
    EXPECT_NE(unit.find(line), std::string::npos) << line;
  if (std::system("command -v systemd-analyze >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "no systemd-analyze";
  // systemd's own check of the unit, with ExecStart pointing at the built binary.
  TempDir dir;
  std::string copy =
      std::regex_replace(unit, std::regex("/usr/local/bin/ferret-plannerd"), FERRET_PLANNERD);
  std::ofstream(dir / "ferret-plannerd.service") << copy;
  const auto r =
      run_program("systemd-analyze", "verify '" + (dir / "ferret-plannerd.service") + "'");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
}

}  // namespace
}  // namespace ferret
