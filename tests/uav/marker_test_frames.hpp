#pragma once
// Test frames with a marker at a known pose: each pixel's ray (through the camera
// model, distortion included) meets the marker's plane, and the marker bitmap (with a
// white quiet zone) or a textured background is sampled there, 4x4 samples a pixel so
// edges are anti-aliased as a real lens and sensor would. Ground truth is exact: the
// corners are CameraModel::project of the black square's corners. Test-only; the
// simulator's renderer is sim/'s.

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/core/random.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/image.hpp"
#include "ferret/perception/marker_family.hpp"

namespace ferret::test {

/// A dictionary by family and name (a function: GCC 12 warns about brace-initialised
/// MarkerDictionary temporaries in initializer lists).
inline MarkerDictionary dictionary(MarkerFamily family, const std::string& name) {
  MarkerDictionary d;
  d.family = family;
  d.name = name;
  return d;
}

struct MarkerScene {
  MarkerDictionary dictionary;
  int id = 0;
  double size_m = 0.2;  ///< black square side
  Pose3 X_CM = Pose3::Identity();
  /// White border around the black square, in cells (a printed marker's quiet zone).
  double quiet_zone_cells = 1.0;
  /// Share of the marker (from its right edge, in M's x) covered by a grey card.
  double occluded_fraction = 0.0;
  double blur_sigma_px = 0.0;  ///< Gaussian blur after sampling
  double noise_sigma = 0.0;    ///< grey levels of per-pixel Gaussian noise
  double exposure_gain = 1.0;  ///< multiplies every grey level
  bool draw_marker = true;     ///< false: background only
  std::uint64_t seed = 1;
};

/// Corners of the black square in OpenCV order (TL, TR, BR, BL of the marker image).
inline std::array<Eigen::Vector3d, 4> black_square_corners_M(double size_m) {
  const double h = size_m / 2;
  return {Eigen::Vector3d{-h, h, 0}, Eigen::Vector3d{h, h, 0}, Eigen::Vector3d{h, -h, 0},
          Eigen::Vector3d{-h, -h, 0}};
}

inline std::array<Eigen::Vector2d, 4> true_corners_px(const CameraModel& camera,
                                                      const MarkerScene& s) {
  std::array<Eigen::Vector2d, 4> out;
  const auto c = black_square_corners_M(s.size_m);
  for (int i = 0; i < 4; ++i) out[i] = *camera.project(s.X_CM * c[i]);
  return out;
}

/// Smooth random texture in 0..255 (value noise on a 23 px lattice plus fine grain).
class Texture {
 public:
  explicit Texture(std::uint64_t seed, int w, int h) : w_(w / 23 + 3), h_(h / 23 + 3) {
    Rng rng(seed);
    lattice_.resize(static_cast<std::size_t>(w_ * h_));
    for (auto& v : lattice_) v = rng.uniform(30.0, 225.0);
  }
  [[nodiscard]] double at(double x, double y) const {
    const double gx = std::clamp(x / 23.0, 0.0, w_ - 2.001),
                 gy = std::clamp(y / 23.0, 0.0, h_ - 2.001);
    const int ix = static_cast<int>(gx), iy = static_cast<int>(gy);
    const double fx = gx - ix, fy = gy - iy;
    auto L = [&](int a, int b) { return lattice_[static_cast<std::size_t>(b * w_ + a)]; };
    return (1 - fy) * ((1 - fx) * L(ix, iy) + fx * L(ix + 1, iy)) +
           fy * ((1 - fx) * L(ix, iy + 1) + fx * L(ix + 1, iy + 1));
  }

