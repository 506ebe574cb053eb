// The `backend` key of a hardware interface's section: sim by default, one of the
// interface's registered backends, nothing else.
#include "ferret/core/backend.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "ferret/core/error.hpp"

namespace ferret {
namespace {

yaml::MapReader section(const std::string& text) {
  return yaml::MapReader(yaml::load_string(text, "m.yaml"), "m.yaml", "uav.winch");
}

const std::vector<std::string> kNames{"sim", "hw", "ros"};

TEST(Backend, LeftOutIsSimAndRegisteredNamesReadAsThemselves) {
  EXPECT_EQ(read_backend(section("{}"), kNames), "sim");
  EXPECT_EQ(read_backend(section("backend: sim"), kNames), "sim");
  EXPECT_EQ(read_backend(section("backend: hw"), kNames), "hw");
  EXPECT_EQ(read_backend(section("backend: ros"), kNames), "ros");
}

TEST(Backend, AnythingElseNamesTheFieldAndListsTheRegisteredOnes) {
  for (const char* text : {"backend: HW", "backend:", "backend: [hw]", "backend: 1"}) {
    try {
      (void)read_backend(section(text), kNames);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "uav.winch.backend") << text;
      EXPECT_THAT(e.what(), ::testing::HasSubstr("m.yaml")) << text;
    }
  }
  try {
    (void)read_backend(section("backend: mavlink"), kNames);
    ADD_FAILURE() << "accepted an unregistered name";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("one of sim, hw, ros"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("mavlink"));
  }
}

TEST(Backend, ARegistryOfBackendsKeepsEachOnesTraits) {
  struct Device {
    virtual ~Device() = default;
  };
  BackendRegistry<Device, int> r;
  r.add(
      "sim", "simulated", [](const int&) { return std::make_unique<Device>(); }, {},
      BackendTraits{.simulated = true});
  r.add("hw", "a device", [](const int&) { return std::make_unique<Device>(); });
  EXPECT_TRUE(r.traits("sim").simulated);
  EXPECT_FALSE(r.traits("hw").simulated);
  EXPECT_THROW((void)r.traits("ros"), std::logic_error);
  EXPECT_EQ(r.expected(), "one of sim, hw");
}

TEST(Backend, DeviceSettingsAreEveryKeyButBackend) {
  EXPECT_FALSE(has_device_settings(section("{}")));
  EXPECT_FALSE(has_device_settings(section("backend: hw")));
  EXPECT_TRUE(has_device_settings(section("port: /dev/ttyUSB0")));
  EXPECT_TRUE(has_device_settings(section("backend: sim\nport: /dev/ttyUSB0")));
}

}  // namespace
}  // namespace ferret
