#include "ferret/mission/search_robot.hpp"

#include <algorithm>

namespace ferret {

SensorOptions sensor_options_for(const RobotDescription& robot, const SensorOptions& base) {
  SensorOptions s = base;
  const CameraSensor& camera = robot.object_camera();
  s.camera_fov_rad = camera.horizontal_fov_rad;
  s.camera_range_m = camera.range_max_m;
  s.image_width_px = camera.image_width_px;
  const IrArray ir = robot.ir_array();
  s.ir_fov_rad = ir.fov_rad;
  s.ir_range_m = ir.range_max_m;
  // Bearings relative to the array's middle, which the search takes as straight ahead.
  s.ir_bearings_rad.clear();
  for (const IrBeam& b : ir.beams)
    s.ir_bearings_rad.push_back(wrap_angle_rad(b.yaw_B_rad - ir.center_yaw_B_rad));
  std::sort(s.ir_bearings_rad.begin(), s.ir_bearings_rad.end());
  s.ir_beams = static_cast<int>(s.ir_bearings_rad.size());
  return s;
}

RobotOptions robot_options_for(const RobotDescription& robot, const RobotOptions& base) {
  RobotOptions r = base;
  r.set_limits(robot.limits);
  r.clearance_m = std::max(base.clearance_m, robot.circumscribed_radius_m);
  return r;
}

ExplorationSettings exploration_settings_for(const RobotDescription& robot,
                                             const MissionConfig& mission,
                                             const std::string& method) {
  ExplorationSettings s;
  s.method = method;
  s.mission = mission;
  s.sensors = sensor_options_for(robot, s.sensors);
  s.robot = robot_options_for(robot, s.robot);
  return s;
}

EpisodeResult run_search(const OccupancyMap2D& map, const Pose2& start,
                         const Eigen::Vector2d& object_W, const std::string& method,
                         const RobotDescription& robot, std::uint64_t seed,
                         const MissionConfig& mission, bool record) {
  ExplorationSettings s = exploration_settings_for(robot, mission, method);
  s.record = record;
  return run_exploration(map, start, object_W, s, seed);
}

}  // namespace ferret
