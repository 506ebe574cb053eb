// `ferret ugv` and `ferret uav` on their hardware (docs/robots.md, "On the robots"):
// each robot's own loop on its steady clock, against fake devices on pseudo-terminals
// (the miniUGV's microcontroller, the winch's Dynamixel), the reference flight adapter
// moving its simulated M100 in wall time, and the robot link over UDP on loopback. No
// timing is asserted: every wait is for an event, with a generous bound.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>

#include "../tether_model/fake_dynamixel.hpp"
#include "../ugv/fake_ugv_mcu.hpp"
#include "ferret/core/clock.hpp"
#include "ferret/link/udp_link.hpp"
#include "ferret/uav/linked_ugv.hpp"
#include "support/cli_runner.hpp"

namespace ferret {
namespace {

using test::run_cli;
using test::TempDir;
using namespace std::chrono_literals;

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

// A loopback port nobody holds right now.
int free_udp_port() {
  link::UdpLinkOptions o;
  o.bind = "127.0.0.1:0";
  return link::UdpLink(o).local_address().port;
}

std::filesystem::path write_file(const TempDir& dir, const std::string& name,
                                 const std::string& text) {
  const auto path = dir.path() / name;
  std::ofstream(path) << text;
  return path;
}

std::string ugv_mission(const std::string& port, const std::string& camera = "none") {
  return "ugv:\n  base:\n    backend: hw\n    serial: {port: " + port +
         "}\n    camera: {device: " + camera + "}\n";
}

// The UAV's end of the link in the test: a LinkedUgv on the wall clock over UDP.
struct TestUav {
  explicit TestUav(int ugv_port) : udp(options(ugv_port)), ugv(clock) {}
  static link::UdpLinkOptions options(int ugv_port) {
    link::UdpLinkOptions o;
    o.bind = "127.0.0.1:0";
    o.peer = "127.0.0.1:" + std::to_string(ugv_port);
    return o;
  }
  // Talks for `how_long` (every 20 ms), or until `until` holds.
  template <class Until>
  bool talk(std::chrono::milliseconds how_long, Until until) {
    const auto end = std::chrono::steady_clock::now() + how_long;
    while (std::chrono::steady_clock::now() < end) {
      link::exchange(udp, ugv.session(), 20);
      if (until()) return true;
    }
    return false;
  }
  SteadyClock clock;
  link::UdpLink udp;
  LinkedUgv ugv;
};

TEST(RobotsOnHardware, TheMiniUgvSearchesWhereTheUavSetItDownAndHoldsWhileTheUavIsSilent) {
  TempDir dir;
  test::FakeUgvMcu mcu;
  const auto mission = write_file(dir, "ugv.yaml", ugv_mission(mcu.port()));
  const int ugv_port = free_udp_port();
  TestUav uav(ugv_port);
  test::CliResult result;
  std::thread process([&] {
    result = run_cli("ugv --mission " + mission.string() +
                     " --seed 3 --duration-s 12 --link-bind 127.0.0.1:" + std::to_string(ugv_port) +
                     " --link-peer " + uav.udp.local_address().to_string() + " -o " +
                     (dir.path() / "record").string());
  });
  // The robot is up when its telemetry arrives (it reports from the start: the UAV's
  // touchdown check reads its attitude while it is lowered).
  const bool heard = uav.talk(120s, [&] { return uav.ugv.session().counters().accepted > 0; });
  if (heard) {
    uav.ugv.deploy(Eigen::Vector3d(2.0, 1.0, 0.0), 0.5);
    // It starts its search there: its pose is reported in the UAV's frame, at the entry.
    EXPECT_TRUE(uav.talk(10s, [&] { return uav.ugv.report().running; }));
    const UgvReport started = uav.ugv.report();
    EXPECT_NEAR(started.p_WG.x(), 2.0, 0.15);
    EXPECT_NEAR(started.p_WG.y(), 1.0, 0.15);
    // It drives (no IR return: open space ahead).
    EXPECT_TRUE(uav.talk(5s, [&] {
      const auto d = mcu.last_drive();
      return d.left_mmps != 0 || d.right_mmps != 0;
    }));
    // The UAV falls silent: the wheels stop and stay stopped.
    std::this_thread::sleep_for(1500ms);
    const auto held = mcu.last_drive();
    EXPECT_EQ(held.left_mmps, 0);
    EXPECT_EQ(held.right_mmps, 0);
    // Heard again, it carries on; then the UAV ends the search.
    EXPECT_TRUE(uav.talk(5s, [&] {
      const auto d = mcu.last_drive();
      return d.left_mmps != 0 || d.right_mmps != 0;
    }));
    uav.ugv.abort("the test is over");
    EXPECT_TRUE(uav.talk(5s, [&] { return uav.ugv.report().done; }));
  }
  process.join();
  ASSERT_TRUE(heard) << result.err;
  EXPECT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(first_line(result.err).rfind("backends: ugv.base: hw (" + mcu.port(), 0), 0u)
      << result.err;
  EXPECT_NE(result.out.find("searches: 1\n"), std::string::npos) << result.out;
  // It held at least once: while the UAV was silent. More holds are right too: a test
  // thread starved past the 0.5 s timeout on a loaded machine is, to the robot, a silent
  // UAV (a CI run under the sanitizer counted 2).
  const auto holds_at = result.out.find("holds: ");
  ASSERT_NE(holds_at, std::string::npos) << result.out;
  EXPECT_GE(std::stoi(result.out.substr(holds_at + 7)), 1) << result.out;
  EXPECT_NE(result.out.find("miniUGV search 1: aborted"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("stopped: duration"), std::string::npos) << result.out;
  // Its record: the one search as its controller saw it, ended before the process did.
  const auto record = nlohmann::json::parse(slurp(dir.path() / "record" / "report.json"));
  EXPECT_EQ(record.at("side"), "ugv");
  EXPECT_TRUE(record.at("ended_early").is_null()) << record.at("ended_early");
  EXPECT_EQ(record.at("backends").at("ugv.base"), "hw");
  ASSERT_EQ(record.at("ugv_deployments").size(), 1u);
  const auto& search = record.at("ugv_deployments").at(0);
  EXPECT_EQ(search.at("outcome"), "aborted");
  EXPECT_GT(search.at("time_s").get<double>(), 0.0);
  EXPECT_LT(search.at("deployed_s").get<double>() + search.at("time_s").get<double>(),
            record.at("time_s").get<double>() + 0.1);
  EXPECT_FALSE(record.contains("samples"));
}

TEST(RobotsOnHardware, TheUavTakesOffWithTheFlightAdapterAndTheWinchsServo) {
  TempDir dir;
  test::FakeDynamixel servo;
  const std::string d = dir.path().string();
  // The adapter's port is known once it listens: the script puts it in the mission YAML.
  // The servo's reply timeout is generous: the fake servo is a thread of this test, and
  // a loaded machine under the sanitizer starved it past the default 3 x 30 ms once.
  write_file(dir, "uav.yaml.in",
             "uav:\n  winch:\n    backend: hw\n    serial: {port: " + servo.port() +
                 ", timeout_ms: 500}\n  flight_controller:\n    backend: hw\n    address: "
                 "127.0.0.1:ADAPTER_PORT\n");
  const std::string script =
      "F='" + std::string(FERRET_CLI) + "'; D='" + d +
      "'\n"
      "timeout 300 \"$F\" flight-adapter serve --real-time --listen 127.0.0.1:0 --clients 1 --seed "
      "2 "
      ">\"$D/fa.out\" 2>\"$D/fa.err\" & FA=$!\n"
      "for i in $(seq 1200); do grep -q 'listening on' \"$D/fa.err\" && break; sleep 0.1; done\n"
      "P=$(sed -n 's/.*listening on 127.0.0.1:\\([0-9]*\\).*/\\1/p' \"$D/fa.err\")\n"
      "sed \"s/ADAPTER_PORT/$P/\" \"$D/uav.yaml.in\" >\"$D/uav.yaml\"\n"
      "timeout 300 \"$F\" uav --mission \"$D/uav.yaml\" --seed 2 --duration-s 10 --link-bind "
      "127.0.0.1:0 "
      "--link-peer 127.0.0.1:" +
      std::to_string(free_udp_port()) +
      " -o \"$D/record\" >\"$D/uav.out\" 2>\"$D/uav.err\"; U=$?\n"
      "wait $FA; A=$?\n"
      "echo \"$U $A\" >\"$D/codes\"\n";
  write_file(dir, "run.sh", script);
  ASSERT_EQ(std::system(("bash '" + d + "/run.sh'").c_str()), 0);
  const std::string err = slurp(dir.path() / "uav.err"), out = slurp(dir.path() / "uav.out");
  EXPECT_EQ(slurp(dir.path() / "codes"), "0 0\n") << err << slurp(dir.path() / "fa.err");
  EXPECT_EQ(
      first_line(err).rfind("backends: ugv.base: sim, uav.winch: hw (" + servo.port() + ")", 0), 0u)
      << err;
  EXPECT_NE(err.find("uav: flight adapter 'sim'"), std::string::npos) << err;
  // Within its ten seconds the vehicle took off and began its search pattern.
  EXPECT_NE(err.find("-> takeoff"), std::string::npos) << err;
  EXPECT_NE(err.find("takeoff -> search"), std::string::npos) << err;
  EXPECT_NE(out.find("stopped: duration"), std::string::npos) << out;
  // The winch was driven: torque on, and read at the control rate.
  EXPECT_EQ(servo.read_table(64, 1), 1u);
  EXPECT_GT(servo.requests(), 100);
  // Its record: cut short by the duration, its own readings of its flight and winch.
  const auto record = nlohmann::json::parse(slurp(dir.path() / "record" / "report.json"));
  EXPECT_EQ(record.at("side"), "uav");
  EXPECT_EQ(record.at("ended_early"), "the process ended (duration)");
  EXPECT_EQ(record.at("backends").at("uav.winch"), "hw");
  EXPECT_GT(record.at("summary").at("flown_m").get<double>(), 1.0);
  EXPECT_GE(record.at("samples").size(), 10u);
  EXPECT_FALSE(record.at("summary").contains("uav_collisions"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "record" / "mission.mcap"));
}

TEST(RobotsOnHardware, BadConfigurationExits2NamingTheField) {
  TempDir dir;
  // Half of the UAV on hardware: its own loop drives only hardware.
  const auto half = write_file(dir, "half.yaml",
                               "uav:\n  winch:\n    backend: hw\n    serial: {port: /dev/null}\n");
  auto r = run_cli("uav --mission " + half.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("uav.flight_controller.backend"), std::string::npos) << r.err;
  // A serial port that is not there.
  const auto missing = write_file(dir, "missing.yaml", ugv_mission("/dev/ferret-no-such-port"));
  r = run_cli("ugv --mission " + missing.string() + " --duration-s 1");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("ugv.base.serial.port"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/dev/ferret-no-such-port"), std::string::npos) << r.err;
  // The options of the other mode.
  r = run_cli("ugv --mission " + missing.string() + " --sim-world 127.0.0.1:47830");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--sim-world"), std::string::npos) << r.err;
  r = run_cli("ugv --link-bind 127.0.0.1:47811");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--link-bind"), std::string::npos) << r.err;
  r = run_cli("ugv --mission " + missing.string() + " --duration-s nan");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--duration-s"), std::string::npos) << r.err;
  // A link address that cannot be bound.
  const auto ok_port = write_file(dir, "ok.yaml", ugv_mission("/dev/null"));
  r = run_cli("ugv --mission " + ok_port.string() + " --link-bind 192.0.2.1:47811");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("192.0.2.1:47811"), std::string::npos) << r.err;
  // No flight adapter where the file says: the run fails (exit 1), naming the address.
  test::FakeDynamixel servo;
  const auto no_adapter =
      write_file(dir, "no_adapter.yaml",
                 "uav:\n  winch:\n    backend: hw\n    serial: {port: " + servo.port() +
                     "}\n  flight_controller:\n    backend: hw\n    address: 127.0.0.1:" +
                     std::to_string(free_udp_port()) + "\n");
  r = run_cli("uav --mission " + no_adapter.string() +
              " --link-bind 127.0.0.1:0 --link-peer 127.0.0.1:9");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("127.0.0.1:"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace ferret
