#include "ferret/sim/robot_backends.hpp"

#include <tuple>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/uav/uav_mission_config.hpp"
#include "ferret/ugv/ugv_mission_config.hpp"

namespace ferret {

std::string RobotBackends::summary() const {
  // A device's backend says where the device is.
  auto with = [](const std::string& backend, bool simulated, const std::string& device) {
    return backend + (simulated ? "" : " (" + device + ")");
  };
  return "ugv.base: " +
         with(ugv_base.backend, ugv_base.simulated(), ugv_base.hw ? ugv_base.hw->serial.port : "") +
         ", uav.winch: " + with(winch.backend, winch.simulated(), winch.hw ? winch.hw->port : "") +
         ", uav.flight_controller: " +
         with(flight_controller.backend, flight_controller.simulated(), flight_controller.address);
}

bool RobotBackends::all_sim() const {
  return ugv_base.simulated() && winch.simulated() && flight_controller.simulated();
}

RobotBackends robot_backends_from_yaml(const YAML::Node& root, const std::string& source) {
  RobotBackends b;
  if (!root.IsDefined() || root.IsNull()) return b;
  const yaml::MapReader doc(root, source);
  if (const auto ugv = doc.optional_child("ugv")) {
    // The section also holds the miniUGV mission's keys (ugv/ugv_mission_config.hpp).
    ugv->allow_only(ugv_section_keys());
    b.ugv_base = ugv::ugv_base_config_from_yaml(ugv->node()["base"], source);
  } else if (doc.given_empty("ugv")) {
    doc.fail("ugv", "a mapping with the miniUGV's backends (base)", "a key without a value");
  }
  if (const auto uav = doc.optional_child("uav")) {
    // The section also holds the UAV mission's keys (uav/uav_mission_config.hpp).
    uav->allow_only(uav_section_keys());
    b.winch = tether::winch_config_from_yaml(uav->node()["winch"], source);
    b.flight_controller =
        flight_controller_config_from_yaml(uav->node()["flight_controller"], source);
  } else if (doc.given_empty("uav")) {
    doc.fail("uav", "a mapping with the UAV's backends (winch, flight_controller)",
             "a key without a value");
  }
  return b;
}

RobotBackends load_robot_backends(const std::filesystem::path& path) {
  return robot_backends_from_yaml(yaml::load_file(path), path.string());
}

std::string robot_backends_to_yaml(const RobotBackends& b) {
  YAML::Emitter e;
  e << YAML::BeginMap;
  e << YAML::Key << "ugv" << YAML::Value << YAML::BeginMap << YAML::Key << "base" << YAML::Value;
  ugv::emit_ugv_base_config(e, b.ugv_base);
  e << YAML::EndMap;
  e << YAML::Key << "uav" << YAML::Value << YAML::BeginMap << YAML::Key << "winch" << YAML::Value;
  tether::emit_winch_config(e, b.winch);
  e << YAML::Key << "flight_controller" << YAML::Value;
  emit_flight_controller_config(e, b.flight_controller);
  e << YAML::EndMap << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

void require_all_sim(const RobotBackends& b, const std::string& source, const std::string& why) {
  const std::tuple<const char*, const std::string&, bool> interfaces[] = {
      {"ugv.base.backend", b.ugv_base.backend, b.ugv_base.simulated()},
      {"uav.winch.backend", b.winch.backend, b.winch.simulated()},
      {"uav.flight_controller.backend", b.flight_controller.backend,
       b.flight_controller.simulated()}};
  for (const auto& [field, backend, simulated] : interfaces)
    if (!simulated) throw InputError(source, field, "sim (" + why + ")", "'" + backend + "'");
}

}  // namespace ferret
