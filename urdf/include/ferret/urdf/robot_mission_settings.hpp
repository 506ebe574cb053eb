#pragma once
// What a mission says about its robots that their URDFs cannot: the motion limits of
// each kind and the `roles` overrides, with where each value came from. The URDF loader
// takes only this part of a mission; MissionConfig (planning/mission_config.hpp) adds
// the object search, the curiosity and the tether.

#include <map>
#include <set>
#include <string>
#include <vector>

#include "ferret/core/motion_limits.hpp"

namespace YAML {
class Emitter;
}

namespace ferret {
namespace yaml {
class MapReader;
}

struct RobotMissionSettings {
  /// ROBOT -> ROLE -> the sensor or link names that play it.
  using Roles = std::map<std::string, std::map<std::string, std::vector<std::string>>>;

  MotionLimits ugv_limits;
  MotionLimits uav_limits{5.0, 2.0, 1.0};
  /// `roles: {ROBOT: {ROLE: NAME or [NAMES]}}`: which sensors or links of the robot
  /// whose URDF is <robot name="ROBOT"> play a role; overrides that role's <ferret
  /// role> markers (docs/configuration.md). Role names are checked here, sensor and
  /// link names when the URDF is loaded.
  Roles roles;

  /// The file the values came from; empty for the built-in defaults.
  std::string source;
  /// The dotted keys the file set ("ugv_limits.max_velocity_mps"); the rest are defaults.
  std::set<std::string> given;
  /// "mission:FILE" when the file set `key`, else "default".
  [[nodiscard]] std::string provenance(const std::string& key) const;
};

/// Reads the mission's `roles` section into `roles` (role names checked; InputError
/// naming the file and field otherwise).
void read_mission_roles(const yaml::MapReader& section, RobotMissionSettings::Roles& roles);
/// The `roles` section as read_mission_roles reads it back; nothing when there are none.
void emit_mission_roles(YAML::Emitter& e, const RobotMissionSettings::Roles& roles);

}  // namespace ferret
