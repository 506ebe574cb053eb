#pragma once
// The flight controller chosen by configuration: `uav.flight_controller.backend` in the
// mission YAML, `sim` (the default: the simulator's point mass) or `hw` (the adapter on
// the M100's computer that speaks to DJI's onboard SDK, reached at `address`;
// docs/robots.md, "Backends"; the protocol and its client: docs/flight_adapter.md).
//
//   uav:
//     flight_controller: {backend: hw, address: 127.0.0.1:47820}

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>

#include "ferret/core/backend.hpp"

namespace ferret {

struct FlightControllerConfig {
  Backend backend = Backend::kSim;
  /// `hw`: the adapter's IPv4 address:port (dotted quad or localhost, port 1..65535);
  /// empty with `sim`, unless the file gives it (then checked the same way).
  std::string address;
};

/// Reads `uav.flight_controller` (`node` may be undefined or null: `sim`). Throws
/// InputError naming the file and the field for an unknown key, a backend other than sim
/// or hw, `hw` without an address, or an address that is not an IPv4 address:port.
[[nodiscard]] FlightControllerConfig flight_controller_config_from_yaml(const YAML::Node& node,
                                                                        const std::string& source);
/// The section as a mapping (backend first) that the reader reads back.
void emit_flight_controller_config(YAML::Emitter& e, const FlightControllerConfig& config);

}  // namespace ferret
