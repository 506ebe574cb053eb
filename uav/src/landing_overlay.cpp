// The landing overlay: a picture a person can hold next to the depth frame.
#include <algorithm>
#include <cmath>

#include "ferret/uav/landing_zone.hpp"

namespace ferret {
namespace {

void put(RgbImage& img, int x, int y, const std::array<std::uint8_t, 3>& rgb) {
  if (x < 0 || y < 0 || x >= img.width_px || y >= img.height_px) return;
  for (int c = 0; c < 3; ++c) img.at(x, y, c) = rgb[static_cast<std::size_t>(c)];
}

void disc(RgbImage& img, const Eigen::Vector2d& c, double r,
          const std::array<std::uint8_t, 3>& rgb) {
  const int r_px = static_cast<int>(std::ceil(r));
  for (int dy = -r_px; dy <= r_px; ++dy)
    for (int dx = -r_px; dx <= r_px; ++dx)
      if (dx * dx + dy * dy <= r * r)
        put(img, static_cast<int>(std::lround(c.x())) + dx,
            static_cast<int>(std::lround(c.y())) + dy, rgb);
}

void ring(RgbImage& img, const Eigen::Vector2d& c, double r, double width,
          const std::array<std::uint8_t, 3>& rgb) {
  const int r_px = static_cast<int>(std::ceil(r + width));
  for (int dy = -r_px; dy <= r_px; ++dy)
    for (int dx = -r_px; dx <= r_px; ++dx) {
      const double d = std::hypot(dx, dy);
      if (d >= r - 0.5 * width && d <= r + 0.5 * width)
        put(img, static_cast<int>(std::lround(c.x())) + dx,
            static_cast<int>(std::lround(c.y())) + dy, rgb);
    }
}

// A blue (near) to yellow (far) ramp, dimmed so that the markings stand out.
std::array<std::uint8_t, 3> ramp(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const auto c = [](double v) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 200.0));
  };
  return {c(t), c(0.3 + 0.6 * t), c(1.0 - t)};
}

}  // namespace

RgbImage landing_overlay(const DepthImageMm& depth, const CameraModel& camera, const Pose3& X_WC,
                         const LandingResult& result, double footprint_radius_m) {
  RgbImage img(depth.width_px, depth.height_px, 0);
  std::uint16_t dmin = 0xffff, dmax = 0;
  for (const auto d : depth.data)
    if (d != 0) {
      dmin = std::min(dmin, d);
      dmax = std::max(dmax, d);
    }
  const double span = dmax > dmin ? static_cast<double>(dmax - dmin) : 1.0;
  for (int y = 0; y < depth.height_px; ++y)
    for (int x = 0; x < depth.width_px; ++x) {
      const std::uint16_t d = depth.at(x, y);
      if (d == 0) continue;  // no return stays black
      const auto c = ramp((d - dmin) / span);
      for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[static_cast<std::size_t>(k)];
    }
  const Pose3 X_CW = X_WC.inverse();
  const auto pixel = [&](const Eigen::Vector3d& p_W,
                         double* radius_px) -> std::optional<Eigen::Vector2d> {
    const Eigen::Vector3d p_C = X_CW * p_W;
    const auto px = camera.project(p_C);
    if (px && radius_px != nullptr) *radius_px = footprint_radius_m * camera.fx_px / p_C.z();
    return px;
  };
  for (const auto& z : result.rejected)
    if (const auto px = pixel(z.center_m, nullptr)) disc(img, *px, 1.5, {220, 30, 30});
  for (std::size_t k = result.zones.size(); k-- > 0;) {
    double r = 0.0;
    if (const auto px = pixel(result.zones[k].center_m, &r)) {
      disc(img, *px, 2.5, {40, 230, 40});
      ring(img, *px, r, 2.0, {40, 230, 40});
      if (k == 0) {
        ring(img, *px, r + 3.0, 3.0, {255, 255, 255});
        disc(img, *px, 4.0, {255, 255, 255});
      }
    }
  }
  return img;
}

}  // namespace ferret
