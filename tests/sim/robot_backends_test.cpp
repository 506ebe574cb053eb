// The backend of each hardware interface from a mission YAML: sim by default, hw with
// its device settings, and every bad input an InputError naming the file and the field.
#include "ferret/sim/robot_backends.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/planning/mission_config.hpp"
#include "support/input_refusal.hpp"

namespace ferret {
namespace {

using ::testing::HasSubstr;

RobotBackends parse(const std::string& text) {
  return robot_backends_from_yaml(yaml::load_string(text, "m.yaml"), "m.yaml");
}

test::Refusal refusal(const std::string& text) {
  return test::refusal_of(text, "m.yaml", [](const std::string& t) { return parse(t); });
}

constexpr const char* kAllHw = R"(
ugv:
  base:
    backend: hw
    serial: {port: /dev/ttyAMA0, baud: 230400}
    camera: {device: /dev/video0}
    epm: {via: gpio, chip: gpiochip0, line: 17, active_low: true}
    odometry: {track_width_m: 0.13}
uav:
  winch:
    backend: hw
    serial: {port: /dev/ttyUSB0, baud: 1000000, id: 3}
    spool: {radius_m: 0.05, payout_direction: -1}
  flight_controller: {backend: hw, address: 192.168.1.20:14550}
)";

TEST(RobotBackends, TheShippedMissionAndAnEmptyFileMeanTheSimulatorEverywhere) {
  const auto shipped =
      load_robot_backends(std::filesystem::path(FERRET_SOURCE_DIR) / "config/mission.yaml");
  EXPECT_TRUE(shipped.all_sim());
  EXPECT_FALSE(shipped.ugv_base.hw || shipped.winch.hw);
  EXPECT_TRUE(parse("").all_sim());
  EXPECT_TRUE(parse("ugv: {}\nuav: {winch: {backend: sim}}\n").all_sim());
  EXPECT_EQ(parse("").summary(), "ugv.base: sim, uav.winch: sim, uav.flight_controller: sim");
}

TEST(RobotBackends, HwEverywhereCarriesEachDevicesSettings) {
  const RobotBackends b = parse(kAllHw);
  EXPECT_FALSE(b.all_sim());
  ASSERT_TRUE(b.ugv_base.hw && b.winch.hw);
  EXPECT_EQ(b.ugv_base.backend, "hw");
  EXPECT_EQ(b.ugv_base.hw->serial.baud, 230400);
  EXPECT_EQ(b.ugv_base.hw->epm.line, 17u);
  EXPECT_DOUBLE_EQ(b.ugv_base.hw->odometry.track_width_m, 0.13);
  EXPECT_EQ(b.winch.hw->port, "/dev/ttyUSB0");
  EXPECT_EQ(b.winch.hw->baud_rate, 1000000);
  EXPECT_EQ(b.winch.hw->id, 3);
  EXPECT_DOUBLE_EQ(b.winch.hw->spool_radius_m, 0.05);
  EXPECT_EQ(b.winch.hw->payout_direction, -1);
  EXPECT_DOUBLE_EQ(b.winch.hw->max_speed_mps, 0.6);  // a key left out keeps its default
  EXPECT_EQ(b.flight_controller.address, "192.168.1.20:14550");
  EXPECT_EQ(b.summary(),
            "ugv.base: hw (/dev/ttyAMA0), uav.winch: hw (/dev/ttyUSB0), "
            "uav.flight_controller: hw (192.168.1.20:14550)");
}

TEST(RobotBackends, TheDumpReadsBackToTheSameSettings) {
  // Device names that YAML would read as another type unless the dump quotes them.
  const std::string odd_names =
      "ugv: {base: {serial: {port: '~'}, camera: {device: 'null'}}}\n"
      "uav: {winch: {serial: {port: 'true'}}, flight_controller: {address: '10.0.0.1:80'}}\n";
  EXPECT_EQ(parse(robot_backends_to_yaml(parse(odd_names))).ugv_base.hw->serial.port, "~");
  for (const std::string& text : {std::string(kAllHw), std::string(""), odd_names}) {
    const std::string dump = robot_backends_to_yaml(parse(text));
    EXPECT_EQ(robot_backends_to_yaml(parse(dump)), dump) << dump;
  }
  const std::string dump = robot_backends_to_yaml(parse(kAllHw));
  EXPECT_THAT(dump, HasSubstr("backend: hw"));
  EXPECT_THAT(dump, HasSubstr("track_width_m: 0.13"));
  EXPECT_THAT(dump, HasSubstr("payout_direction: -1"));
  // Every interface says its backend, also when the file said nothing.
  const std::string defaults = robot_backends_to_yaml(parse(""));
  EXPECT_EQ(defaults,
            "ugv:\n  base:\n    backend: sim\n    stall_time_s: 0.3\n"
            "uav:\n  winch:\n    backend: sim\n  flight_controller:\n    backend: sim\n");
}

TEST(RobotBackends, SimulatedWithTheRobotsSettingsStillChecksThem) {
  // Switching a robot's file to the simulator is one line; the rest stays checked.
  const RobotBackends b =
      parse("ugv: {base: {backend: sim, serial: {port: /dev/ttyAMA0}, camera: {device: '0'}}}\n");
  EXPECT_EQ(b.ugv_base.backend, "sim");
  EXPECT_TRUE(b.ugv_base.hw);
  EXPECT_EQ(refusal("ugv: {base: {backend: sim, serial: {port: /dev/ttyAMA0, baud: 7}, "
                    "camera: {device: '0'}}}\n")
                .field,
            "ugv.base.serial.baud");
  EXPECT_EQ(refusal("uav: {flight_controller: {backend: sim, address: nowhere}}\n").field,
            "uav.flight_controller.address");
}

TEST(RobotBackends, BadInputNamesTheFieldAndWhatItShouldBe) {
  const struct {
    const char* yaml;
    const char* field;
    const char* expected;
  } cases[] = {
      {"ugv: {base: {backend: real}}\n", "ugv.base.backend", "one of sim, hw"},
      {"ugv: {base: {backend: }}\n", "ugv.base.backend", "one of sim, hw"},
      {"ugv: {base: {backend: [hw]}}\n", "ugv.base.backend", "a string"},
      {"ugv: {base: {backend: hw}}\n", "ugv.base.serial", "required field missing"},
      {"ugv: {base: {backend: hw, serial: {port: /dev/ttyAMA0}}}\n", "ugv.base.camera",
       "required field missing"},
      {"ugv: {base: {backend: hw, serial: {port: ''}, camera: {device: '0'}}}\n",
       "ugv.base.serial.port", "serial device"},
      {"ugv: {base: {backend: hw, serial: {port: /dev/ttyAMA0}, camera: {device: '0'}, "
       "odometry: {track_width_m: .nan}}}\n",
       "ugv.base.odometry.track_width_m", "a number in"},
      {"ugv: {base: {backend: hw, serial: {port: /dev/ttyAMA0, baud: fast}, "
       "camera: {device: '0'}}}\n",
       "ugv.base.serial.baud", "an integer"},
      {"ugv: {wheels: {}}\n", "ugv.wheels", "one of"},
      {"ugv: 5\n", "ugv", "mapping"},
      {"ugv:\n", "ugv", "mapping"},
      {"uav: {winch: {backend: hw}}\n", "uav.winch.serial", "required field missing"},
      {"uav: {winch: {backend: hw, serial: {port: /dev/ttyUSB0, id: 300}}}\n",
       "uav.winch.serial.id", "[0, 252]"},
      {"uav: {winch: {backend: hw, serial: {port: /dev/ttyUSB0}, spool: {radius_m: .nan}}}\n",
       "uav.winch.spool.radius_m", "a number in"},
      {"uav: {winch: {backend: hw, serial: {port: /dev/ttyUSB0}, spool: {radius_m: -0.1}}}\n",
       "uav.winch.spool.radius_m", "a number in"},
      {"uav: {winch: {backend: hw, serial: {port: /dev/ttyUSB0}, "
       "spool: {payout_direction: 2}}}\n",
       "uav.winch.spool.payout_direction", "1 or -1"},
      {"uav: {winch: {backend: sim, motor: x}}\n", "uav.winch.motor", "one of"},
      {"uav: {winch: {backend: ros}}\n", "uav.winch.backend", "one of sim, hw"},
      {"uav: {flight_controller: {backend: hw}}\n", "uav.flight_controller.address",
       "required field missing"},
      {"uav: {flight_controller: {backend: hw, address: 192.168.1.20}}\n",
       "uav.flight_controller.address", "an IPv4 address:port"},
      {"uav: {flight_controller: {backend: hw, address: '10.0.0.1:0'}}\n",
       "uav.flight_controller.address", "a port in 1..65535"},
      {"uav: {flight_controller: {backend: hw, address: 'a b:14550'}}\n",
       "uav.flight_controller.address", "an IPv4 address:port"},
      {"uav: {flight_controller: {backend: dji}}\n", "uav.flight_controller.backend",
       "one of sim, hw"},
      {"uav: {camera: {}}\n", "uav.camera", "one of"},
  };
  for (const auto& c : cases) {
    const test::Refusal r = refusal(c.yaml);
    EXPECT_EQ(r.field, c.field) << c.yaml << r.what;
    EXPECT_THAT(r.what, HasSubstr(c.expected)) << c.yaml;
    EXPECT_THAT(r.what, HasSubstr("m.yaml")) << c.yaml;
  }
}

TEST(RobotBackends, TheMissionLoaderLeavesTheBackendSectionsToThisReader) {
  const MissionConfig m = mission_config_from_yaml(yaml::load_string(kAllHw, "m.yaml"), "m.yaml");
  EXPECT_DOUBLE_EQ(m.tether.total_length_m, TetherParams{}.total_length_m);
}

TEST(RobotBackends, ACommandThatOnlySimulatesNamesTheFirstRealInterface) {
  require_all_sim(parse(""), "m.yaml", "why");
  try {
    require_all_sim(parse("uav: {winch: {backend: hw, serial: {port: /dev/ttyUSB0}}}\n"), "m.yaml",
                    "ferret mission simulates");
    FAIL() << "a hw winch passed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "uav.winch.backend");
    EXPECT_THAT(e.what(), HasSubstr("sim (ferret mission simulates)"));
  }
}

}  // namespace
}  // namespace ferret
