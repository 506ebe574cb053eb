#include "ferret/uav/flight_path_follower.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

namespace ferret {
namespace {

double yaw_of(const Eigen::Vector3d& d) { return std::atan2(d.y(), d.x()); }

}  // namespace

FlightPathFollower::FlightPathFollower(FlightController& flight, FlightPlanner planner,
                                       Options options)
    : flight_(flight), planner_(std::move(planner)), options_(options) {}

bool FlightPathFollower::fly_to(const Eigen::Vector3d& goal, double speed_mps, bool carrying,
                                std::optional<double> yaw_rad) {
  const FlightState s = flight_.state();
  // A new path starts where the UAV comes to a stop, not where it is: the planner checks
  // the way from its start, and a UAV at 3 m/s still covers two metres braking along the
  // way it was flying (which went round what lay ahead). The braking line is checked too;
  // when it is not clear, the new path starts at the old one's next corner, reached
  // along a segment that was checked.
  Eigen::Vector3d from = s.p_W;
  if (const double v = s.v_W.norm(); v > 0.3) {
    const Eigen::Vector3d stop = s.p_W + s.v_W * (v / (2.0 * options_.braking_accel_mps2));
    const auto brake = planner_(s.p_W, stop, carrying);
    if (brake && brake->size() == 2)
      from = stop;
    else if (!path_.empty())
      from = path_[std::min(next_, path_.size() - 1)];
  }
  auto path = planner_(from, goal, carrying);
  if (!path || path->empty()) {
    ++plans_failed_;
    path_.clear();
    return false;
  }
  path_ = std::move(*path);
  next_ = 0;
  speed_mps_ = speed_mps;
  yaw_rad_ = yaw_rad;
  return true;
}

void FlightPathFollower::fly_straight(const Eigen::Vector3d& goal, double speed_mps) {
  path_ = {goal};
  next_ = 0;
  speed_mps_ = speed_mps;
}

bool FlightPathFollower::follow(const FlightState& s) {
  if (path_.empty()) return true;
  // Corners of a planned path are passed closely: the plan is collision-checked along
  // its segments only, so cutting a corner could graze what the planner went round.
  // A corner is left only once reached and slowed down, so the turn happens on it.
  while (next_ + 1 < path_.size() &&
         (path_[next_] - s.p_W).norm() <= std::min(0.15, options_.waypoint_tolerance_m) &&
         s.v_W.norm() < 0.5)
    ++next_;
  const Eigen::Vector3d& target = path_[next_];
  const bool last = next_ + 1 == path_.size();
  // At the end the setpoint and heading are still commanded: a heading that changed
  // (a refined opening) is turned to even when the position is already reached.
  const bool arrived =
      last && (target - s.p_W).norm() <= options_.waypoint_tolerance_m && s.v_W.norm() < 0.3;
  // Face the way it flies (the marker camera looks ahead); the final heading when given.
  double yaw = s.yaw_rad;
  const Eigen::Vector3d d = target - s.p_W;
  if (d.head<2>().norm() > 0.5) yaw = yaw_of(d);
  const bool final_heading = last && yaw_rad_ && d.head<2>().norm() < 1.0;
  if (final_heading) yaw = *yaw_rad_;
  // Turn on the spot at the start of a segment: the planner checked the segment with
  // the UAV facing along it, and its shape is not round.
  const Eigen::Vector3d& hold = path_[next_ > 0 ? next_ - 1 : 0];
  if (!final_heading && (s.p_W - hold).norm() < 0.3 &&
      std::abs(std::remainder(yaw - s.yaw_rad, 2 * std::numbers::pi)) > 0.15) {
    flight_.command_position(hold, yaw, speed_mps_);
    return false;
  }
  flight_.command_position(target, yaw, speed_mps_);
  return arrived;
}

}  // namespace ferret
