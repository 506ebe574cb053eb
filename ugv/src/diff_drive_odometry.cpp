#include "ferret/ugv/diff_drive_odometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ferret::ugv {

DiffDriveOdometry::DiffDriveOdometry(DiffDriveParams params, const Pose2& X_WG_start)
    : params_(params), pose_(X_WG_start) {}

double DiffDriveOdometry::metres_per_tick() const {
  return 2.0 * std::numbers::pi * params_.wheel_radius_m / params_.ticks_per_rev;
}

void DiffDriveOdometry::reset_baseline() {
  have_baseline_ = false;
  window_.clear();
  speed_mps_ = 0.0;
}

void DiffDriveOdometry::update(std::int32_t left_ticks, std::int32_t right_ticks,
                               std::uint32_t mcu_time_ms) {
  const auto baseline = [&] {
    have_baseline_ = true;
    left_ = left_ticks;
    right_ = right_ticks;
    time_ms_ = mcu_time_ms;
    window_.clear();
    window_.push_back({time_s_, distance_m_});
    speed_mps_ = 0.0;
  };
  if (!have_baseline_) return baseline();
  // Differences modulo 2^32: a counter that wrapped still gives the small step.
  const auto dt_ms = static_cast<std::int32_t>(mcu_time_ms - time_ms_);
  const auto dl_ticks = static_cast<std::int32_t>(static_cast<std::uint32_t>(left_ticks) -
                                                  static_cast<std::uint32_t>(left_));
  const auto dr_ticks = static_cast<std::int32_t>(static_cast<std::uint32_t>(right_ticks) -
                                                  static_cast<std::uint32_t>(right_));
  if (dt_ms < 0) {  // the MCU restarted: its counts are new too
    ++rebaselines_;
    return baseline();
  }
  const double k = metres_per_tick();
  const double dl = k * dl_ticks, dr = k * dr_ticks;
  const double dt_s = dt_ms / 1000.0;
  // A repeated timestamp can carry no motion; a jump beyond any wheel's speed is a glitch.
  const double fastest = std::max(std::abs(dl), std::abs(dr));
  if ((dt_ms == 0 && fastest > 0.0) ||
      (dt_ms > 0 && fastest / dt_s > params_.max_plausible_wheel_speed_mps)) {
    ++rebaselines_;
    return baseline();
  }
  left_ = left_ticks;
  right_ = right_ticks;
  time_ms_ = mcu_time_ms;
  time_s_ += dt_s;

  const double ds = 0.5 * (dl + dr);
  const double dtheta = (dr - dl) / params_.track_width_m;
  const double theta = pose_.yaw_rad;
  if (std::abs(dtheta) < 1e-9) {
    pose_.x_m += ds * std::cos(theta);
    pose_.y_m += ds * std::sin(theta);
  } else {
    const double radius = ds / dtheta;  // the arc's radius (0 for a turn on the spot)
    pose_.x_m += radius * (std::sin(theta + dtheta) - std::sin(theta));
    pose_.y_m -= radius * (std::cos(theta + dtheta) - std::cos(theta));
  }
  pose_.yaw_rad = wrap_angle_rad(theta + dtheta);

  distance_m_ += ds;
  window_.push_back({time_s_, distance_m_});
  // Keep the newest sample that is at least a window old as the reference.
  while (window_.size() > 2 && time_s_ - window_[1].time_s >= params_.speed_window_s)
    window_.pop_front();
  const Sample& ref = window_.front();
  speed_mps_ = time_s_ > ref.time_s ? (distance_m_ - ref.distance_m) / (time_s_ - ref.time_s) : 0.0;
}

}  // namespace ferret::ugv
