#pragma once
// The two_sites world with the reference robots and the default mission's settings, as
// the mission module's unit tests start from.

#include "ferret/core/data_path.hpp"
#include "ferret/mission/mission_settings.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/sim/mission_run.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::test {

struct TwoSitesMission {
  PlanningWorld world = load_planning_world(data_path("worlds/two_sites.yaml"));
  RobotDescription uav = load_robot_description(data_path("models/m100.urdf"), MissionConfig{});
  RobotDescription ugv = load_robot_description(data_path("models/miniugv.urdf"), MissionConfig{});
  MissionRunSettings settings = mission_settings_for(uav, ugv, MissionConfig{}, *world.spec);
};

}  // namespace ferret::test
