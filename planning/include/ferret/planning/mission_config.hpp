#pragma once
// The mission's common sections, one struct each beside the module that uses it:
// curiosity (planning/curiosity_params.hpp), object_search (mapping/
// object_search_params.hpp), tether (tether_model/tether_params.hpp), ugv_limits and
// uav_limits (core/motion_limits.hpp) and roles (urdf/robot_mission_settings.hpp).
// Planning is the lowest module that sees them all, and the planners, controllers and
// the planner service all take a MissionConfig; every default is the paper's value
// where the paper gives one (docs/configuration.md lists them all).

#include <filesystem>
#include <string>

#include "ferret/mapping/object_search_params.hpp"
#include "ferret/planning/curiosity_params.hpp"
#include "ferret/tether_model/tether_params.hpp"
#include "ferret/urdf/robot_mission_settings.hpp"

namespace YAML {
class Node;
}

namespace ferret {

/// The robots' part (limits, roles, provenance) is a RobotMissionSettings, so a
/// MissionConfig is passed as it is to the URDF loader.
struct MissionConfig : RobotMissionSettings {
  CuriosityParams curiosity;
  ObjectSearchParams object_search;
  TetherParams tether;
};

/// Reads a mission YAML (sections: curiosity, object_search, tether, ugv_limits,
/// uav_limits, roles; every key optional, unknown keys rejected). The sections `ugv` and
/// `uav` (the robots' hardware backends and the UAV mission's keys) are allowed and left
/// to their readers (mission/mission_document.hpp reads them all). Throws InputError
/// naming the file and field for a wrong type, a value out of range or an unknown key.
[[nodiscard]] MissionConfig load_mission_config(const std::filesystem::path& path);
/// The same from a parsed node; `source` names it in errors.
[[nodiscard]] MissionConfig mission_config_from_yaml(const YAML::Node& node,
                                                     const std::string& source);
/// YAML text that load_mission_config reads back to the same values.
[[nodiscard]] std::string mission_config_to_yaml(const MissionConfig& config);
/// YAML map of every numeric key of the mission -> its provenance (see above).
[[nodiscard]] std::string mission_provenance_to_yaml(const MissionConfig& config);

}  // namespace ferret
