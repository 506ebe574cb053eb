// PX4-Avoidance's safe_landing_planner rule (the cell test of
// SafeLandingPlanner::isLandingPossible with its published defaults), reimplemented
// on ferret's types so that it runs on the same frames as LandingZoneDetector.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "ferret/uav/landing_zone.hpp"
#include "landing_points.hpp"

namespace ferret {

LandingResult Px4LandingBaseline::detect(const DepthImageMm& depth, const CameraModel& camera,
                                         const Pose3& X_WC, const Eigen::Vector3d& p_WV) const {
  const Options& o = options_;
  LandingResult result;
  const std::vector<Eigen::Vector3d> points =
      internal::depth_to_world_points(depth, camera, X_WC, o.min_depth_m, o.max_depth_m);
  const int n = static_cast<int>(std::lround(o.grid_size_m / o.cell_size_m));
  // The grid is centred on the vehicle; points on or beyond its border are dropped.
  const Eigen::Vector2d lo = p_WV.head<2>() - Eigen::Vector2d::Constant(0.5 * o.grid_size_m);
  const Eigen::Vector2d hi = lo + Eigen::Vector2d::Constant(o.grid_size_m);
  const auto idx = [n](int i, int j) { return static_cast<std::size_t>(j) * n + i; };
  std::vector<double> cnt(static_cast<std::size_t>(n) * n, 0.0), mean(cnt.size(), 0.0),
      m2(cnt.size(), 0.0);
  for (const auto& p : points) {
    if (!(p.x() > lo.x() && p.x() < hi.x() && p.y() > lo.y() && p.y() < hi.y())) continue;
    const int i = std::min(n - 1, static_cast<int>(std::floor((p.x() - lo.x()) / o.cell_size_m)));
    const int j = std::min(n - 1, static_cast<int>(std::floor((p.y() - lo.y()) / o.cell_size_m)));
    const std::size_t k = idx(i, j);
    // Welford's running mean and variance, as the original accumulates them.
    cnt[k] += 1.0;
    const double delta = p.z() - mean[k];
    mean[k] += delta / cnt[k];
    m2[k] += delta * (p.z() - mean[k]);
  }
  std::vector<int> land(cnt.size(), 0);
  for (std::size_t k = 0; k < cnt.size(); ++k) {
    const double var = cnt[k] > 0 ? m2[k] / cnt[k] : 0.0;  // population variance
    land[k] = (cnt[k] >= o.n_points_threshold && std::sqrt(var) <= o.std_dev_threshold_m) ? 1 : 0;
  }
  // The neighbourhood vote; cells beyond the grid count as not landable with mean 0
  // (the original pads with zeros), and so do empty cells (their mean stays 0).
  const int s = o.smoothing_size;
  struct Cand {
    Eigen::Vector3d c;
    double d;
  };
  std::vector<Cand> cands;
  const Eigen::Vector2d target = o.p_WE ? o.p_WE->head<2>() : p_WV.head<2>();
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      int land_count = 0, diff_count = 0;
      const double m0 = mean[idx(i, j)];
      for (int dj = -s; dj <= s; ++dj)
        for (int di = -s; di <= s; ++di) {
          const int ci = i + di, cj = j + dj;
          const bool inside = ci >= 0 && cj >= 0 && ci < n && cj < n;
          const double m = inside ? mean[idx(ci, cj)] : 0.0;
          if (inside) land_count += land[idx(ci, cj)];
          if (std::abs(m0 - m) > o.mean_diff_threshold_m) ++diff_count;
        }
      if (s > 0 && !(land_count > o.min_n_land_cells && diff_count <= o.max_n_mean_diff_cells))
        continue;
      if (s <= 0 && land[idx(i, j)] == 0) continue;
      const Eigen::Vector3d c(lo.x() + (i + 0.5) * o.cell_size_m,
                              lo.y() + (j + 0.5) * o.cell_size_m, m0);
      cands.push_back({c, (c.head<2>() - target).norm()});
    }
  std::sort(cands.begin(), cands.end(), [](const Cand& a, const Cand& b) {
    if (a.d != b.d) return a.d < b.d;
    if (a.c.x() != b.c.x()) return a.c.x() < b.c.x();
    return a.c.y() < b.c.y();
  });
  for (const auto& c : cands) {
    LandingZone z;
    z.center_m = c.c;
    z.distance_to_opening_m = o.p_WE ? c.d : std::numeric_limits<double>::quiet_NaN();
    z.score = -c.d;
    result.zones.push_back(z);
    if (static_cast<int>(result.zones.size()) >= o.max_zones) break;
  }
  result.no_safe_zone = result.zones.empty();
  if (result.no_safe_zone)
    result.reason = points.empty() ? "no safe zone in view: no depth returns in the frame"
                                   : "no safe zone in view: no cell passes the PX4 rule";
  return result;
}

}  // namespace ferret
