#pragma once
// The settings `ferret mission` runs a simulated mission with, put together from the
// robots' descriptions, the mission config and the world (docs/mission.md): the
// miniUGV's search from its robot, the UAV's limits and landing-zone footprint, the
// winch's limits both robots count on.

#include <map>
#include <string>
#include <vector>

#include "ferret/planning/mission_config.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/sim/mission_run.hpp"
#include "ferret/uav/opening_locator.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {

/// The openings of a world's markers (what the team placed and tells the UAV).
[[nodiscard]] std::vector<OpeningInMarker> world_openings(const WorldSpec& world);

/// The settings `ferret mission` runs with: the miniUGV's search from its robot and the
/// mission (method cdos, trajectories recorded), the UAV's limits and landing-zone
/// footprint from its robot, the search area the world's bounds less 1 m (the legs
/// start at the edge so that the forward camera sees markers near it).
[[nodiscard]] MissionRunSettings mission_settings_for(const RobotDescription& uav,
                                                      const RobotDescription& ugv,
                                                      const MissionConfig& mission,
                                                      const WorldSpec& world);

/// What run_mission drives each interface with, before it runs (a log's first line):
/// every interface simulated, the miniUGV's link inside the process. The result's
/// `backends` say the same from the objects themselves.
[[nodiscard]] std::map<std::string, std::string> mission_backends();

}  // namespace ferret
