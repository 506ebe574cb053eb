#pragma once
// The settings of one simulated object search (the paper's episode, and the miniUGV's
// search in a hidden space of a simulated mission): the method, the simulated sensors,
// the robot's motion limits, the mission. The controller that runs the search is
// mission/'s (mission/exploration_run.hpp); the simulation only checks its inputs.

#include <string>

#include "ferret/core/pose.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/sim/hidden_space_sim.hpp"
#include "ferret/ugv/explore_options.hpp"
#include "ferret/ugv/path_follower.hpp"

namespace ferret {

/// The search's tuning (decision period, revisits, the cdos options, the tether's margins)
/// is the controller's own (ExploreTuning), embedded, not copied.
struct ExplorationSettings : ExploreTuning {
  std::string method = "cdos";
  SensorOptions sensors;
  RobotOptions robot;
  MissionConfig mission;
  double time_limit_s = 300.0;
  bool record = false;  ///< keep the trajectory, decisions and final maps
  /// Time each step that ran a decision cycle (EpisodeResult::decision_cycle_s): wall
  /// time, for benchmarks only; it changes nothing the search does.
  bool time_decision_cycles = false;
};

/// The checks every simulated episode makes of its inputs.
/// @throws std::invalid_argument for an unknown method or a start off the free space.
void check_episode(const OccupancyMap2D& truth, const Pose2& start, const std::string& method);

}  // namespace ferret
