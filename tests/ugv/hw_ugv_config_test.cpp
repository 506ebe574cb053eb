// The hardware backend's YAML section: defaults, every choice, and bad input named by
// its field.
#include "ferret/ugv/hw_ugv_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"

namespace ferret::ugv {
namespace {

using ::testing::HasSubstr;

HwUgvConfig parse(const std::string& base_yaml) {
  const YAML::Node doc = yaml::load_string(base_yaml, "mission.yaml");
  return hw_ugv_config_from_yaml(doc, "mission.yaml");
}

/// The InputError's field and message for a config that must be refused.
std::pair<std::string, std::string> refusal(const std::string& base_yaml) {
  try {
    (void)parse(base_yaml);
  } catch (const InputError& e) {
    return {e.field(), e.what()};
  }
  ADD_FAILURE() << "accepted: " << base_yaml;
  return {};
}

constexpr const char* kMinimal = "serial: {port: /dev/ttyAMA0}\ncamera: {device: /dev/video0}\n";

TEST(HwUgvConfig, TheBriefsExampleParses) {
  const HwUgvConfig c = parse(R"(backend: hw
serial: {port: /dev/ttyAMA0, baud: 115200}
camera: {device: /dev/video0}
epm: {via: gpio, chip: gpiochip0, line: 17}
odometry: {wheel_radius_m: 0.021, ticks_per_rev: 360, track_width_m: 0.1}
)");
  EXPECT_EQ(c.serial.port, "/dev/ttyAMA0");
  EXPECT_EQ(c.serial.baud, 115200);
  EXPECT_EQ(c.camera.device, "/dev/video0");
  EXPECT_EQ(c.epm.via, HwUgvConfig::Epm::Via::kGpio);
  EXPECT_EQ(c.epm.chip, "gpiochip0");
  EXPECT_EQ(c.epm.line, 17u);
  EXPECT_DOUBLE_EQ(c.odometry.wheel_radius_m, 0.021);
  EXPECT_DOUBLE_EQ(c.odometry.ticks_per_rev, 360.0);
  EXPECT_DOUBLE_EQ(c.odometry.track_width_m, 0.1);
  EXPECT_EQ(c.source, "mission.yaml");
}

TEST(HwUgvConfig, LeftOutKeysTakeTheDocumentedDefaults) {
  const HwUgvConfig c = parse(kMinimal);
  const HwUgvConfig d;
  EXPECT_EQ(c.serial.baud, 115200);
  EXPECT_EQ(c.epm.via, HwUgvConfig::Epm::Via::kMcu);
  EXPECT_DOUBLE_EQ(c.link.telemetry_timeout_s, d.link.telemetry_timeout_s);
  EXPECT_DOUBLE_EQ(c.link.command_rate_hz, 20.0);
  EXPECT_DOUBLE_EQ(c.odometry.wheel_radius_m, 0.02);
  EXPECT_DOUBLE_EQ(c.odometry.track_width_m, 0.105);
  EXPECT_DOUBLE_EQ(c.odometry.ticks_per_rev, 360.0);
}

TEST(HwUgvConfig, ACameraIsAnIndexAPathAFileOrNone) {
  EXPECT_EQ(parse("serial: {port: /dev/serial0}\ncamera: {device: 0}\n").camera.device, "0");
  EXPECT_EQ(parse("serial: {port: /dev/serial0}\ncamera: {device: none}\n").camera.device, "none");
  EXPECT_EQ(parse("serial: {port: /dev/serial0}\ncamera: {device: run.avi}\n").camera.device,
            "run.avi");
}

TEST(HwUgvConfig, AnUnknownKeyIsNamedWithItsPath) {
  const auto [field, what] =
      refusal("serial: {port: /dev/ttyAMA0, baudrate: 9600}\ncamera: {device: 0}\n");
  EXPECT_EQ(field, "ugv.base.serial.baudrate");
  EXPECT_THAT(what, HasSubstr("one of: port, baud"));
  EXPECT_EQ(refusal(std::string(kMinimal) + "wheels: {}\n").first, "ugv.base.wheels");
}

TEST(HwUgvConfig, AMissingPortOrCameraIsNamed) {
  EXPECT_EQ(refusal("serial: {baud: 115200}\ncamera: {device: 0}\n").first, "ugv.base.serial.port");
  EXPECT_EQ(refusal("camera: {device: 0}\n").first, "ugv.base.serial");
  EXPECT_EQ(refusal("serial: {port: ''}\ncamera: {device: 0}\n").first, "ugv.base.serial.port");
  EXPECT_EQ(refusal("serial: {port: /dev/ttyAMA0}\n").first, "ugv.base.camera");
  EXPECT_EQ(refusal("serial: {port: /dev/ttyAMA0}\ncamera: {}\n").first, "ugv.base.camera.device");
}

TEST(HwUgvConfig, BadNumbersAreNamedWithWhatWasExpected) {
  const std::string head = kMinimal;
  auto [f1, w1] = refusal(head + "odometry: {wheel_radius_m: -0.02}\n");
  EXPECT_EQ(f1, "ugv.base.odometry.wheel_radius_m");
  EXPECT_THAT(w1, HasSubstr("-0.02"));
  EXPECT_EQ(refusal(head + "odometry: {track_width_m: .nan}\n").first,
            "ugv.base.odometry.track_width_m");
  EXPECT_EQ(refusal(head + "odometry: {track_width_m: nan}\n").first,
            "ugv.base.odometry.track_width_m");
  EXPECT_EQ(refusal(head + "odometry: {ticks_per_rev: 0}\n").first,
            "ugv.base.odometry.ticks_per_rev");
  EXPECT_EQ(refusal(head + "odometry: {ticks_per_rev: 12.5}\n").first,
            "ugv.base.odometry.ticks_per_rev");
  EXPECT_EQ(refusal(head + "link: {telemetry_timeout_s: 0}\n").first,
            "ugv.base.link.telemetry_timeout_s");
  EXPECT_EQ(refusal(head + "link: {command_rate_hz: inf}\n").first,
            "ugv.base.link.command_rate_hz");
  EXPECT_EQ(refusal(head + "link: {command_timeout_s:}\n").first,
            "ugv.base.link.command_timeout_s");
  EXPECT_EQ(refusal("serial: {port: /dev/ttyAMA0, baud: 12}\ncamera: {device: 0}\n").first,
            "ugv.base.serial.baud");
  EXPECT_EQ(refusal("serial: {port: /dev/ttyAMA0, baud: fast}\ncamera: {device: 0}\n").first,
            "ugv.base.serial.baud");
}

TEST(HwUgvConfig, TheEpmChoiceIsChecked) {
  const std::string head = kMinimal;
  auto [f, w] = refusal(head + "epm: {via: relay}\n");
  EXPECT_EQ(f, "ugv.base.epm.via");
  EXPECT_THAT(w, HasSubstr("mcu, gpio"));
  EXPECT_EQ(refusal(head + "epm: {via: gpio, line: 17}\n").first, "ugv.base.epm.chip");
  EXPECT_EQ(refusal(head + "epm: {via: gpio, chip: gpiochip0}\n").first, "ugv.base.epm.line");
  EXPECT_EQ(refusal(head + "epm: {via: gpio, chip: gpiochip0, line: -1}\n").first,
            "ugv.base.epm.line");
  EXPECT_EQ(refusal(head + "epm: {via: mcu, line: 4}\n").first, "ugv.base.epm.line");
  EXPECT_TRUE(parse(head + "epm: {via: gpio, chip: /dev/gpiochip0, line: 4, active_low: true}\n")
                  .epm.active_low);
}

TEST(HwUgvConfig, TheBackendKeyIsCheckedButNotChosenHere) {
  EXPECT_EQ(refusal(std::string(kMinimal) + "backend: simulator\n").first, "ugv.base.backend");
  EXPECT_EQ(parse(std::string(kMinimal) + "backend: sim\n").serial.port,
            parse(kMinimal).serial.port);
}

TEST(HwUgvConfig, CheckNamesTheFieldOfAConfigBuiltInCode) {
  HwUgvConfig c;
  c.serial.port = "/dev/ttyAMA0";
  c.camera.device = "0";
  c.odometry.wheel_radius_m = -1.0;
  try {
    c.check();
    FAIL() << "a negative radius passed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "ugv.base.odometry.wheel_radius_m");
    EXPECT_EQ(e.source(), "defaults");
  }
}

}  // namespace
}  // namespace ferret::ugv
