#pragma once
// States along a plan and how a motion between two of them is checked. The planners
// and `ferret validate` share these functions, so a path the planners return is
// checked at exactly the poses validation checks (no returned path can fail it).

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "ferret/core/pose.hpp"

namespace ferret {

class CollisionChecker;

/// A state of a plan: time, position, heading, and the taut tether length there
/// (NaN when the plan has no tether on the floor).
struct Waypoint {
  double t_s = 0.0;
  double x_m = 0.0;
  double y_m = 0.0;
  double z_m = 0.0;
  double yaw_rad = 0.0;
  double tether_length_m = std::numeric_limits<double>::quiet_NaN();

  [[nodiscard]] Eigen::Vector3d position() const { return {x_m, y_m, z_m}; }
  [[nodiscard]] Pose3 pose() const;
};

/// Sampling resolution of motion checks: the largest step in position and in heading
/// between two checked poses.
struct CheckResolution {
  double step_m = 0.02;
  double step_rad = 0.05;
};

/// Number of steps a segment is cut into (poses checked: steps + 1, ends included).
[[nodiscard]] int segment_steps(const Waypoint& a, const Waypoint& b, const CheckResolution& res);
/// Linear in position and time, along the shorter arc in heading; s in [0, 1].
[[nodiscard]] Waypoint interpolate(const Waypoint& a, const Waypoint& b, double s);

/// The fraction s of the first colliding pose of the segment a -> b, or nullopt when
/// every checked pose is free. `exact` asks FCL alone (the reference), otherwise the
/// checker's fast path (which gives the same answers). `cancelled`, when set, is asked
/// every 64 poses; true stops the check and returns nullopt (the caller asks it again).
[[nodiscard]] std::optional<double> first_collision(CollisionChecker& checker, const Waypoint& a,
                                                    const Waypoint& b, const CheckResolution& res,
                                                    bool exact = false,
                                                    const std::function<bool()>& cancelled = {});

/// How the miniUGV drives from a to b: it turns in place to the drive heading, drives
/// straight, and turns in place to b's heading. It drives forwards or backwards,
/// whichever turns less. Returns the poses after a (b last); times are not set.
[[nodiscard]] std::vector<Waypoint> turn_drive_turn(const Waypoint& a, const Waypoint& b);
/// The drive heading turn_drive_turn uses from a towards b (b's heading counts).
[[nodiscard]] double drive_heading_rad(const Waypoint& a, const Waypoint& b);
/// The drive heading from a towards the point b when b's heading is free to choose:
/// the one that asks the smaller turn at a.
[[nodiscard]] double free_drive_heading_rad(const Waypoint& a, const Eigen::Vector2d& b);

/// Time to drive `distance_m` in a straight line from rest to rest with speed <=
/// max_velocity_mps and |acceleration| <= max_acceleration_mps2: a trapezoidal
/// profile, or a triangular one when the drive is too short to reach the speed limit.
/// An infinite acceleration limit gives distance / speed. @pre limits > 0
[[nodiscard]] double rest_to_rest_time_s(double distance_m, double max_velocity_mps,
                                         double max_acceleration_mps2);

/// Sets times along a path whose every segment is driven from rest to rest within
/// the velocity and acceleration limits (rest_to_rest_time_s), turning at the yaw-rate
/// limit: each segment takes the longer of its translation and rotation times. The
/// robot stops at every state, which a turn-in-place miniUGV does anyway and a
/// multirotor can. Between states the plan reads as constant speed (docs/validate.md):
/// with these times its segment-to-segment acceleration stays <= half the limit.
/// @pre limits > 0
void assign_times(std::vector<Waypoint>& path, double max_velocity_mps, double max_yaw_rate_radps,
                  double max_acceleration_mps2);

}  // namespace ferret
