#pragma once
// The flight controller chosen by configuration: `uav.flight_controller.backend` in the
// mission YAML names one of flight_controller_backends(), `sim` (the default: the
// simulator's point mass) or `hw` (the adapter on the M100's computer that speaks to DJI's
// onboard SDK, reached at `address`; docs/robots.md, "Backends"; the protocol and its
// client: docs/flight_adapter.md). A new backend is one class and one add() line in
// register_builtin_flight_controller_backends().
//
//   uav:
//     flight_controller: {backend: hw, address: 127.0.0.1:47820}

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "ferret/core/backend.hpp"
#include "ferret/uav/flight_controller.hpp"

namespace ferret {

struct FlightControllerConfig {
  std::string backend = std::string(kSimBackend);  ///< a name of flight_controller_backends()
  /// `hw`: the adapter's IPv4 address:port (dotted quad or localhost, port 1..65535);
  /// empty with `sim`, unless the file gives it (then checked the same way).
  std::string address;

  /// True when the simulated world serves the backend (its registry's traits).
  [[nodiscard]] bool simulated() const;
};

/// Reads `uav.flight_controller` (`node` may be undefined or null: `sim`). Throws
/// InputError naming the file and the field for an unknown key, a backend not registered
/// (listing them), `hw` without an address, or an address that is not an IPv4 address:port.
[[nodiscard]] FlightControllerConfig flight_controller_config_from_yaml(const YAML::Node& node,
                                                                        const std::string& source);
/// The section as a mapping (backend first) that the reader reads back.
void emit_flight_controller_config(YAML::Emitter& e, const FlightControllerConfig& config);

/// A flight controller and the cameras it serves, as one backend brings them up (the
/// mission takes both from the same vehicle).
class FlightBackend {
 public:
  virtual ~FlightBackend() = default;
  [[nodiscard]] virtual FlightController& flight() = 0;
  [[nodiscard]] virtual UavCameras& cameras() = 0;
  /// What the far end said it is (the flight adapter's hello: "sim", "dji-osdk", ...).
  [[nodiscard]] virtual std::string peer_name() const = 0;
};

using FlightBackendFactory =
    std::function<std::unique_ptr<FlightBackend>(const FlightControllerConfig&)>;

/// What a backend is built from.
struct FlightBackendSetup {
  const FlightControllerConfig& config;
  const FlightBackendFactory& sim;  ///< builds the `sim` backend (the simulator's owner)
  int reply_timeout_ms = 2000;      ///< `hw`: how long the adapter may take to answer
};

using FlightControllerBackendRegistry = BackendRegistry<FlightBackend, FlightBackendSetup>;

/// Adds "sim" and "hw".
void register_builtin_flight_controller_backends(FlightControllerBackendRegistry& registry);
/// The flight controller's backends, registered on first use.
[[nodiscard]] const FlightControllerBackendRegistry& flight_controller_backends();

/// The backend `config` names: `hw` connects to the flight adapter at config.address and
/// greets it (throws link::StreamError / FlightAdapterError as AdapterFlightController
/// does); `sim` calls `sim`. @throws std::invalid_argument for `sim` without a factory.
[[nodiscard]] std::unique_ptr<FlightBackend> make_flight_backend(
    const FlightControllerConfig& config, const FlightBackendFactory& sim = {},
    int reply_timeout_ms = 2000);

}  // namespace ferret
