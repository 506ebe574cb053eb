#pragma once
// The miniUGV's skid-steer path follower (pure pursuit with turn-in-place) and the
// robot's motion limits. It returns a velocity command for the base; it only ever
// steers into cells that G knows to be free: the robot does not drive into space its
// IR has not seen.

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <vector>

#include "ferret/core/motion_limits.hpp"
#include "ferret/core/pose.hpp"
#include "ferret/mapping/ir_grid.hpp"

namespace ferret {

/// The robot's motion limits (the mission's ugv_limits, capped by its URDF) and how it
/// keeps off obstacles.
struct RobotOptions : MotionLimits {
  /// Takes the limits of a robot or a mission section, keeping the rest.
  void set_limits(const MotionLimits& limits) { static_cast<MotionLimits&>(*this) = limits; }

  double clearance_m = 0.15;  ///< paths keep this far from occupied cells of G
  /// Within this of the robot the clearance is waived, so that a robot that finds a
  /// wall (or a gap narrower than twice the clearance) around it can drive out.
  double escape_radius_m = 1.0;
  /// Half the body's width (m): the follower never steps this disc deeper into an
  /// occupied cell of G, and the planners keep it off them where they waive the
  /// clearance. 0: a point robot (the paper's experiment).
  double body_radius_m = 0.0;
};

struct VelocityCommand {
  double v_mps = 0.0;
  double w_radps = 0.0;
};

/// Where a unicycle ends after dt with command `c`: the yaw first, then the step
/// along the new heading. Bases and the follower's own look-ahead share it.
[[nodiscard]] Pose2 integrate_unicycle(const Pose2& pose, const VelocityCommand& c, double dt_s);

class PathFollower {
 public:
  explicit PathFollower(const RobotOptions& robot) : robot_(robot) {}

  /// A new path (waypoints in W); with a heading, the goal is a viewpoint to stand on
  /// and face.
  void set_path(std::vector<Eigen::Vector2d> path, std::optional<double> heading_rad);
  [[nodiscard]] bool has_path() const { return !path_.empty(); }
  void clear() { path_.clear(); }

  /// The command for the next dt from `pose`; `reached` is set once the goal (and
  /// heading) is reached. Keeps the last commanded speed for its acceleration limit.
  VelocityCommand step(const Pose2& pose, const IrGrid& grid, double dt_s, bool& reached);
  /// The speed last commanded.
  [[nodiscard]] double speed_mps() const { return v_mps_; }
  /// A top speed below the robot's own, from the next step on (the line's, say).
  void set_speed_limit_mps(double v_mps) { speed_limit_mps_ = v_mps; }

 private:
  /// How far the occupied cells of G reach into the body's disc round `q` (0: none).
  [[nodiscard]] double body_depth_m(const Eigen::Vector2d& q, const IrGrid& grid) const;

  /// The deeper of the recovery's current segment's ends: where the robot began it and
  /// the waypoint it drives to.
  [[nodiscard]] double segment_base_depth_m(const IrGrid& grid) const;
  /// The robot at `p` is done with the segment to path_[next_]: the next one starts
  /// here, no deeper than this one's ends.
  void begin_segment(const Eigen::Vector2d& p, const IrGrid& grid);

  RobotOptions robot_;
  std::vector<Eigen::Vector2d> path_;
  int precise_ = 0;           ///< waypoints left to follow precisely after a blocked step
  bool has_heading_ = false;  // (not std::optional: GCC 12 warns falsely about it here)
  double heading_rad_ = 0.0;
  std::size_t next_ = 0;
  double v_mps_ = 0.0;
  double speed_limit_mps_ = std::numeric_limits<double>::infinity();
  double segment_start_depth_m_ = 0.0;  ///< the body's depth where the segment began
};

}  // namespace ferret
