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

#include "ferret/mission/mission_files.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/sim/mission_run.hpp"
#include "ferret/sim/robot_backends.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {

/// What --world, --robot-uav, --robot-ugv, --mission, --method, --planner and
/// --no-landing-zone say (empty: the shipped defaults).
struct MissionSetupOptions {
  std::string world, robot_uav, robot_ugv, mission, method = "cdos", planner = "grid";
  std::string no_landing_zone;  ///< empty: the mission YAML's uav.no_landing_zone (hover)
  std::string faults;           ///< a `faults:` file, after the mission YAML's (empty: none)
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
void check_openings_admit(const WorldSpec& world, const std::string& source,
                          const RobotDescription& ugv);

/// Loads and checks everything; InputError naming the option or the file and field.
[[nodiscard]] MissionSetup load_mission_setup(const MissionSetupOptions& o);

}  // namespace ferret
