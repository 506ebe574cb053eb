#pragma once
// The winch chosen by configuration: `uav.winch.backend` in the mission YAML names one of
// winch_backends(), `sim` (the default: SimulatedWinch) or `hw` (DynamixelWinch on a
// serial port; docs/robots.md, "Backends"). A new backend is one class and one add() line
// in register_builtin_winch_backends() (with its settings, a member of WinchConfig read
// here).
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
  std::string backend = std::string(kSimBackend);  ///< a name of winch_backends()
  /// The servo's settings: required with `backend: hw` (serial.port at least); with
  /// `sim`, checked when the section has them, unused.
  std::optional<DynamixelWinch::Options> hw;

  /// True when the simulated world serves the backend (winch_backends()' traits).
  [[nodiscard]] bool simulated() const;
};

/// What a winch backend is built from.
struct WinchBackendSetup {
  WinchConfig config;
  SimulatedWinch::Options sim;  ///< the `sim` backend's
};

using WinchBackendRegistry = BackendRegistry<Winch, WinchBackendSetup>;

/// Adds "sim" and "hw".
void register_builtin_winch_backends(WinchBackendRegistry& registry);
/// The winch backends, registered on first use.
[[nodiscard]] const WinchBackendRegistry& winch_backends();

/// Reads `uav.winch` (`node` may be undefined or null: `sim`). Throws InputError naming
/// the file and the field for an unknown key, a backend not registered (listing them), `hw`
/// without serial.port, a number out of range (NaN, a negative spool radius ...) or a key
/// without a value.
[[nodiscard]] WinchConfig winch_config_from_yaml(const YAML::Node& node, const std::string& source);
/// The section as a mapping (backend first) that winch_config_from_yaml reads back.
void emit_winch_config(YAML::Emitter& e, const WinchConfig& config);

/// The backend `config` names, from winch_backends(). `hw` opens the port and connects to the servo
/// (velocity mode, torque on): it throws SerialError for a port that cannot be opened and
/// DynamixelError for a servo that does not answer or is not an accepted model. `sim`
/// is a SimulatedWinch with `sim` (the simulator advances it; only its owner can).
[[nodiscard]] std::unique_ptr<Winch> make_winch(const WinchConfig& config,
                                                const SimulatedWinch::Options& sim = {});

}  // namespace ferret::tether
