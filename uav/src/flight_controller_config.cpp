#include "ferret/uav/flight_controller_config.hpp"

#include <algorithm>

#include "ferret/core/number.hpp"
#include "ferret/core/yaml_config.hpp"

namespace ferret {
namespace {

constexpr const char* kAddress =
    "HOST:PORT, the flight-controller adapter (e.g. 192.168.1.20:14550)";

/// A host name or address (letters, digits, '.', '-', '_') and a decimal port in [1, 65535].
void check_address(const yaml::MapReader& r, const std::string& text) {
  const std::string got = yaml::internal::describe(r.node()["address"]);
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0) r.fail("address", kAddress, got);
  const std::string host = text.substr(0, colon);
  const bool host_ok = std::all_of(host.begin(), host.end(), [](char ch) {
    return (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') ||
           ch == '.' || ch == '-' || ch == '_';
  });
  const std::string port = text.substr(colon + 1);
  const bool port_digits = !port.empty() && std::all_of(port.begin(), port.end(), [](char ch) {
    return ch >= '0' && ch <= '9';
  });  // parse_integer would forgive the spaces around it
  if (!host_ok || !port_digits) r.fail("address", kAddress, got);
  try {
    (void)parse_integer(port, 1, 65535, r.source(), r.field_path("address"));
  } catch (const InputError&) {
    r.fail("address", kAddress, got);  // the whole address, not just its port, in the message
  }
}

}  // namespace

FlightControllerConfig flight_controller_config_from_yaml(const YAML::Node& node,
                                                          const std::string& source) {
  FlightControllerConfig c;
  if (!node.IsDefined() || node.IsNull()) return c;
  const yaml::MapReader r(node, source, "uav.flight_controller");
  r.allow_only({"backend", "address"});
  c.backend = read_backend(r);
  if (c.backend == Backend::kHw || has_device_settings(r)) {
    c.address = r.get<std::string>("address");
    check_address(r, c.address);
  }
  return c;
}

void emit_flight_controller_config(YAML::Emitter& e, const FlightControllerConfig& c) {
  e << YAML::BeginMap << YAML::Key << "backend" << YAML::Value << std::string(to_string(c.backend));
  if (!c.address.empty()) e << YAML::Key << "address" << YAML::Value << c.address;
  e << YAML::EndMap;
}

}  // namespace ferret
