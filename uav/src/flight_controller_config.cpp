#include "ferret/uav/flight_controller_config.hpp"

#include <stdexcept>

#include "ferret/core/yaml_config.hpp"
#include "ferret/link/ip_address.hpp"
#include "ferret/link/message_stream.hpp"
#include "ferret/uav/adapter_flight_controller.hpp"

namespace ferret {
namespace {

// The vehicle's flight adapter over TCP: the connection lives as long as its client.
class AdapterFlightBackend final : public FlightBackend {
 public:
  AdapterFlightBackend(link::MessageStream stream, int reply_timeout_ms)
      : channel_(std::move(stream), reply_timeout_ms), flight_(channel_, "hw") {}
  FlightController& flight() override { return flight_; }
  UavCameras& cameras() override { return flight_; }
  [[nodiscard]] std::string peer_name() const override { return flight_.adapter_name(); }

 private:
  link::StreamRpcChannel channel_;
  AdapterFlightController flight_;
};

}  // namespace

FlightControllerConfig flight_controller_config_from_yaml(const YAML::Node& node,
                                                          const std::string& source) {
  FlightControllerConfig c;
  if (!node.IsDefined() || node.IsNull()) return c;
  const yaml::MapReader r(node, source, "uav.flight_controller");
  r.allow_only({"backend", "address"});
  c.backend = read_backend(r, flight_controller_backends().names());
  if (!c.simulated() || has_device_settings(r)) {
    c.address = r.get<std::string>("address");
    // The robot link's address form: the adapter runs on the onboard computer, reached by
    // its IPv4 address (or localhost), as docs/flight_adapter.md's client connects.
    (void)link::parse_ipv4_address(c.address, r.source(), r.field_path("address"));
  }
  return c;
}

void emit_flight_controller_config(YAML::Emitter& e, const FlightControllerConfig& c) {
  e << YAML::BeginMap << YAML::Key << "backend" << YAML::Value << c.backend;
  if (!c.address.empty()) e << YAML::Key << "address" << YAML::Value << c.address;
  e << YAML::EndMap;
}

bool FlightControllerConfig::simulated() const {
  return flight_controller_backends().traits(backend).simulated;
}

void register_builtin_flight_controller_backends(FlightControllerBackendRegistry& registry) {
  registry.add(
      "sim", "the simulated M100 (built by the simulator, which owns the world)",
      [](const FlightBackendSetup& s) {
        if (!s.sim)
          throw std::invalid_argument(
              "make_flight_backend: backend sim without the simulator's factory");
        return s.sim(s.config);
      },
      {}, BackendTraits{.simulated = true});
  registry.add("hw", "the M100's flight adapter at `address` (AdapterFlightController)",
               [](const FlightBackendSetup& s) -> std::unique_ptr<FlightBackend> {
                 // The reader checked the address; a bad one here is a caller's config.
                 const link::Ipv4Address address = link::parse_ipv4_address(
                     s.config.address, "make_flight_backend", "uav.flight_controller.address");
                 return std::make_unique<AdapterFlightBackend>(
                     link::MessageStream::connect(address, 5.0), s.reply_timeout_ms);
               });
}

const FlightControllerBackendRegistry& flight_controller_backends() {
  return filled_registry<FlightControllerBackendRegistry,
                         register_builtin_flight_controller_backends>();
}

std::unique_ptr<FlightBackend> make_flight_backend(const FlightControllerConfig& config,
                                                   const FlightBackendFactory& sim,
                                                   int reply_timeout_ms) {
  return flight_controller_backends().make(config.backend, {config, sim, reply_timeout_ms},
                                           "make_flight_backend", "uav.flight_controller.backend");
}

}  // namespace ferret
