#pragma once
// The robots' part of a mission YAML (roles, ugv_limits, uav_limits) for the URDF
// loader's tests, read with the section readers the mission's reader calls
// (planning/mission_config.hpp reads the whole document).

#include <yaml-cpp/yaml.h>

#include <string>

#include "ferret/core/yaml_config.hpp"
#include "ferret/urdf/robot_mission_settings.hpp"

namespace ferret::test {

inline RobotMissionSettings robot_mission_from_yaml(const std::string& text,
                                                    const std::string& source) {
  RobotMissionSettings m;
  m.source = source;
  const yaml::MapReader root(YAML::Load(text), source);
  root.allow_only({"roles", "ugv_limits", "uav_limits"});
  if (const auto r = root.optional_child("roles")) read_mission_roles(*r, m.roles);
  for (const char* section : {"ugv_limits", "uav_limits"})
    if (const auto r = root.optional_child(section)) {
      read_motion_limits(*r, section[1] == 'g' ? m.ugv_limits : m.uav_limits);
      for (const auto& entry : r->node())
        m.given.insert(std::string(section) + "." + entry.first.as<std::string>());
    }
  return m;
}

}  // namespace ferret::test
