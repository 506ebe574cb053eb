#pragma once
// The winch chosen by configuration: `uav.winch.backend` in the mission YAML, `sim` (the
// default: SimulatedWinch) or `hw` (DynamixelWinch on a serial port; docs/robots.md,
// "Backends").
//
//   uav:
//     winch:
//       backend: hw
//       serial: {port: /dev/ttyUSB0, baud: 57600, id: 1}
//       spool: {radius_m: 0.09, payout_direction: 1, max_speed_mps: 0.6}

#include <yaml-cpp/yaml.h>

#include <memory>
#include <optional>
#include <string>

#include "ferret/core/backend.hpp"
#include "ferret/tether_model/dynamixel_winch.hpp"
#include "ferret/tether_model/simulated_winch.hpp"

namespace ferret::tether {

struct WinchConfig {
  Backend backend = Backend::kSim;
  /// The servo's settings: required with `backend: hw` (serial.port at least); with
  /// `sim`, checked when the section has them, unused.
  std::optional<DynamixelWinch::Options> hw;
};

/// Reads `uav.winch` (`node` may be undefined or null: `sim`). Throws InputError naming
/// the file and the field for an unknown key, a backend other than sim or hw, `hw`
/// without serial.port, a number out of range (NaN, a negative spool radius ...) or a key
/// without a value.
[[nodiscard]] WinchConfig winch_config_from_yaml(const YAML::Node& node, const std::string& source);
/// The section as a mapping (backend first) that winch_config_from_yaml reads back.
void emit_winch_config(YAML::Emitter& e, const WinchConfig& config);

/// The backend `config` names. `hw` opens the port and connects to the servo (velocity
/// mode, torque on): it throws SerialError for a port that cannot be opened and
/// DynamixelError for a servo that does not answer or is not an accepted model. `sim`
/// is a SimulatedWinch with `sim` (the simulator advances it; only its owner can).
[[nodiscard]] std::unique_ptr<Winch> make_winch(const WinchConfig& config,
                                                const SimulatedWinch::Options& sim = {});

}  // namespace ferret::tether
