// PX4-Avoidance's safe_landing_planner rule (the cell test of
// SafeLandingPlanner::isLandingPossible with its published defaults), reimplemented
// on ferret's types so that it runs on the same frames as LandingZoneDetector.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "ferret/core/error.hpp"
#include "ferret/uav/landing_zone.hpp"
#include "landing_points.hpp"

namespace ferret {

namespace {

// One frame binned into the grid: per cell the count, mean and population variance of
// the points' heights (Welford's running sums, as the original accumulates them).
struct Px4Cells {
  std::vector<double> count, mean, variance;
};

Px4Cells bin_frame(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector2d& lo,
                   const Eigen::Vector2d& hi, int n, double cell_m) {
  const auto idx = [n](int i, int j) { return static_cast<std::size_t>(j) * n + i; };
  Px4Cells g;
  g.count.assign(static_cast<std::size_t>(n) * n, 0.0);
  g.mean.assign(g.count.size(), 0.0);
  g.variance.assign(g.count.size(), 0.0);
  std::vector<double> m2(g.count.size(), 0.0);
  for (const auto& p : points) {
    if (!(p.x() > lo.x() && p.x() < hi.x() && p.y() > lo.y() && p.y() < hi.y())) continue;
    const int i = std::min(n - 1, static_cast<int>(std::floor((p.x() - lo.x()) / cell_m)));
    const int j = std::min(n - 1, static_cast<int>(std::floor((p.y() - lo.y()) / cell_m)));
    const std::size_t k = idx(i, j);
    g.count[k] += 1.0;
    const double delta = p.z() - g.mean[k];
    g.mean[k] += delta / g.count[k];
    m2[k] += delta * (p.z() - g.mean[k]);
  }
  for (std::size_t k = 0; k < g.count.size(); ++k)
    if (g.count[k] > 0) g.variance[k] = m2[k] / g.count[k];
  return g;
}

}  // namespace

LandingResult Px4LandingBaseline::detect(const DepthImageMm& depth, const CameraModel& camera,
                                         const Pose3& X_WC, const Eigen::Vector3d& p_WV) const {
  return detect(std::vector<PosedDepthFrame>{{&depth, X_WC}}, camera, p_WV);
}

LandingResult Px4LandingBaseline::detect(const std::vector<PosedDepthFrame>& frames,
                                         const CameraModel& camera,
                                         const Eigen::Vector3d& p_WV) const {
  const Options& o = options_;
  LandingResult result;
  internal::require_frames(frames);
  const int n = static_cast<int>(std::lround(o.grid_size_m / o.cell_size_m));
  // The grid is centred on the vehicle; points on or beyond its border are dropped.
  const Eigen::Vector2d lo = p_WV.head<2>() - Eigen::Vector2d::Constant(0.5 * o.grid_size_m);
  const Eigen::Vector2d hi = lo + Eigen::Vector2d::Constant(o.grid_size_m);
  const auto idx = [n](int i, int j) { return static_cast<std::size_t>(j) * n + i; };
  // Frame by frame, the original's low-pass on the cells' mean and variance (alpha of
  // history), started from the first frame as if the grid had held that view before;
  // the counts are the last frame's, as in the original.
  Px4Cells grid;
  bool any_points = false;
  for (const PosedDepthFrame& f : frames) {
    const std::vector<Eigen::Vector3d> points =
        internal::depth_to_world_points(*f.depth, camera, f.X_WC, o.min_depth_m, o.max_depth_m);
    any_points = any_points || !points.empty();
    Px4Cells cur = bin_frame(points, lo, hi, n, o.cell_size_m);
    if (!grid.count.empty()) {
      for (std::size_t k = 0; k < cur.mean.size(); ++k) {
        cur.mean[k] = o.alpha * grid.mean[k] + (1.0 - o.alpha) * cur.mean[k];
        cur.variance[k] = o.alpha * grid.variance[k] + (1.0 - o.alpha) * cur.variance[k];
      }
    }
    grid = std::move(cur);
  }
  const std::vector<double>& cnt = grid.count;
  const std::vector<double>& mean = grid.mean;
  std::vector<int> land(cnt.size(), 0);
  for (std::size_t k = 0; k < cnt.size(); ++k)
    land[k] =
        (cnt[k] >= o.n_points_threshold && std::sqrt(grid.variance[k]) <= o.std_dev_threshold_m)
            ? 1
            : 0;
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
    result.reason = !any_points ? "no safe zone in view: no depth returns in the frame"
                                : "no safe zone in view: no cell passes the PX4 rule";
  return result;
}

}  // namespace ferret
