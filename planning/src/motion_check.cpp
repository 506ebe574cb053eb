#include "ferret/planning/motion_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ferret/planning/collision_checker.hpp"

namespace ferret {

Pose3 Waypoint::pose() const {
  Pose3 X = Pose3::Identity();
  X.translation() = position();
  X.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return X;
}

int segment_steps(const Waypoint& a, const Waypoint& b, const CheckResolution& res) {
  const double dp = (b.position() - a.position()).norm();
  const double dyaw = std::abs(wrap_angle_rad(b.yaw_rad - a.yaw_rad));
  const double n = std::ceil(std::max(dp / res.step_m, dyaw / res.step_rad));
  // Saturates (a cast of a larger double is undefined): callers bound the work they
  // accept (plan_check_count()).
  constexpr int kMax = std::numeric_limits<int>::max() / 2;
  if (!(n < kMax)) return kMax;
  return std::max(1, static_cast<int>(n));
}

Waypoint interpolate(const Waypoint& a, const Waypoint& b, double s) {
  Waypoint w;
  w.t_s = a.t_s + s * (b.t_s - a.t_s);
  w.x_m = a.x_m + s * (b.x_m - a.x_m);
  w.y_m = a.y_m + s * (b.y_m - a.y_m);
  w.z_m = a.z_m + s * (b.z_m - a.z_m);
  w.yaw_rad = wrap_angle_rad(a.yaw_rad + s * wrap_angle_rad(b.yaw_rad - a.yaw_rad));
  return w;
}

std::optional<double> first_collision(CollisionChecker& checker, const Waypoint& a,
                                      const Waypoint& b, const CheckResolution& res, bool exact,
                                      const std::function<bool()>& cancelled) {
  const int n = segment_steps(a, b, res);
  for (int k = 0; k <= n; ++k) {
    if (cancelled && k % 64 == 63 && cancelled()) return std::nullopt;
    const double s = static_cast<double>(k) / n;
    const Pose3 X = interpolate(a, b, s).pose();
    if (exact ? checker.in_collision_fcl(X) : checker.in_collision(X)) return s;
  }
  return std::nullopt;
}

double drive_heading_rad(const Waypoint& a, const Waypoint& b) {
  const double h = std::atan2(b.y_m - a.y_m, b.x_m - a.x_m);
  const double back = wrap_angle_rad(h + std::numbers::pi);
  const auto turning = [&](double heading) {
    return std::abs(wrap_angle_rad(heading - a.yaw_rad)) +
           std::abs(wrap_angle_rad(b.yaw_rad - heading));
  };
  return turning(back) < turning(h) - 1e-12 ? back : h;
}

double free_drive_heading_rad(const Waypoint& a, const Eigen::Vector2d& b) {
  const double h = std::atan2(b.y() - a.y_m, b.x() - a.x_m);
  const double back = wrap_angle_rad(h + std::numbers::pi);
  return std::abs(wrap_angle_rad(back - a.yaw_rad)) <
                 std::abs(wrap_angle_rad(h - a.yaw_rad)) - 1e-12
             ? back
             : h;
}

std::vector<Waypoint> turn_drive_turn(const Waypoint& a, const Waypoint& b) {
  std::vector<Waypoint> out;
  const bool moves = std::hypot(b.x_m - a.x_m, b.y_m - a.y_m) > 1e-9;
  if (moves) {
    const double h = drive_heading_rad(a, b);
    Waypoint turned = a;
    turned.yaw_rad = h;
    if (std::abs(wrap_angle_rad(h - a.yaw_rad)) > 1e-12) out.push_back(turned);
    Waypoint driven = b;
    driven.yaw_rad = h;
    out.push_back(driven);
    if (std::abs(wrap_angle_rad(b.yaw_rad - h)) > 1e-12) out.push_back(b);
  } else {
    out.push_back(b);
  }
  return out;
}

double rest_to_rest_time_s(double distance_m, double max_velocity_mps,
                           double max_acceleration_mps2) {
  const double v = max_velocity_mps, a = max_acceleration_mps2;
  // Accelerating to v and braking from it takes v^2 / a of the distance.
  if (distance_m >= v * v / a) return distance_m / v + v / a;
  return 2.0 * std::sqrt(distance_m / a);
}

void assign_times(std::vector<Waypoint>& path, double max_velocity_mps, double max_yaw_rate_radps,
                  double max_acceleration_mps2) {
  for (std::size_t k = 1; k < path.size(); ++k) {
    const double dp = (path[k].position() - path[k - 1].position()).norm();
    const double dyaw = std::abs(wrap_angle_rad(path[k].yaw_rad - path[k - 1].yaw_rad));
    path[k].t_s =
        path[k - 1].t_s + std::max(rest_to_rest_time_s(dp, max_velocity_mps, max_acceleration_mps2),
                                   dyaw / max_yaw_rate_radps);
  }
}

}  // namespace ferret
