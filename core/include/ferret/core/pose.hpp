#pragma once
// Planar and spatial poses. Names follow monogram notation: X_WG is the pose of
// the miniUGV (G) in the world (W), p_WE the position of the entry E in W.

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace ferret {

/// Wraps an angle to (-pi, pi].
[[nodiscard]] inline double wrap_angle_rad(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

[[nodiscard]] inline double deg_to_rad(double deg) { return deg * std::numbers::pi / 180.0; }
[[nodiscard]] inline double rad_to_deg(double rad) { return rad * 180.0 / std::numbers::pi; }

/// A pose in the plane: position in metres, heading in radians (x forward).
struct Pose2 {
  double x_m = 0.0;
  double y_m = 0.0;
  double yaw_rad = 0.0;

  [[nodiscard]] Eigen::Vector2d position() const { return {x_m, y_m}; }
  /// This pose composed with a pose expressed in its frame: X_WB * X_BC.
  [[nodiscard]] Pose2 operator*(const Pose2& X_BC) const {
    const double c = std::cos(yaw_rad), s = std::sin(yaw_rad);
    return {x_m + c * X_BC.x_m - s * X_BC.y_m, y_m + s * X_BC.x_m + c * X_BC.y_m,
            wrap_angle_rad(yaw_rad + X_BC.yaw_rad)};
  }
};

/// A pose in space (rigid transform).
using Pose3 = Eigen::Isometry3d;

}  // namespace ferret
