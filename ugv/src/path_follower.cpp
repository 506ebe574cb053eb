#include "ferret/ugv/path_follower.hpp"

#include <algorithm>
#include <cmath>

namespace ferret {
namespace {

constexpr double kPositionTolerance_m = 0.1;
constexpr double kViewpointTolerance_m = 0.04;
constexpr double kHeadingTolerance_rad = 0.15;
constexpr double kLookahead_m = 0.3;
constexpr double kWaypointTolerance_m = 0.02;  // a precise waypoint reached (at most)

/// How much deeper into G's occupied cells than the recovery's segment's ends the body
/// may go along it: a quarter cell (what the cells' raster hides). Counted from the
/// segment's ends, not from where the robot stands, so that a slow robot's many small
/// steps do not each add it.
double precise_allowance_m(const GridGeometry& g) { return 0.25 * g.resolution_m; }

}  // namespace

Pose2 integrate_unicycle(const Pose2& pose, const VelocityCommand& c, double dt_s) {
  const double yaw = wrap_angle_rad(pose.yaw_rad + c.w_radps * dt_s);
  return {pose.x_m + c.v_mps * dt_s * std::cos(yaw), pose.y_m + c.v_mps * dt_s * std::sin(yaw),
          yaw};
}

void PathFollower::set_path(std::vector<Eigen::Vector2d> path, std::optional<double> heading_rad) {
  path_ = std::move(path);
  has_heading_ = heading_rad.has_value();
  heading_rad_ = heading_rad.value_or(0.0);
  // After a blocked step, stay precise on the new path too, starting from its first
  // waypoint (the centre of the robot's cell): re-planning every cycle must not throw
  // the robot back into the corner it was cutting.
  next_ = path_.size() > 1 && precise_ == 0 ? 1 : 0;
}

VelocityCommand PathFollower::step(const Pose2& pose, const IrGrid& grid, double dt,
                                   bool& reached) {
  reached = false;
  if (path_.empty()) {
    v_mps_ = 0.0;
    return {};
  }
  const Eigen::Vector2d p = pose.position();
  const Eigen::Vector2d goal = path_.back();
  const double to_goal = (goal - p).norm();
  // A goal with a heading is a viewpoint chosen for its line of sight: stand on it.
  if (to_goal < (has_heading_ ? kViewpointTolerance_m : kPositionTolerance_m)) {
    v_mps_ = 0.0;
    if (!has_heading_) {
      reached = true;
      return {};
    }
    const double e = wrap_angle_rad(heading_rad_ - pose.yaw_rad);
    if (std::abs(e) < kHeadingTolerance_rad) {
      reached = true;
      return {};
    }
    return {0.0, std::clamp(4.0 * e, -robot_.max_yaw_rate_radps, robot_.max_yaw_rate_radps)};
  }
  if (precise_ > 0) {
    // Recovery after a blocked step: waypoint by waypoint, exactly along the segments
    // (which cross only free cells), turning on the spot at each. A waypoint counts as
    // reached within a quarter cell: a robot on a cell's edge is half a cell from its
    // centre, and heading on from there would cut the neighbour the step was refused.
    const double reached_m = std::min(kWaypointTolerance_m, 0.25 * grid.geometry().resolution_m);
    while ((path_[next_] - p).norm() < reached_m && next_ + 1 < path_.size()) {
      begin_segment(p, grid);
      ++next_;
      --precise_;
    }
    // Its first waypoint, the centre of the robot's own cell, is passed by when it lies
    // deeper in a wall than the robot stands: a robot pressed against an obstacle
    // cannot get there.
    const GridGeometry& g = grid.geometry();
    if (robot_.body_radius_m > 0.0 && next_ + 1 < path_.size() &&
        (path_[next_] - g.center(g.cell_at(p.x(), p.y()))).norm() < 1e-9 &&
        body_depth_m(path_[next_], grid) > body_depth_m(p, grid) + precise_allowance_m(g)) {
      begin_segment(p, grid);
      ++next_;
      precise_ = std::max(0, precise_ - 1);
    }
  } else {
    while (next_ + 1 < path_.size() && (path_[next_] - p).norm() < kLookahead_m) ++next_;
  }
  const Eigen::Vector2d target = path_[next_];
  const Eigen::Vector2d to = target - p;
  const double e = wrap_angle_rad(std::atan2(to.y(), to.x()) - pose.yaw_rad);
  const double w = std::clamp(4.0 * e, -robot_.max_yaw_rate_radps, robot_.max_yaw_rate_radps);
  double v_des = 0.0;
  if (std::abs(e) < (precise_ > 0 ? 0.03 : 0.6)) {
    v_des = std::min(robot_.max_velocity_mps, speed_limit_mps_) * std::cos(e);
    v_des = std::min(v_des,
                     std::sqrt(2.0 * robot_.max_acceleration_mps2 * to_goal));  // stop at the goal
    if (precise_ > 0) v_des = std::min(v_des, to.norm() / dt);  // land on the waypoint
  }
  const double dv = robot_.max_acceleration_mps2 * dt;
  double v = std::clamp(v_des, v_mps_ - 2 * dv, v_mps_ + dv);  // brake harder than accelerate
  v = std::max(v, 0.0);
  const Eigen::Vector2d next = integrate_unicycle(pose, {v, w}, dt).position();
  const GridGeometry& g = grid.geometry();
  const Cell c = g.cell_at(next.x(), next.y());
  const bool same_cell = c == g.cell_at(p.x(), p.y());  // a noisy hit may mark the robot's cell
  // Pure pursuit cuts the corners of the path (and swings wide after them), and a path
  // planned before G saw an obstacle can run into it: never deeper into what G knows is
  // occupied than the body already is. (The recovery keeps exactly to segments between
  // cells the planner let the body cross: along them the depth may grow by what the
  // cells' raster hides.)
  const Cell here = g.cell_at(p.x(), p.y());
  const double depth_here_m = robot_.body_radius_m > 0.0 ? body_depth_m(p, grid) : 0.0;
  double deepest_m = depth_here_m + 1e-9;
  if (precise_ > 0 && robot_.body_radius_m > 0.0)
    deepest_m = std::max(deepest_m, segment_base_depth_m(grid) + precise_allowance_m(g));
  const bool deeper = robot_.body_radius_m > 0.0 && v > 0.0 && body_depth_m(next, grid) > deepest_m;
  if (!g.contains(c) || (grid.label(c) != GridLabel::kFree && !same_cell) || deeper) {
    // Not known free (a corner cut, or space the IR has not seen), or the body would
    // press into an obstacle: stop, and go on precisely from the centre of the current
    // cell along the path's segments.
    v = 0.0;
    // The new segment starts here; a recovery blocked again does not start it deeper
    // than its last one allowed (else each block would add another allowance).
    segment_start_depth_m_ =
        precise_ > 0 ? std::min(depth_here_m, segment_base_depth_m(grid)) : depth_here_m;
    // The look-ahead passes a waypoint 0.3 m before the robot does: the corner the body
    // cut is gone round exactly, by its waypoint. (Only for the body's cut: a point
    // robot, the paper's experiment, recovers as it always has.)
    if (deeper && precise_ == 0 && next_ >= 2 && (path_[next_ - 1] - p).norm() < kLookahead_m)
      --next_;
    const Eigen::Vector2d centre = g.center(here);
    if ((path_[next_] - centre).norm() > 1e-9)
      path_.insert(path_.begin() + static_cast<std::ptrdiff_t>(next_), centre);
    precise_ = 3;
  }
  v_mps_ = v;
  return {v, w};
}

double PathFollower::segment_base_depth_m(const IrGrid& grid) const {
  return std::max(segment_start_depth_m_, body_depth_m(path_[next_], grid));
}

void PathFollower::begin_segment(const Eigen::Vector2d& p, const IrGrid& grid) {
  if (robot_.body_radius_m > 0.0)
    segment_start_depth_m_ = std::min(body_depth_m(p, grid), segment_base_depth_m(grid));
}

double PathFollower::body_depth_m(const Eigen::Vector2d& q, const IrGrid& grid) const {
  const GridGeometry& g = grid.geometry();
  return disc_depth_m(g, q, robot_.body_radius_m, [&](Cell c) {
    return g.contains(c) && grid.label(c) == GridLabel::kOccupied;
  });
}

}  // namespace ferret
