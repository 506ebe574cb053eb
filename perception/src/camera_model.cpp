#include "ferret/perception/camera_model.hpp"

#include <fmt/format.h>

#include <cmath>

#include "ferret/core/error.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

constexpr int kMaxSidePx = 16384;

void require(bool ok, const CameraModel& m, const std::string& field, const std::string& expected,
             const std::string& got) {
  if (!ok) throw InputError(m.source.empty() ? m.name : m.source, field, expected, got);
}

}  // namespace

const char* to_string(DistortionModel model) {
  return model == DistortionModel::kPlumbBob ? "plumb_bob" : "none";
}

CameraModel CameraModel::from_fov(std::string name, int width_px, int height_px,
                                  double horizontal_fov_rad) {
  CameraModel m;
  m.name = std::move(name);
  m.width_px = width_px;
  m.height_px = height_px;
  m.fx_px = 0.5 * width_px / std::tan(0.5 * horizontal_fov_rad);
  m.fy_px = m.fx_px;  // square pixels, as Gazebo renders them
  // Gazebo's default principal point is the image centre; in OpenCV's pixel convention
  // (0 at the centre of the first pixel) that is (w - 1) / 2.
  m.cx_px = 0.5 * (width_px - 1);
  m.cy_px = 0.5 * (height_px - 1);
  m.projection.leftCols<3>() = m.K();
  return m;
}

Eigen::Matrix3d CameraModel::K() const {
  Eigen::Matrix3d k;
  k << fx_px, skew, cx_px, 0.0, fy_px, cy_px, 0.0, 0.0, 1.0;
  return k;
}

double CameraModel::horizontal_fov_rad() const {
  return std::atan((cx_px + 0.5) / fx_px) + std::atan((width_px - 0.5 - cx_px) / fx_px);
}
double CameraModel::vertical_fov_rad() const {
  return std::atan((cy_px + 0.5) / fy_px) + std::atan((height_px - 0.5 - cy_px) / fy_px);
}

bool CameraModel::has_distortion() const {
  if (distortion == DistortionModel::kNone) return false;
  for (const double d : distortion_coefficients)
    if (d != 0.0) return true;
  return false;
}

Eigen::Vector2d CameraModel::distort(const Eigen::Vector2d& xy) const {
  if (!has_distortion()) return xy;
  const auto& [k1, k2, p1, p2, k3] = distortion_coefficients;
  const double x = xy.x(), y = xy.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (k1 + r2 * (k2 + r2 * k3));
  return {x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
          y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y};
}

Eigen::Vector2d CameraModel::undistort(const Eigen::Vector2d& xy_distorted) const {
  if (!has_distortion()) return xy_distorted;
  // Newton's method on distort(u) = target, with the Jacobian by central differences:
  // a few steps reach machine precision for lens distortion inside the image, where
  // OpenCV's fixed-point iteration can stall on strong barrel distortion.
  Eigen::Vector2d u = xy_distorted;
  for (int i = 0; i < 20; ++i) {
    const Eigen::Vector2d r = distort(u) - xy_distorted;
    if (r.squaredNorm() < 1e-24) break;
    constexpr double h = 1e-7;
    Eigen::Matrix2d J;
    J.col(0) = (distort(u + Eigen::Vector2d(h, 0)) - distort(u - Eigen::Vector2d(h, 0))) / (2 * h);
    J.col(1) = (distort(u + Eigen::Vector2d(0, h)) - distort(u - Eigen::Vector2d(0, h))) / (2 * h);
    if (std::abs(J.determinant()) < 1e-12) break;
    u -= J.inverse() * r;
  }
  return u;
}

std::optional<Eigen::Vector2d> CameraModel::project(const Eigen::Vector3d& p_C) const {
  if (!(p_C.z() > 0.0)) return std::nullopt;
  const Eigen::Vector2d d = distort(Eigen::Vector2d(p_C.x() / p_C.z(), p_C.y() / p_C.z()));
  return Eigen::Vector2d(fx_px * d.x() + skew * d.y() + cx_px, fy_px * d.y() + cy_px);
}

