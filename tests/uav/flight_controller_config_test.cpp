// The flight controller's section: sim by default, hw only with the adapter's IPv4 address:port.
#include "ferret/uav/flight_controller_config.hpp"

#include <gtest/gtest.h>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"

namespace ferret {
namespace {

FlightControllerConfig parse(const std::string& text) {
  return flight_controller_config_from_yaml(yaml::load_string(text, "m.yaml"), "m.yaml");
}

TEST(FlightControllerConfig, SimByDefaultHwWithItsAddress) {
  EXPECT_EQ(flight_controller_config_from_yaml(YAML::Node(), "m.yaml").backend, Backend::kSim);
  const FlightControllerConfig c = parse("backend: hw\naddress: 127.0.0.1:47820\n");
  EXPECT_EQ(c.backend, Backend::kHw);
  EXPECT_EQ(c.address, "127.0.0.1:47820");
  EXPECT_TRUE(parse("backend: sim\n").address.empty());
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
