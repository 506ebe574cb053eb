#pragma once
// The flight controller chosen by configuration: `uav.flight_controller.backend` in the
// mission YAML, `sim` (the default: the simulator's point mass) or `hw` (the adapter on
// the M100's computer that speaks to DJI's onboard SDK, reached at `address`;
// docs/robots.md, "Backends"). The hw client is not part of ferret yet: this is its
// configuration, read and checked so that a robot's file is complete.
//
//   uav:
//     flight_controller: {backend: hw, address: 192.168.1.20:14550}

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <string>

#include "ferret/core/backend.hpp"

namespace ferret {

struct FlightControllerConfig {
  Backend backend = Backend::kSim;
  /// `hw`: the adapter's HOST:PORT (a name or an address, and a port in [1, 65535]);
  /// empty with `sim`, unless the file gives it (then checked the same way).
  std::string address;
};

/// Reads `uav.flight_controller` (`node` may be undefined or null: `sim`). Throws
/// InputError naming the file and the field for an unknown key, a backend other than sim
/// or hw, `hw` without an address, or an address that is not HOST:PORT.
[[nodiscard]] FlightControllerConfig flight_controller_config_from_yaml(const YAML::Node& node,
                                                                        const std::string& source);
/// The section as a mapping (backend first) that the reader reads back.
void emit_flight_controller_config(YAML::Emitter& e, const FlightControllerConfig& config);

}  // namespace ferret