Eigen::Vector3d CameraModel::ray(const Eigen::Vector2d& pixel) const {
  const double yd = (pixel.y() - cy_px) / fy_px;
  const double xd = (pixel.x() - cx_px - skew * yd) / fx_px;
  const Eigen::Vector2d u = undistort({xd, yd});
  return {u.x(), u.y(), 1.0};
}

bool CameraModel::in_image(const Eigen::Vector2d& pixel, double margin_px) const {
  return pixel.x() >= -0.5 + margin_px && pixel.y() >= -0.5 + margin_px &&
         pixel.x() < width_px - 0.5 - margin_px && pixel.y() < height_px - 0.5 - margin_px;
}

void CameraModel::check() const {
  const auto size_ok = [](int s) { return s >= 1 && s <= kMaxSidePx; };
  require(size_ok(width_px), *this, "image_width", fmt::format("1 to {} px", kMaxSidePx),
          std::to_string(width_px));
  require(size_ok(height_px), *this, "image_height", fmt::format("1 to {} px", kMaxSidePx),
          std::to_string(height_px));
  require(std::isfinite(fx_px) && fx_px > 0, *this, "camera_matrix.fx",
          "a finite focal length > 0 px", fmt::format("{}", fx_px));
  require(std::isfinite(fy_px) && fy_px > 0, *this, "camera_matrix.fy",
          "a finite focal length > 0 px", fmt::format("{}", fy_px));
  require(std::isfinite(skew), *this, "camera_matrix.skew", "a finite number",
          fmt::format("{}", skew));
  require(std::isfinite(cx_px) && cx_px >= -0.5 && cx_px <= width_px - 0.5, *this,
          "camera_matrix.cx",
          fmt::format("a principal point inside the image, -0.5 to {} px", width_px - 0.5),
          fmt::format("{}", cx_px));
  require(std::isfinite(cy_px) && cy_px >= -0.5 && cy_px <= height_px - 0.5, *this,
          "camera_matrix.cy",
          fmt::format("a principal point inside the image, -0.5 to {} px", height_px - 0.5),
          fmt::format("{}", cy_px));
  for (std::size_t i = 0; i < distortion_coefficients.size(); ++i)
    require(std::isfinite(distortion_coefficients[i]), *this,
            fmt::format("distortion_coefficients.data[{}]", i), "a finite number",
            fmt::format("{}", distortion_coefficients[i]));
  require(
      rectification.allFinite() &&
          (rectification * rectification.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-6 &&
          std::abs(rectification.determinant() - 1.0) < 1e-6,
      *this, "rectification_matrix", "a rotation (orthonormal, determinant +1)",
      "a matrix that is not");
  require(projection.allFinite(), *this, "projection_matrix", "finite numbers",
          "a NaN or infinity");
}

Pose3 X_SC() {
  // Columns: the optical axes expressed in S. x_C = -y_S (right), y_C = -z_S (down),
  // z_C = x_S (forward).
  Pose3 X = Pose3::Identity();
  X.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  return X;
}

CameraModel camera_model(const CameraSensor& sensor, const std::string& urdf_source) {
  CameraModel m = CameraModel::from_fov(sensor.name, sensor.image_width_px, sensor.image_height_px,
                                        sensor.horizontal_fov_rad);
  m.source = fmt::format("{} (sensor {})", urdf_source, sensor.name);
  // A Gazebo <lens><intrinsics> block is a calibration: it replaces the pinhole the fov
  // implies (SDF's rule), and P follows K as for any monocular camera.
  if (sensor.intrinsics) {
    m.fx_px = sensor.intrinsics->fx_px;
    m.fy_px = sensor.intrinsics->fy_px;
    m.cx_px = sensor.intrinsics->cx_px;
    m.cy_px = sensor.intrinsics->cy_px;
    m.skew = sensor.intrinsics->skew;
    m.projection.leftCols<3>() = m.K();
  }
  // Gazebo's <distortion> is Brown-Conrady about the principal point (the loader refuses
  // another centre), i.e. plumb_bob, whose order is k1, k2, p1, p2, k3.
  if (sensor.distortion) {
    const CameraDistortion& d = *sensor.distortion;
    m.distortion = DistortionModel::kPlumbBob;
    m.distortion_coefficients = {d.k1, d.k2, d.p1, d.p2, d.k3};
  }
  m.check();
  return m;
}

}  // namespace ferret
