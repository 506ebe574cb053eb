// The winch's factory: `uav.winch` of a mission YAML picks the simulated spool or the
// Dynamixel servo, and the settings in the file are the ones the servo receives.
#include "ferret/tether_model/winch_factory.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "fake_dynamixel.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"

namespace ferret::tether {
namespace {

WinchConfig parse(const std::string& text) {
  return winch_config_from_yaml(yaml::load_string(text, "m.yaml"), "m.yaml");
}

TEST(WinchFactory, NoSectionIsTheSimulatedSpoolWithTheSimulatorsOptions) {
  const WinchConfig c = winch_config_from_yaml(YAML::Node(), "m.yaml");
  EXPECT_EQ(c.backend, "sim");
  SimulatedWinch::Options sim;
  sim.initial_released_m = 2.5;
  const std::unique_ptr<Winch> w = make_winch(c, sim);
  ASSERT_NE(dynamic_cast<SimulatedWinch*>(w.get()), nullptr);
  EXPECT_DOUBLE_EQ(w->read_state().released_m, 2.5);
}

TEST(WinchFactory, HwConnectsToTheServoWithTheFilesSettings) {
  test::FakeDynamixel fake(311, 3);
  const WinchConfig c = parse("backend: hw\nserial: {port: " + fake.port() +
                              ", id: 3, timeout_ms: 200}\n"
                              "spool: {radius_m: 0.05, max_acceleration_mps2: 2.0}\n");
  const std::unique_ptr<Winch> w = make_winch(c);
  ASSERT_NE(dynamic_cast<DynamixelWinch*>(w.get()), nullptr);
  // Connected: velocity mode and torque on, on the servo with id 3.
  EXPECT_EQ(fake.read_table(mx2::kOperatingMode, 1), 1u);
  EXPECT_EQ(fake.read_table(mx2::kTorqueEnable, 1), 1u);
  // 2 m/s^2 on the file's 5 cm spool (not the default 9 cm): 106.8 units of 214.577 rev/min^2.
  EXPECT_EQ(fake.read_table(mx2::kProfileAcceleration, 4), 107u);
}

TEST(WinchFactory, HwOnAMissingPortThrowsTheDriversError) {
  const WinchConfig c = parse("backend: hw\nserial: {port: /dev/ttyUSB_ferret_missing}\n");
  EXPECT_THROW((void)make_winch(c), SerialError);
}

TEST(WinchFactory, TheBackendsAreARegistryAndAnotherNameListsThem) {
  EXPECT_EQ(winch_backends().names(), (std::vector<std::string>{"sim", "hw"}));
  EXPECT_TRUE(parse("backend: sim\n").simulated());
  EXPECT_FALSE(parse("backend: hw\nserial: {port: /dev/ttyUSB0}\n").simulated());
  try {
    (void)parse("backend: ros\n");
    FAIL() << "an unregistered backend passed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "uav.winch.backend");
    EXPECT_THAT(e.what(), ::testing::HasSubstr("one of sim, hw"));
  }
  // A backend registered beside the built-ins is built by name.
  WinchBackendRegistry r;
  register_builtin_winch_backends(r);
  r.add("fixed", "a spool that reports 7 m", [](const WinchBackendSetup&) {
    SimulatedWinch::Options o;
    o.initial_released_m = 7.0;
    return std::make_unique<SimulatedWinch>(o);
  });
  EXPECT_DOUBLE_EQ(r.make("fixed", {}, "test")->read_state().released_m, 7.0);
}

TEST(WinchFactory, AnUnknownKeyIsNamed) {
  try {
    (void)parse("backend: hw\nserial: {port: /dev/ttyUSB0, speed: 1}\n");
    FAIL() << "an unknown key passed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "uav.winch.serial.speed");
  }
}

}  // namespace
}  // namespace ferret::tether
