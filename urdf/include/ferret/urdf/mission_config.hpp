#pragma once
// What a robot's URDF cannot say: the object-search constants, the tether and the
// motion limits of a mission. Loaded from config/mission.yaml; every default is the
// paper's value where the paper gives one (docs/configuration.md lists them all).

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace ferret {

/// Curiosity c(p) = -(p + a)^2 / (4 b) + K (paper eq. curiosity).
struct CuriosityParams {
  double a = -0.5;
  double b = 0.1;
  double K = 0.62;
};

/// Object map O and the detection model (paper sect. IV-A, pinned down in
/// docs/object_search.md).
struct ObjectSearchParams {
  double lambda1 = 0.10;     ///< below: labelled free of the object
  double lambda2 = 0.95;     ///< above: the object; found when its cell passes this
  double eta_m = 1.0;        ///< conf = eta / d (d in metres)
  double conf_floor = 0.55;  ///< a detection is always weak positive evidence
  double conf_cap = 0.99;
  double miss_likelihood = 0.4;  ///< "no object" likelihood for a cell seen at zero distance
};

/// The tether and winch geometry (paper sect. III-A).
struct TetherParams {
  double total_length_m = 15.0;  ///< L
  double entry_offset_m = 1.0;   ///< l_0: winch to the hidden-space entry point
  /// The miniUGV drives no faster than the winch can follow should its line catch on a
  /// corner its map does not hold (tether::LineCatchLimit; docs/mission.md).
  bool catch_speed_limit = true;
};

/// Motion limits of one robot.
struct MotionLimits {
  double max_velocity_mps = 2.0;
  double max_acceleration_mps2 = 2.0;
  double max_yaw_rate_radps = 2.0;
};

struct MissionConfig {
  CuriosityParams curiosity;
  ObjectSearchParams object_search;
  TetherParams tether;
  MotionLimits ugv_limits;
  MotionLimits uav_limits{5.0, 2.0, 1.0};
  /// `roles: {ROBOT: {ROLE: NAME or [NAMES]}}`: which sensors or links of the robot
  /// whose URDF is <robot name="ROBOT"> play a role; overrides that role's <ferret
  /// role> markers (docs/configuration.md). Role names are checked here, sensor and
  /// link names when the URDF is loaded.
  std::map<std::string, std::map<std::string, std::vector<std::string>>> roles;

  /// The file the values came from; empty for the built-in defaults.
  std::string source;
  /// The dotted keys the file set ("ugv_limits.max_velocity_mps"); the rest are defaults.
  std::set<std::string> given;
  /// "mission:FILE" when the file set `key`, else "default".
  [[nodiscard]] std::string provenance(const std::string& key) const;
};

/// Reads a mission YAML (sections: curiosity, object_search, tether, ugv_limits,
/// uav_limits, roles; every key optional, unknown keys rejected). The sections `ugv` and
/// `uav` (the robots' hardware backends) are allowed and left to
/// load_robot_backends (sim/robot_backends.hpp). Throws InputError naming
/// the file and field for a wrong type, a value out of range or an unknown key.
[[nodiscard]] MissionConfig load_mission_config(const std::filesystem::path& path);
/// The same from a parsed node; `source` names it in errors.
[[nodiscard]] MissionConfig mission_config_from_yaml(const YAML::Node& node,
                                                     const std::string& source);
/// YAML text that load_mission_config reads back to the same values.
[[nodiscard]] std::string mission_config_to_yaml(const MissionConfig& config);
/// YAML map of every numeric key of the mission -> its provenance (see above).
[[nodiscard]] std::string mission_provenance_to_yaml(const MissionConfig& config);

}  // namespace ferret
