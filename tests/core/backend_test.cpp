// The `backend` key of a hardware interface's section: sim by default, hw, nothing else.
#include "ferret/core/backend.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "ferret/core/error.hpp"

namespace ferret {
namespace {

yaml::MapReader section(const std::string& text) {
  return yaml::MapReader(yaml::load_string(text, "m.yaml"), "m.yaml", "uav.winch");
}

TEST(Backend, LeftOutIsSimAndTheTwoNamesReadAsThemselves) {
  EXPECT_EQ(read_backend(section("{}")), Backend::kSim);
  EXPECT_EQ(read_backend(section("backend: sim")), Backend::kSim);
  EXPECT_EQ(read_backend(section("backend: hw")), Backend::kHw);
  EXPECT_EQ(to_string(Backend::kSim), "sim");
  EXPECT_EQ(to_string(Backend::kHw), "hw");
}

TEST(Backend, AnythingElseNamesTheFieldAndTheChoices) {
  for (const char* text : {"backend: HW", "backend:", "backend: [hw]", "backend: 1"}) {
    try {
      (void)read_backend(section(text));
      ADD_FAILURE() << "accepted: " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "uav.winch.backend") << text;
      EXPECT_THAT(e.what(), ::testing::HasSubstr("m.yaml")) << text;
    }
  }
}

TEST(Backend, DeviceSettingsAreEveryKeyButBackend) {
  EXPECT_FALSE(has_device_settings(section("{}")));
  EXPECT_FALSE(has_device_settings(section("backend: hw")));
  EXPECT_TRUE(has_device_settings(section("port: /dev/ttyUSB0")));
  EXPECT_TRUE(has_device_settings(section("backend: sim\nport: /dev/ttyUSB0")));
}

}  // namespace
}  // namespace ferret
