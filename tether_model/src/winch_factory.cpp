#include "ferret/tether_model/winch_factory.hpp"

#include <stdexcept>

#include "ferret/core/yaml_config.hpp"
#include "ferret/core/yaml_emit.hpp"

namespace ferret::tether {
namespace {

/// An optional integer in [lo, hi]; `what` says it in the error ("an integer in [1, 252]").
int integer_in(const yaml::MapReader& r, const char* key, int lo, int hi, int fallback,
               const std::string& what) {
  const int v = r.get_or<int>(key, fallback);
  if (v < lo || v > hi) r.fail(key, what, std::to_string(v));
  return v;
}

DynamixelWinch::Options read_dynamixel(const yaml::MapReader& root) {
  DynamixelWinch::Options o;
  const yaml::MapReader serial = root.child("serial");
  serial.allow_only({"port", "baud", "id", "timeout_ms", "retries"});
  o.port = serial.get<std::string>("port");
  if (o.port.empty())
    serial.fail("port", "the Dynamixel adapter's serial device (e.g. /dev/ttyUSB0)", "''");
  o.baud_rate =
      integer_in(serial, "baud", 9600, 4500000, o.baud_rate, "an integer in [9600, 4500000] baud");
  o.id = static_cast<std::uint8_t>(
      integer_in(serial, "id", 0, 252, o.id, "a Dynamixel id in [0, 252]"));
  o.bus.timeout_ms =
      integer_in(serial, "timeout_ms", 1, 1000, o.bus.timeout_ms, "an integer in [1, 1000] ms");
  o.bus.retries = integer_in(serial, "retries", 0, 10, o.bus.retries, "an integer in [0, 10]");
  if (const auto spool = root.optional_child("spool")) {
    spool->allow_only({"radius_m", "payout_direction", "max_speed_mps", "max_acceleration_mps2",
                       "initial_released_m", "tension_n_per_current_unit"});
    o.spool_radius_m = spool->get_in_range_or("radius_m", 1e-3, 1.0, o.spool_radius_m);
    o.payout_direction = spool->get_or<int>("payout_direction", o.payout_direction);
    if (o.payout_direction != 1 && o.payout_direction != -1)
      spool->fail("payout_direction", "1 or -1", std::to_string(o.payout_direction));
    o.max_speed_mps = spool->get_in_range_or("max_speed_mps", 1e-3, 10.0, o.max_speed_mps);
    o.max_acceleration_mps2 =
        spool->get_in_range_or("max_acceleration_mps2", 1e-3, 100.0, o.max_acceleration_mps2);
    o.initial_released_m =
        spool->get_in_range_or("initial_released_m", 0.0, 1000.0, o.initial_released_m);
    o.tension_n_per_current_unit = spool->get_in_range_or("tension_n_per_current_unit", 1e-6, 10.0,
                                                          o.tension_n_per_current_unit);
  }
  return o;
}

}  // namespace

WinchConfig winch_config_from_yaml(const YAML::Node& node, const std::string& source) {
  WinchConfig c;
  if (!node.IsDefined() || node.IsNull()) return c;
  const yaml::MapReader root(node, source, "uav.winch");
  root.allow_only({"backend", "serial", "spool"});
  c.backend = read_backend(root, winch_backends().names());
  if (!c.simulated() || has_device_settings(root)) c.hw = read_dynamixel(root);
  return c;
}

void emit_winch_config(YAML::Emitter& e, const WinchConfig& c) {
  e << YAML::BeginMap << YAML::Key << "backend" << YAML::Value << c.backend;
  if (c.hw) {
    const DynamixelWinch::Options& o = *c.hw;
    e << YAML::Key << "serial" << YAML::Value << YAML::BeginMap;
    e << YAML::Key << "port" << YAML::Value << o.port;
    e << YAML::Key << "baud" << YAML::Value << o.baud_rate;
    e << YAML::Key << "id" << YAML::Value << static_cast<int>(o.id);
    e << YAML::Key << "timeout_ms" << YAML::Value << o.bus.timeout_ms;
    e << YAML::Key << "retries" << YAML::Value << o.bus.retries << YAML::EndMap;
    internal::emit_key_number_map(e, "spool",
                                  {{"radius_m", o.spool_radius_m},
                                   {"payout_direction", static_cast<double>(o.payout_direction)},
                                   {"max_speed_mps", o.max_speed_mps},
                                   {"max_acceleration_mps2", o.max_acceleration_mps2},
                                   {"initial_released_m", o.initial_released_m},
                                   {"tension_n_per_current_unit", o.tension_n_per_current_unit}});
  }
  e << YAML::EndMap;
}

bool WinchConfig::simulated() const { return winch_backends().traits(backend).simulated; }

void register_builtin_winch_backends(WinchBackendRegistry& registry) {
  registry.add(
      "sim", "the simulated winch (SimulatedWinch; the simulator advances it)",
      [](const WinchBackendSetup& s) { return std::make_unique<SimulatedWinch>(s.sim); }, {},
      BackendTraits{.simulated = true});
  registry.add("hw", "a Dynamixel servo on a serial port (DynamixelWinch)",
               [](const WinchBackendSetup& s) -> std::unique_ptr<Winch> {
                 if (!s.config.hw)
                   throw std::invalid_argument("make_winch: backend hw without its options");
                 auto winch = std::make_unique<DynamixelWinch>(*s.config.hw);
                 (void)winch->connect();
                 return winch;
               });
}

const WinchBackendRegistry& winch_backends() {
  return filled_registry<WinchBackendRegistry, register_builtin_winch_backends>();
}

std::unique_ptr<Winch> make_winch(const WinchConfig& config, const SimulatedWinch::Options& sim) {
  return winch_backends().make(config.backend, {config, sim}, "make_winch", "uav.winch.backend");
}

}  // namespace ferret::tether
