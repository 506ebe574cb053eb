#include "ferret/sim/sim_ugv_base.hpp"

#include <algorithm>
#include <cmath>

namespace ferret {

SimUgvBase::SimUgvBase(HiddenSpaceSim& sim, const Pose2& start, SimUgvOptions options)
    : sim_(sim),
      options_(options),
      pose_(start),
      battery_(std::clamp(options.initial_battery_fraction, 0.0, 1.0)) {}

void SimUgvBase::command_velocity(double v_mps, double w_radps) {
  const RobotOptions& r = options_.robot;
  // A base clips, it does not refuse; NaN (a controller's bug) stops the robot.
  command_.v_mps =
      std::isfinite(v_mps) ? std::clamp(v_mps, -r.max_velocity_mps, r.max_velocity_mps) : 0.0;
  command_.w_radps = std::isfinite(w_radps)
                         ? std::clamp(w_radps, -r.max_yaw_rate_radps, r.max_yaw_rate_radps)
                         : 0.0;
}

Eigen::Vector2d SimUgvBase::rear(const Pose2& pose) const {
  return pose.position() -
         options_.rear_offset_m * Eigen::Vector2d(std::cos(pose.yaw_rad), std::sin(pose.yaw_rad));
}

double SimUgvBase::body_penetration_m(const Eigen::Vector2d& p) const {
  const GridGeometry& g = sim_.truth().geometry;
  const double depth =
      disc_depth_m(g, p, options_.body_radius_m, [this](Cell c) { return sim_.blocks(c); });
  // The truth marks a cell by its centre: an obstacle's face lies within half a cell of
  // the blocked cells' edge, so only what reaches further in is certainly a contact.
  return std::max(0.0, depth - 0.5 * g.resolution_m);
}

void SimUgvBase::step(double dt_s) {
  if (battery_ <= 0.0) command_ = {};  // a flat battery stops the wheels
  Pose2 next = integrate_unicycle(pose_, command_, dt_s);
  const Eigen::Vector2d object = sim_.object();
  const double touch_m = sim_.options().object_radius_m;
  contact_ = false;
  if (!held_ && command_.v_mps < 0.0) {
    // Backing into the object: the rear stops at its surface.
    if ((rear(next) - object).norm() <= touch_m) {
      next = pose_;
      next.yaw_rad = wrap_angle_rad(pose_.yaw_rad + command_.w_radps * dt_s);
      contact_ = true;
    }
  } else if (!held_ && (rear(pose_) - object).norm() <= touch_m + 0.005) {
    contact_ = true;
  }
  if (held_) contact_ = true;
  if (contact_ && epm_on_ && options_.object_graspable) held_ = true;
  if (!epm_on_) held_ = false;
  // A wall stops the body (it still turns on the spot, and backs off): a step that
  // would press it deeper into the truth is not taken. Each stretch of steps the body
  // spends against a wall is one contact.
  const double depth_now = body_penetration_m(pose_.position());
  double depth = body_penetration_m(next.position());
  bool blocked = false;
  if (depth > 0.0 && depth > depth_now) {
    next.x_m = pose_.x_m;
    next.y_m = pose_.y_m;
    depth = depth_now;
    blocked = true;
  }
  if (blocked || depth > 0.0) {
    if (!in_contact_) ++contacts_;
    in_contact_ = true;
    deepest_contact_m_ = std::max(deepest_contact_m_, depth);
  } else {
    in_contact_ = false;
  }
  contact_depth_m_ = in_contact_ ? depth : 0.0;
  driven_m_ += (next.position() - pose_.position()).norm();
  v_mps_ = (next.position() - pose_.position()).norm() / dt_s * (command_.v_mps < 0 ? -1.0 : 1.0);
  pose_ = next;
  const double speed_share = std::abs(command_.v_mps) / options_.robot.max_velocity_mps;
  const double drain =
      (options_.idle_drain_share + (1.0 - options_.idle_drain_share) * speed_share) * dt_s /
      options_.battery_endurance_s;
  battery_ = std::max(0.0, battery_ - drain_factor_ * drain);
}

UgvStatus SimUgvBase::status() const {
  // The magnet's sensor feels only a ferromagnetic body.
  return {battery_, epm_on_, (contact_ || held_) && options_.object_graspable};
}

}  // namespace ferret
