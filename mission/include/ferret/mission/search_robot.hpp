#pragma once
// The object search driven by a robot's description: the simulator's sensors (camera
// fov alpha, D_cam, image width; IR fov beta, D_IR and its beams) and the search's
// motion limits (v_max, yaw rate, acceleration) taken from a RobotDescription, and
// one call that runs a search (docs/object_search.md, "The robot").

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "ferret/core/pose.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/mission/exploration_run.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {

/// `base` with the sensors the robot describes: the camera with role object_camera
/// (fov, clip far as D_cam, image width) and the range sensors with role ir (the
/// array's fov, its smallest range_max as D_IR, every beam's bearing). The sensors
/// are taken at the robot's origin, level, as the search's sensor model assumes.
/// The noise, rates and detector values stay `base`'s (a URDF does not say them).
/// @throws InputError naming the URDF and the role when a role is missing.
[[nodiscard]] SensorOptions sensor_options_for(const RobotDescription& robot,
                                               const SensorOptions& base = {});

/// `base` with the robot's motion limits (RobotDescription::limits: the mission's
/// ugv_limits with v_max capped by the wheels) and a path clearance of at least the
/// robot's circumscribed radius.
[[nodiscard]] RobotOptions robot_options_for(const RobotDescription& robot,
                                             const RobotOptions& base = {});

/// Settings for a search with this robot and mission: the sensors and limits above,
/// `method`, the mission; everything else ExplorationSettings' defaults.
[[nodiscard]] ExplorationSettings exploration_settings_for(const RobotDescription& robot,
                                                           const MissionConfig& mission,
                                                           const std::string& method = "cdos");

/// One search: the robot (e.g. from load_robot) in `map` from `start`, the object at
/// `object_W`, with a method of the exploration-policy registry. Deterministic in the
/// seed. `record` keeps the trajectory, decisions and final maps.
/// @throws InputError for a missing role, std::invalid_argument as run_exploration.
[[nodiscard]] EpisodeResult run_search(const OccupancyMap2D& map, const Pose2& start,
                                       const Eigen::Vector2d& object_W, const std::string& method,
                                       const RobotDescription& robot, std::uint64_t seed,
                                       const MissionConfig& mission = {}, bool record = false);

}  // namespace ferret
