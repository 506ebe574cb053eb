#include "landing_points.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <utility>

#include "ferret/core/error.hpp"
#include "ferret/uav/landing_zone.hpp"

namespace ferret::internal {
namespace {

bool same_intrinsics(const CameraModel& a, const CameraModel& b) {
  return a.width_px == b.width_px && a.height_px == b.height_px && a.fx_px == b.fx_px &&
         a.fy_px == b.fy_px && a.cx_px == b.cx_px && a.cy_px == b.cy_px && a.skew == b.skew &&
         a.distortion == b.distortion && a.distortion_coefficients == b.distortion_coefficients;
}

// Undistorting every pixel costs more than the rest of the detector, and a robot's
// camera does not change between frames: the rays of the last camera are kept.
struct RayCache {
  std::mutex mutex;
  CameraModel camera;
  std::shared_ptr<const std::vector<Eigen::Vector2f>> rays;  // x/z, y/z per pixel
};

std::shared_ptr<const std::vector<Eigen::Vector2f>> rays_of(const CameraModel& camera) {
  static RayCache cache;
  std::lock_guard lock(cache.mutex);
  if (cache.rays && same_intrinsics(cache.camera, camera)) return cache.rays;
  auto rays = std::make_shared<std::vector<Eigen::Vector2f>>(
      static_cast<std::size_t>(camera.width_px) * static_cast<std::size_t>(camera.height_px));
  for (int v = 0; v < camera.height_px; ++v)
    for (int u = 0; u < camera.width_px; ++u) {
      const Eigen::Vector3d r = camera.ray({u, v});
      (*rays)[static_cast<std::size_t>(v) * static_cast<std::size_t>(camera.width_px) +
              static_cast<std::size_t>(u)] = r.head<2>().cast<float>();
    }
  cache.camera = camera;
  cache.rays = rays;
  return rays;
}

}  // namespace

std::vector<Eigen::Vector3d> depth_to_world_points(const DepthImageMm& depth,
                                                   const CameraModel& camera, const Pose3& X_WC,
                                                   double min_depth_m, double max_depth_m,
                                                   std::vector<Eigen::Vector3d>* border) {
  if (depth.width_px != camera.width_px || depth.height_px != camera.height_px)
    throw InputError("depth frame", "size",
                     fmt::format("the camera's {} x {} px", camera.width_px, camera.height_px),
                     fmt::format("{} x {}", depth.width_px, depth.height_px));
  const auto ray_table = rays_of(camera);
  const std::vector<Eigen::Vector2f>& rays = *ray_table;
  const Eigen::Matrix3d R = X_WC.linear();
  const Eigen::Vector3d t = X_WC.translation();
  std::vector<Eigen::Vector3d> points;
  points.reserve(depth.data.size());
  for (std::size_t i = 0; i < depth.data.size(); ++i) {
    const std::uint16_t mm = depth.data[i];
    if (mm == 0) continue;  // no return: unknown, never free
    const double z = 1e-3 * mm;
    if (z < min_depth_m || z > max_depth_m) continue;
    const Eigen::Vector3d p_C(rays[i].x() * z, rays[i].y() * z, z);
    const int u = static_cast<int>(i % static_cast<std::size_t>(depth.width_px));
    const int v = static_cast<int>(i / static_cast<std::size_t>(depth.width_px));
    const bool edge = u == 0 || v == 0 || u == depth.width_px - 1 || v == depth.height_px - 1;
    (edge && border != nullptr ? *border : points).push_back(R * p_C + t);
  }
  return points;
}

void require_frames(const std::vector<PosedDepthFrame>& frames) {
  if (frames.empty()) throw InputError("depth frames", "count", "at least one frame", "none");
  for (const PosedDepthFrame& f : frames)
    if (f.depth == nullptr) throw InputError("depth frames", "depth", "a frame", "none");
}

}  // namespace ferret::internal

namespace ferret {

DepthImageMm fuse_depth_frames(const std::vector<PosedDepthFrame>& frames,
                               const CameraModel& camera) {
  internal::require_frames(frames);
  DepthFrameFusion fusion(camera);
  for (const PosedDepthFrame& f : frames) fusion.add(*f.depth, f.X_WC);
  return fusion.fused();
}

DepthFrameFusion::DepthFrameFusion(CameraModel camera) : camera_(std::move(camera)) {}

void DepthFrameFusion::add(const DepthImageMm& depth, const Pose3& X_WC) {
  const int w = camera_.width_px, h = camera_.height_px;
  if (depth.width_px != w || depth.height_px != h)
    throw InputError("depth frames", "size", fmt::format("the camera's {} x {} px", w, h),
                     fmt::format("{} x {}", depth.width_px, depth.height_px));
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  if (frames_ == 0) {
    if (!rays_) rays_ = internal::rays_of(camera_);
    sum_m_.assign(n, 0.0);
    count_.assign(n, 0);
    X_WC_ = X_WC;
    X_RW_ = X_WC.inverse();
  }
  const std::vector<Eigen::Vector2f>& rays = *rays_;
  const Pose3 X_RC = X_RW_ * X_WC;
  const bool same_pose = X_RC.isApprox(Pose3::Identity(), 1e-12);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint16_t mm = depth.data[i];
    if (mm == 0) continue;
    const double z = 1e-3 * mm;
    std::size_t k = i;
    double z_R = z;
    if (!same_pose) {
      const Eigen::Vector3d p_R = X_RC * Eigen::Vector3d(rays[i].x() * z, rays[i].y() * z, z);
      const auto px = camera_.project(p_R);
      if (!px) continue;
      if (!camera_.in_image(*px)) continue;  // beyond the first frame's view
      // The nearest pixel (non-negative after the test above, so truncation rounds;
      // lround took a fifth of the time).
      const auto u = static_cast<std::size_t>(px->x() + 0.5);
      const auto v = static_cast<std::size_t>(px->y() + 0.5);
      k = v * static_cast<std::size_t>(w) + u;
      z_R = p_R.z();
    }
    sum_m_[k] += z_R;
    ++count_[k];
  }
  ++frames_;
}

DepthImageMm DepthFrameFusion::fused() const {
  if (frames_ == 0) throw InputError("depth frames", "count", "at least one frame", "none");
  DepthImageMm out(camera_.width_px, camera_.height_px);
  for (std::size_t k = 0; k < count_.size(); ++k)
    if (count_[k] > 0)
      out.data[k] = static_cast<std::uint16_t>(
          std::clamp(std::floor(1000.0 * sum_m_[k] / count_[k] + 0.5), 1.0, 65535.0));
  return out;
}

void DepthFrameFusion::clear() {
  frames_ = 0;  // the sums are reset by the next first frame; the rays are the camera's
}

}  // namespace ferret
