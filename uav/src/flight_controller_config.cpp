#include "ferret/uav/flight_controller_config.hpp"

#include "ferret/core/yaml_config.hpp"
#include "ferret/link/ip_address.hpp"

namespace ferret {

FlightControllerConfig flight_controller_config_from_yaml(const YAML::Node& node,
                                                          const std::string& source) {
  FlightControllerConfig c;
  if (!node.IsDefined() || node.IsNull()) return c;
  const yaml::MapReader r(node, source, "uav.flight_controller");
  r.allow_only({"backend", "address"});
  c.backend = read_backend(r);
  if (c.backend == Backend::kHw || has_device_settings(r)) {
    c.address = r.get<std::string>("address");
    // The robot link's address form: the adapter runs on the onboard computer, reached by
    // its IPv4 address (or localhost), as docs/flight_adapter.md's client connects.
    (void)link::parse_ipv4_address(c.address, r.source(), r.field_path("address"));
  }
  return c;
}

void emit_flight_controller_config(YAML::Emitter& e, const FlightControllerConfig& c) {
  e << YAML::BeginMap << YAML::Key << "backend" << YAML::Value << std::string(to_string(c.backend));
  if (!c.address.empty()) e << YAML::Key << "address" << YAML::Value << c.address;
  e << YAML::EndMap;
}

}  // namespace ferret
