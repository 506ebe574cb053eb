#pragma once
// What `ferret mission`, `ferret sim-world`, `ferret uav` and `ferret ugv` read alike: the
// world, the two robots, the mission YAML and the command line's choices, made into the
// settings of one mission. The three processes of a mission run read the same files and
// so build the same settings; the in-process `ferret mission` builds them the same way.
// The command line's options that fill MissionSetupOptions are apps/'s.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/planning/planning_world.hpp"
#include "ferret/sim/mission_run.hpp"
#include "ferret/sim/robot_backends.hpp"
#include "ferret/urdf/mission_config.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {

/// What --world, --robot-uav, --robot-ugv, --mission, --method, --planner and
/// --no-landing-zone say (empty: the shipped defaults).
struct MissionSetupOptions {
  std::string world, robot_uav, robot_ugv, mission, method = "cdos", planner = "grid";
  std::string no_landing_zone;  ///< empty: the mission YAML's uav.no_landing_zone (hover)
};

struct MissionSetup {
  std::filesystem::path world_path;
  MissionConfig mission;
  RobotBackends backends;  ///< the mission YAML's (all sim without one)
  RobotDescription uav, ugv;
  PlanningWorld world;
  MissionRunSettings settings;
};

/// InputError (naming the world file and the hidden space) unless every opening admits
/// the miniUGV: its collision box's width and height at most the opening's.
void check_openings_admit(const WorldSpec& world, const std::string& source, const RobotDescription& ugv);

/// The names of the models shipped with ferret (m100, miniugv).
[[nodiscard]] const std::vector<std::string>& shipped_model_names();
/// --robot's value as a file: "" gives `default_model` (a shipped file name such as
/// "miniugv.urdf"); a shipped model's name gives its file; anything else is a path,
/// which must exist. InputError listing the shipped names otherwise.
[[nodiscard]] std::filesystem::path resolve_robot(const std::string& robot, std::string_view default_model);

/// The mission YAML, or the built-in defaults when `path` is empty. Its backend sections
/// (`ugv`, `uav`: load_robot_backends) are checked as well.
[[nodiscard]] MissionConfig load_mission_or_defaults(const std::string& path);

/// Loads and checks everything; InputError naming the option or the file and field.
[[nodiscard]] MissionSetup load_mission_setup(const MissionSetupOptions& o);

}  // namespace ferret
