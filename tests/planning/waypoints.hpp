#pragma once
// Waypoints written the way the tests think of them.

#include "ferret/planning/plan_file.hpp"

namespace ferret::test {

/// A miniUGV state on the floor: time, position, heading.
inline Waypoint ugv_at(double t_s, double x_m, double y_m, double yaw_rad) {
  Waypoint w;
  w.t_s = t_s;
  w.x_m = x_m;
  w.y_m = y_m;
  w.yaw_rad = yaw_rad;
  return w;
}

/// A UAV pose (time 0): position and heading.
inline Waypoint uav_at(double x_m, double y_m, double z_m, double yaw_rad) {
  Waypoint w;
  w.x_m = x_m;
  w.y_m = y_m;
  w.z_m = z_m;
  w.yaw_rad = yaw_rad;
  return w;
}

}  // namespace ferret::test
