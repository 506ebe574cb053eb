// The miniUGV base's factory: `ugv.base` of a mission YAML picks the simulator's base
// (built by the simulator's own factory) or HwUgvBase on the MCU's serial port.
#include "ferret/ugv/ugv_base_factory.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "fake_ugv_mcu.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/ugv/hw_ugv_base.hpp"

namespace ferret::ugv {
namespace {

const RobotDescription& miniugv() {
  static const RobotDescription robot = load_robot("miniugv");
  return robot;
}

UgvBaseConfig parse(const std::string& text) {
  return ugv_base_config_from_yaml(yaml::load_string(text, "m.yaml"), "m.yaml");
}

TEST(UgvBaseFactory, SimIsBuiltByTheSimulatorsFactoryWithTheContext) {
  const UgvBaseConfig c = ugv_base_config_from_yaml(YAML::Node(), "m.yaml");
  EXPECT_EQ(c.backend, "sim");
  const Pose2 start{1.0, 2.0, 0.5};
  bool called = false;
  const UgvBaseFactory sim = [&](const UgvBaseConfig&, const UgvBaseContext& context) {
    called = true;
    EXPECT_EQ(context.X_WG_start.x_m, 1.0);
    return std::unique_ptr<UgvBase>();
  };
  (void)make_ugv_base(c, {miniugv(), {}, start}, sim);
  EXPECT_TRUE(called);
  EXPECT_THROW((void)make_ugv_base(c, {miniugv(), {}, start}), std::invalid_argument);
}

TEST(UgvBaseFactory, HwBringsUpTheRealBaseOnTheFilesPort) {
  test::FakeUgvMcu fake;
  const UgvBaseConfig c = parse("backend: hw\nserial: {port: " + fake.port() +
                                "}\ncamera: {device: none}\nlink: {connect_timeout_s: 5}\n");
  ASSERT_TRUE(c.hw);
  bool sim_called = false;
  const auto base = make_ugv_base(c, {miniugv(), {}, Pose2{0.5, 0.0, 0.0}},
                                  [&](const UgvBaseConfig&, const UgvBaseContext&) {
                                    sim_called = true;
                                    return std::unique_ptr<UgvBase>();
                                  });
  ASSERT_NE(dynamic_cast<HwUgvBase*>(base.get()), nullptr);
  EXPECT_FALSE(sim_called);
  EXPECT_EQ(base->backend(), "hw");
  EXPECT_DOUBLE_EQ(base->odometry().x_m, 0.5);  // the context's start pose
}

TEST(UgvBaseFactory, TheBackendsAreARegistryAndAnotherNameListsThem) {
  EXPECT_EQ(ugv_base_backends().names(), (std::vector<std::string>{"sim", "hw"}));
  EXPECT_TRUE(parse("backend: sim\n").simulated());
  EXPECT_FALSE(
      parse("backend: hw\nserial: {port: /dev/ttyAMA0}\ncamera: {device: '0'}\n").simulated());
  try {
    (void)parse("backend: ros\n");
    FAIL() << "an unregistered backend passed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "ugv.base.backend");
    EXPECT_NE(std::string(e.what()).find("one of sim, hw"), std::string::npos) << e.what();
  }
}

TEST(UgvBaseFactory, TheBackendKeyAloneIsNotHardwareSettings) {
  EXPECT_FALSE(parse("backend: sim\n").hw);
  EXPECT_THROW((void)parse("backend: hw\n"), InputError);  // hw needs its port and camera
}

TEST(UgvBaseFactory, TheStallTimeIsEveryBackendsAndChecked) {
  EXPECT_EQ(parse("backend: sim\n").stall_time_s, 0.3);
  // Not a device setting: the simulated base stays without hardware settings.
  const UgvBaseConfig sim = parse("backend: sim\nstall_time_s: 0.8\n");
  EXPECT_EQ(sim.stall_time_s, 0.8);
  EXPECT_FALSE(sim.hw);
  const UgvBaseConfig hw = parse(
      "backend: hw\nstall_time_s: 1.5\nserial: {port: /dev/ttyAMA0}\ncamera: {device: '0'}\n");
  EXPECT_EQ(hw.stall_time_s, 1.5);
  ASSERT_TRUE(hw.hw);
  EXPECT_EQ(hw.hw->serial.port, "/dev/ttyAMA0");
  for (const char* bad : {"0", "0.01", "11", ".nan", ".inf", "-1", "soon", "[1]"}) {
    try {
      (void)parse(std::string("backend: sim\nstall_time_s: ") + bad + "\n");
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "ugv.base.stall_time_s") << bad;
    }
  }
  // A sim section still refuses a key nobody reads.
  try {
    (void)parse("backend: sim\nstall_tme_s: 1\n");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "ugv.base.stall_tme_s");
  }
}

}  // namespace
}  // namespace ferret::ugv
