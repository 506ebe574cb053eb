#include "ferret/urdf/robot_mission_settings.hpp"

#include <algorithm>

#include "ferret/core/yaml_config.hpp"

namespace ferret {
namespace {

const std::vector<std::string>& known_roles() {
  static const std::vector<std::string> roles{
      "object_camera", "ir",  "marker_camera", "depth_camera",
      "epm",           "imu", "winch_spool",   "tether_attachment"};
  return roles;
}

}  // namespace

void read_mission_roles(const yaml::MapReader& r, RobotMissionSettings::Roles& roles) {
  for (const auto& robot : r.node()) {
    // A list or mapping as a key (`? [a]`) is not a name (found by fuzz/mission_fuzz.cpp).
    if (!robot.first.IsScalar())
      throw InputError(r.source(), "roles", "robot names as keys",
                       "a key that is " + yaml::internal::describe(robot.first));
    const auto robot_name = robot.first.as<std::string>();
    if (!robot.second.IsMap() || robot.second.size() == 0)
      r.fail(robot_name, "a mapping of roles to sensor or link names for the robot '" + robot_name +
                             "' (e.g. {object_camera: cam, ir: [ir_l, ir_r]})");
    const yaml::MapReader rr(robot.second, r.source(), r.field_path(robot_name));
    auto& out = roles[robot_name];
    for (const auto& entry : robot.second) {
      if (!entry.first.IsScalar())
        throw InputError(r.source(), r.field_path(robot_name), "role names as keys",
                         "a key that is " + yaml::internal::describe(entry.first));
      const auto role = entry.first.as<std::string>();
      if (std::find(known_roles().begin(), known_roles().end(), role) == known_roles().end()) {
        std::string list;
        for (const auto& k : known_roles()) list += (list.empty() ? "" : ", ") + k;
        rr.fail(role, "a role: one of " + list, role);
      }
      std::vector<std::string> names;
      if (entry.second.IsScalar())
        names.push_back(rr.get<std::string>(role));
      else
        names = rr.get_list<std::string>(role);
      if (names.empty()) rr.fail(role, "a sensor or link name, or a non-empty list of them");
      for (const auto& n : names)
        if (n.empty()) rr.fail(role, "non-empty sensor or link names");
      out[role] = names;
    }
  }
}

void emit_mission_roles(YAML::Emitter& e, const RobotMissionSettings::Roles& roles) {
  if (roles.empty()) return;
  e << YAML::Key << "roles" << YAML::Value << YAML::BeginMap;
  for (const auto& [robot, robot_roles] : roles) {
    e << YAML::Key << robot << YAML::Value << YAML::BeginMap;
    for (const auto& [role, names] : robot_roles)
      e << YAML::Key << role << YAML::Value << YAML::Flow << names;
    e << YAML::EndMap;
  }
  e << YAML::EndMap;
}

std::string RobotMissionSettings::provenance(const std::string& key) const {
  return given.count(key) > 0 ? "mission:" + source : "default";
}

}  // namespace ferret
