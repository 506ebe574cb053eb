#pragma once
// The IR occupancy grid G of the object search (paper sect. IV-B, eq. (occ)): a 2D
// log-odds grid updated from IR range beams, with OctoMap's inverse sensor model
// (hit 0.7, miss 0.4, clamped to [0.12, 0.97]). Cells never touched by a ray are
// unknown; the others are occupied at p >= 0.5 and free below (OctoMap's rule).
//
// The grid also keeps what the explorer asks of it every decision, incrementally:
// an inflation count (how many occupied cells lie within the robot's clearance) so
// that "can the robot stand here" is O(1), and the list of cells whose label
// changed since the frontier tracker last looked.

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

#include "ferret/core/grid.hpp"
#include "ferret/core/pose.hpp"
#include "ferret/mapping/block_revisions.hpp"

namespace ferret {

enum class GridLabel : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

/// One beam of a planar range sensor; `bearing_rad` is relative to the sensor heading.
struct RangeBeam {
  double bearing_rad = 0.0;
  double range_m = 0.0;  ///< measured range; >= the scan's max_range_m means "no return"
};

/// One scan of a planar range sensor (the IR fan, or the camera used as a range finder).
struct RangeScan {
  Pose2 X_WS;                ///< sensor pose in the world (map) frame
  double max_range_m = 4.0;  ///< D_IR (or D_cam)
  std::vector<RangeBeam> beams;
};

/// Visits the cells a segment crosses, in order from `from` to `to` (Amanatides-Woo
/// traversal: every cell the segment touches, no gaps, no duplicates). `visit(Cell,
/// double distance_m)` gets the distance from `from` to the cell's entry point and
/// returns false to stop. Cells outside the grid end the traversal.
template <class Visit>
void trace_ray(const GridGeometry& g, const Eigen::Vector2d& from, const Eigen::Vector2d& to,
               Visit&& visit) {
  const double res = g.resolution_m;
  const double fx = (from.x() - g.origin_x_m) / res, fy = (from.y() - g.origin_y_m) / res;
  const double tx = (to.x() - g.origin_x_m) / res, ty = (to.y() - g.origin_y_m) / res;
  int i = static_cast<int>(std::floor(fx)), j = static_cast<int>(std::floor(fy));
  const int ei = static_cast<int>(std::floor(tx)), ej = static_cast<int>(std::floor(ty));
  const double dx = tx - fx, dy = ty - fy;
  const double len_cells = std::hypot(dx, dy);
  const int si = dx > 0 ? 1 : (dx < 0 ? -1 : 0), sj = dy > 0 ? 1 : (dy < 0 ? -1 : 0);
  constexpr double kInf = 1e30;
  // Parameter t in [0, 1] along the segment where the next vertical/horizontal line is crossed.
  const double dt_i = si != 0 ? 1.0 / std::abs(dx) : kInf,
               dt_j = sj != 0 ? 1.0 / std::abs(dy) : kInf;
  double t_i =
      si > 0 ? (std::floor(fx) + 1 - fx) * dt_i : (si < 0 ? (fx - std::floor(fx)) * dt_i : kInf);
  double t_j =
      sj > 0 ? (std::floor(fy) + 1 - fy) * dt_j : (sj < 0 ? (fy - std::floor(fy)) * dt_j : kInf);
  double t = 0.0;
  const int max_steps = std::abs(ei - i) + std::abs(ej - j) + 1;
  for (int step = 0; step < max_steps; ++step) {
    const Cell c{i, j};
    if (!g.contains(c)) return;
    if (!visit(c, t * len_cells * res)) return;
    if (t_i < t_j) {
      t = t_i;
      t_i += dt_i;
      i += si;
    } else {
      t = t_j;
      t_j += dt_j;
      j += sj;
    }
    if (t > 1.0) return;
  }
}

class IrGrid {
 public:
  /// OctoMap's defaults; `clearance_m` is the robot's radius plus margin.
  struct Options {
    double prob_hit = 0.7;
    double prob_miss = 0.4;
    double clamp_min = 0.12;
    double clamp_max = 0.97;
    double clearance_m = 0.15;
  };

  IrGrid(GridGeometry geometry, Options options);

  /// Folds one scan in: cells a beam passes are misses, the cell where it returns is a
  /// hit; within one scan a cell is updated at most once and a hit wins over a miss
  /// (as OctoMap's insertPointCloud does), so many beams near the sensor do not count
  /// as many observations.
  void integrate_scan(const RangeScan& scan);

  /// One update of one cell, paper eq. (occ) in log-odds form:
  /// l_t = clamp(l_{t-1} + logit(p(g | z_t))), prior 0.5 (log-odds 0).
  void update_cell(Cell c, bool hit);
  /// Sets a cell to an occupancy probability (clamped to [clamp_min, clamp_max]) as if
  /// observed: a grid received from elsewhere (the planner service's next-goal request).
  void set_probability(Cell c, double p_occupied);

  /// Marks the cells within `radius_m` of `p_W` free (the robot knows the ground it
  /// stands on before its first scan).
  void mark_free_disk(const Eigen::Vector2d& p_W, double radius_m);

  [[nodiscard]] const GridGeometry& geometry() const { return geometry_; }
  [[nodiscard]] const Options& options() const { return options_; }
  [[nodiscard]] float log_odds(Cell c) const { return log_odds_[geometry_.index(c)]; }
  [[nodiscard]] double probability(Cell c) const;
  [[nodiscard]] GridLabel label(Cell c) const {
    return static_cast<GridLabel>(label_[geometry_.index(c)]);
  }
  [[nodiscard]] GridLabel label_at(std::size_t idx) const {
    return static_cast<GridLabel>(label_[idx]);
  }
  /// True when an occupied cell lies within clearance_m of `c` (or `c` is occupied).
  [[nodiscard]] bool near_occupied(std::size_t idx) const { return inflation_[idx] > 0; }
  /// Known free and clear of every occupied cell by clearance_m: the robot may stand here.
  [[nodiscard]] bool traversable(std::size_t idx) const {
    return label_[idx] == static_cast<std::uint8_t>(GridLabel::kFree) && inflation_[idx] == 0;
  }
  /// Cells whose label changed since the last call (each index once).
  [[nodiscard]] std::vector<std::size_t> take_changed_cells();
  /// Where and when labels changed, for readers that keep what they computed from them.
  [[nodiscard]] const BlockRevisions& label_revisions() const { return label_revisions_; }

 private:
  void set_label(std::size_t idx, GridLabel label);

  GridGeometry geometry_;
  Options options_;
  float l_hit_, l_miss_, l_min_, l_max_;
  std::vector<float> log_odds_;
  std::vector<std::uint8_t> label_;
  std::vector<std::uint16_t> inflation_;
  std::vector<Cell> inflation_offsets_;
  std::vector<std::size_t> changed_;
  std::vector<std::uint8_t> changed_flag_;
  BlockRevisions label_revisions_{geometry_};
  // Per-cell stamps of the scan being integrated (one update per cell per scan).
  std::vector<std::uint32_t> hit_stamp_, free_stamp_;
  std::uint32_t scan_id_ = 0;
};

/// logit(p) = ln(p / (1 - p)).
[[nodiscard]] inline double logit(double p) { return std::log(p / (1.0 - p)); }
/// The inverse of logit.
[[nodiscard]] inline double inverse_logit(double l) { return 1.0 / (1.0 + std::exp(-l)); }

}  // namespace ferret
