// The flight controller's section: sim by default, hw only with the adapter's IPv4 address:port.
#include "ferret/uav/flight_controller_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"

namespace ferret {
namespace {

FlightControllerConfig parse(const std::string& text) {
  return flight_controller_config_from_yaml(yaml::load_string(text, "m.yaml"), "m.yaml");
}

TEST(FlightControllerConfig, SimByDefaultHwWithItsAddress) {
  EXPECT_EQ(flight_controller_config_from_yaml(YAML::Node(), "m.yaml").backend, "sim");
  const FlightControllerConfig c = parse("backend: hw\naddress: 127.0.0.1:47820\n");
  EXPECT_EQ(c.backend, "hw");
  EXPECT_EQ(c.address, "127.0.0.1:47820");
  EXPECT_TRUE(parse("backend: sim\n").address.empty());
}

TEST(FlightControllerConfig, TheBackendsAreARegistryAndAnotherNameListsThem) {
  EXPECT_EQ(flight_controller_backends().names(), (std::vector<std::string>{"sim", "hw"}));
  EXPECT_TRUE(parse("backend: sim\n").simulated());
  EXPECT_FALSE(parse("backend: hw\naddress: 127.0.0.1:47820\n").simulated());
  try {
    (void)parse("backend: mavlink\naddress: 127.0.0.1:14550\n");
    FAIL() << "an unregistered backend passed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "uav.flight_controller.backend");
    EXPECT_THAT(e.what(), ::testing::HasSubstr("one of sim, hw"));
  }
}

TEST(FlightControllerConfig, TheSimBackendIsTheSimulatorsToBuild) {
  const FlightControllerConfig sim = parse("backend: sim\n");
  EXPECT_THROW((void)make_flight_backend(sim), std::invalid_argument);
  bool called = false;
  (void)make_flight_backend(sim, [&](const FlightControllerConfig& c) {
    called = true;
    EXPECT_EQ(c.backend, "sim");
    return std::unique_ptr<FlightBackend>();
  });
  EXPECT_TRUE(called);
}

TEST(FlightControllerConfig, AnAddressThatIsNotHostColonPortIsNamed) {
  for (const char* address :
       {"10.0.0.1", ":14550", "10.0.0.1:", "10.0.0.1:65536", "10.0.0.1:-1", "10.0.0.1:1e3",
        "host name:80", "10.0.0.1:80 ", "m100.local:47820", "10.0.0.1:0"}) {
    try {
      (void)parse("backend: hw\naddress: '" + std::string(address) + "'\n");
      ADD_FAILURE() << "accepted " << address;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "uav.flight_controller.address") << address;
    }
  }
  EXPECT_EQ(parse("backend: hw\naddress: '10.0.0.1:1'\n").address, "10.0.0.1:1");
  EXPECT_EQ(parse("backend: hw\naddress: '10.0.0.1:65535'\n").address, "10.0.0.1:65535");
}

}  // namespace
}  // namespace ferret