 private:
  int w_, h_;
  std::vector<double> lattice_;
};

inline GrayImage render_marker_frame(const CameraModel& camera, const MarkerScene& s) {
  const MarkerBitmap bitmap = marker_bitmap(s.dictionary, s.id);
  const int total = bitmap.cells.width_px;
  const double cell_m = s.size_m / bitmap.black_square_cells;
  // Bitmap coordinates: (0, 0) at the top-left of the bitmap; M's origin at the centre
  // of the black square.
  const double origin_cells = bitmap.black_square_offset + bitmap.black_square_cells / 2.0;
  const double quiet = std::max(0.0, s.quiet_zone_cells - bitmap.black_square_offset);
  const Pose3 X_MC = s.X_CM.inverse();
  const Eigen::Vector3d p_MC = X_MC.translation();
  const Texture texture(s.seed, camera.width_px, camera.height_px);
  std::vector<double> value(static_cast<std::size_t>(camera.width_px * camera.height_px));
  auto sample = [&](double px, double py) -> double {
    const double bg = texture.at(px, py);
    if (!s.draw_marker) return bg;
    const Eigen::Vector3d ray_M = X_MC.linear() * camera.ray({px, py});
    if (std::abs(ray_M.z()) < 1e-12) return bg;
    const double t = -p_MC.z() / ray_M.z();
    if (t <= 0) return bg;
    const Eigen::Vector3d q = p_MC + t * ray_M;
    const double u = q.x() / cell_m + origin_cells;  // cells, right
    const double v = origin_cells - q.y() / cell_m;  // cells, down
    if (u < -quiet || v < -quiet || u >= total + quiet || v >= total + quiet) return bg;
    if (s.occluded_fraction > 0.0 &&
        q.x() >
            s.size_m / 2 + quiet * cell_m - s.occluded_fraction * (s.size_m + 2 * quiet * cell_m))
      return 128.0;
    if (u < 0 || v < 0 || u >= total || v >= total) return 255.0;
    return bitmap.cells.at(static_cast<int>(u), static_cast<int>(v));
  };
  // Supersample only around the marker (its quiet zone's projection plus a margin):
  // the background texture is smooth, one sample a pixel is exact enough there.
  int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  if (s.draw_marker) {
    const double half_m = (total / 2.0 + quiet) * cell_m;
    const Eigen::Vector3d centre_M{(total / 2.0 - origin_cells) * cell_m,
                                   (origin_cells - total / 2.0) * cell_m, 0};
    double lo_x = 1e18, lo_y = 1e18, hi_x = -1e18, hi_y = -1e18;
    bool all_in_front = true;
    for (double sx : {-1.0, 1.0})
      for (double sy : {-1.0, 1.0}) {
        const auto px =
            camera.project(s.X_CM * (centre_M + Eigen::Vector3d{sx * half_m, sy * half_m, 0}));
        if (!px) {
          all_in_front = false;
          continue;
        }
        lo_x = std::min(lo_x, px->x());
        lo_y = std::min(lo_y, px->y());
        hi_x = std::max(hi_x, px->x());
        hi_y = std::max(hi_y, px->y());
      }
    if (all_in_front) {
      x0 = std::max(0, static_cast<int>(lo_x) - 8);
      y0 = std::max(0, static_cast<int>(lo_y) - 8);
      x1 = std::min(camera.width_px - 1, static_cast<int>(hi_x) + 8);
      y1 = std::min(camera.height_px - 1, static_cast<int>(hi_y) + 8);
    } else {
      x1 = camera.width_px - 1;
      y1 = camera.height_px - 1;
    }
  }
  constexpr int kSub = 4;
  for (int y = 0; y < camera.height_px; ++y)
    for (int x = 0; x < camera.width_px; ++x) {
      if (x < x0 || x > x1 || y < y0 || y > y1) {
        value[static_cast<std::size_t>(y * camera.width_px + x)] = texture.at(x, y);
        continue;
      }
      double sum = 0;
      for (int j = 0; j < kSub; ++j)
        for (int i = 0; i < kSub; ++i)
          sum += sample(x - 0.5 + (i + 0.5) / kSub, y - 0.5 + (j + 0.5) / kSub);
      value[static_cast<std::size_t>(y * camera.width_px + x)] = sum / (kSub * kSub);
    }
  if (s.blur_sigma_px > 0) {
    // Separable Gaussian, clamped at the border.
    const int r = static_cast<int>(std::ceil(3 * s.blur_sigma_px));
    std::vector<double> k(static_cast<std::size_t>(2 * r + 1));
    double ks = 0;
    for (int i = -r; i <= r; ++i)
      ks += k[static_cast<std::size_t>(i + r)] =
          std::exp(-0.5 * i * i / (s.blur_sigma_px * s.blur_sigma_px));
    for (auto& kv : k) kv /= ks;
    std::vector<double> tmp(value.size());
    const int W = camera.width_px, H = camera.height_px;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        double a = 0;
        for (int i = -r; i <= r; ++i)
          a += k[static_cast<std::size_t>(i + r)] *
               value[static_cast<std::size_t>(y * W + std::clamp(x + i, 0, W - 1))];
        tmp[static_cast<std::size_t>(y * W + x)] = a;
      }
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        double a = 0;
        for (int i = -r; i <= r; ++i)
          a += k[static_cast<std::size_t>(i + r)] *
               tmp[static_cast<std::size_t>(std::clamp(y + i, 0, H - 1) * W + x)];
        value[static_cast<std::size_t>(y * W + x)] = a;
      }
  }
  Rng rng(derive_seed(s.seed, {1}));
  GrayImage image(camera.width_px, camera.height_px);
  for (std::size_t i = 0; i < value.size(); ++i) {
    double g = value[i] * s.exposure_gain;
    if (s.noise_sigma > 0) g += rng.normal(0.0, s.noise_sigma);
    image.data[i] = static_cast<std::uint8_t>(std::clamp(std::lround(g), 0L, 255L));
  }
  return image;
}

/// The marker at distance `distance_m` straight ahead, its face turned by `yaw_rad`
/// about the marker's y axis (off-axis angle) and rolled by `roll_rad` in the image.
inline Pose3 marker_ahead(double distance_m, double yaw_rad, double roll_rad = 0.0,
                          const Eigen::Vector2d& offset_m = Eigen::Vector2d::Zero()) {
  // Facing the camera: M's z towards -z_C, y up (-y_C), x right (x_C).
  Eigen::Matrix3d R_facing;
  R_facing << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  Pose3 X_CM = Pose3::Identity();
  X_CM.linear() = R_facing *
                  Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                  Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitY()).toRotationMatrix();
  X_CM.translation() = Eigen::Vector3d(offset_m.x(), offset_m.y(), distance_m);
  return X_CM;
}

}  // namespace ferret::test
