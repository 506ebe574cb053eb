#include "ferret/mission/mission_settings.hpp"

#include <algorithm>

#include "ferret/mission/search_robot.hpp"
#include "ferret/uav/flight_planner.hpp"

namespace ferret {

std::vector<OpeningInMarker> world_openings(const WorldSpec& world) {
  UavMissionOptions o;
  fill_uav_mission_from_world(o, world, MissionConfig{});
  return o.openings;
}

MissionRunSettings mission_settings_for(const RobotDescription& uav, const RobotDescription& ugv,
                                        const MissionConfig& mission, const WorldSpec& world) {
  MissionRunSettings s;
  s.ugv.exploration = exploration_settings_for(ugv, mission);
  s.ugv.exploration.mission = mission;
  s.ugv.exploration.method = "cdos";
  s.ugv.exploration.record = true;
  // The miniUGV's maps: a square its taut tether cannot leave, L - l_0 each way from the
  // entry and half a metre beyond, as a robot that knows nothing of the space is set up
  // (not the truth slice's extent, which would tell it the space's size).
  const double reach_m = mission.tether.total_length_m - mission.tether.entry_offset_m;
  s.ugv.map_window_m = Eigen::Vector2d::Constant(2.0 * reach_m + 1.0);
  // Body contacts are judged with the disc inside the URDF's collision box.
  const Eigen::Vector3d body = ugv.bounding_box_B.sizes();
  if (body.allFinite() && body.x() > 0.0 && body.y() > 0.0) {
    s.ugv.base.body_radius_m = 0.5 * std::min(body.x(), body.y());
    // The controllers keep the same disc off what G holds.
    s.ugv.exploration.robot.body_radius_m = s.ugv.base.body_radius_m;
  }
  // Tethered, the miniUGV drives no faster than the winch pays out (less a margin for
  // the controller), or it drags the line taut: the spool's 0.6 m/s against 2 m/s.
  const double spool_mps = s.uav.winch_control.limits.max_speed_mps;
  s.ugv.exploration.robot.max_velocity_mps =
      std::min(s.ugv.exploration.robot.max_velocity_mps, 0.8 * spool_mps);
  // And no faster than the winch can follow a catch on a corner no map holds, before the
  // pull passes the tension limit less the hanging weight and the guard's threshold:
  // it notices after two control periods and the servo's lag.
  if (mission.tether.catch_speed_limit)
    s.ugv.ugv.line_catch = tether::LineCatchLimit::for_winch(s.uav.winch_control);
  // The winch's reel-in guard counts on the miniUGV's real limits.
  if (s.uav.winch_control.reel_in_guard.on()) {
    s.uav.winch_control.reel_in_guard.ugv_speed_mps = s.ugv.exploration.robot.max_velocity_mps;
    s.uav.winch_control.reel_in_guard.ugv_acceleration_mps2 =
        s.ugv.exploration.robot.max_acceleration_mps2;
  }
  s.uav.landing = LandingZoneDetector::Options::for_robot(uav, &mission);
  s.uav.tether = mission.tether;  // (the world's run sets it again; validation needs it now)
  s.uav_max_speed_mps = uav.limits.max_velocity_mps;
  s.uav_max_accel_mps2 = uav.limits.max_acceleration_mps2;
  s.uav_max_yaw_rate_radps = uav.limits.max_yaw_rate_radps;
  s.uav.search_area_m = {world.bounds_min_m.x() + 1.0, world.bounds_min_m.y() + 1.0,
                         world.bounds_max_m.x() - 1.0, world.bounds_max_m.y() - 1.0};
  return s;
}

std::map<std::string, std::string> mission_backends() {
  return {{"uav.flight_controller", "sim"},
          {"uav.cameras", "sim"},
          {"uav.winch", "sim"},
          {"ugv.base", "sim"},
          {"link", "in-process"}};
}

}  // namespace ferret
