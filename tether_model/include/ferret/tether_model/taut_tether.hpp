#pragma once
// The taut tether in the hidden space (paper sect. III-A): from the winch it drops
// through the entry point E and then lies on the floor along the path the miniUGV
// drove, pulled taut around obstacle corners. Taut, it is the shortest path from E
// to the robot in the homotopy class of the driven path: a polyline E, w_1..w_k, p
// whose wrap points w_i are convex obstacle corners.
//
// The model is incremental. As the robot moves from p to p', the last tether
// segment (from the last anchor a to the robot) sweeps the triangle (a, p, p').
// The first obstacle corner the sweep meets becomes a new wrap point; a wrap point
// is released when the robot crosses the line through it and the anchor before it
// (the tether straightens). Obstacles are occupied cells of a grid, so the corners
// are cell corners where the occupied region is convex; each corner remembers on
// which side its obstacle lies, so a tether grazing a corner wraps only when it is
// pushed into the obstacle.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "ferret/core/grid.hpp"
#include "ferret/tether_model/tether_params.hpp"

namespace ferret {

struct OccupancyMap2D;

/// A convex obstacle corner the tether can wrap around.
struct TetherCorner {
  Eigen::Vector2d p_W;  ///< the corner (a grid vertex)
  /// Occupied quadrants around the corner, bit q for the quadrant whose diagonal is
  /// kQuadrantDiagonal[q]: 0 (+x,+y), 1 (-x,+y), 2 (-x,-y), 3 (+x,-y).
  std::uint8_t occupied_quadrants = 0;
};

/// The convex corners of the blocked cells of a grid, bucketed for range queries.
class TetherCorners {
 public:
  /// Corners of the cells for which `blocked` is true. Cells outside the grid are
  /// treated as not blocked (the robot never leaves the map, so the tether cannot
  /// wrap around its border).
  [[nodiscard]] static std::shared_ptr<const TetherCorners> from_grid(
      const GridGeometry& geometry, const std::function<bool(Cell)>& blocked);
  /// Corners of the occupied cells of a 2D map; unknown cells block when
  /// `unknown_blocks` (the hidden-space policy: never plan a tether through unknown space).
  [[nodiscard]] static std::shared_ptr<const TetherCorners> from_map(const OccupancyMap2D& map,
                                                                     bool unknown_blocks = true);
  /// Corners from an explicit list (tests, polygonal worlds).
  [[nodiscard]] static std::shared_ptr<const TetherCorners> from_list(
      std::vector<TetherCorner> corners);

  [[nodiscard]] const std::vector<TetherCorner>& all() const { return corners_; }
  /// Calls `visit` for every corner whose position lies in [lo, hi] (and maybe a few more).
  void for_each_in_box(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi,
                       const std::function<void(const TetherCorner&)>& visit) const;

 private:
  explicit TetherCorners(std::vector<TetherCorner> corners);
  std::vector<TetherCorner> corners_;
  // Uniform buckets over the corners' bounding box, corner indices per bucket.
  Eigen::Vector2d lo_{0, 0};
  double bucket_m_ = 1.0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<std::uint32_t>> buckets_;
};

/// One wrap point of the tether and the turning direction of the tether there
/// (+1: the tether turns counter-clockwise at the corner, -1: clockwise).
struct WrapPoint {
  Eigen::Vector2d p_W;
  int side = 1;
  friend bool operator==(const WrapPoint&, const WrapPoint&) = default;
};

class TautTether {
 public:
  /// A tether that enters at p_WE with the robot at p_WR, lying straight between them.
  /// @pre the segment from p_WE to p_WR is free (the robot starts where the tether drops).
  TautTether(std::shared_ptr<const TetherCorners> corners, const Eigen::Vector2d& p_WE,
             const Eigen::Vector2d& p_WR);
  /// A tether with the robot at the entry point.
  TautTether(std::shared_ptr<const TetherCorners> corners, const Eigen::Vector2d& p_WE)
      : TautTether(std::move(corners), p_WE, p_WE) {}

  /// A tether that already bends at `wraps` (as a plan file records it), robot at p_WR.
  TautTether(std::shared_ptr<const TetherCorners> corners, const Eigen::Vector2d& p_WE,
             std::vector<WrapPoint> wraps, const Eigen::Vector2d& p_WR);

  /// Drives the robot in a straight line to p_W, wrapping and unwrapping corners.
  void move_to(const Eigen::Vector2d& p_W);

  [[nodiscard]] const Eigen::Vector2d& entry() const { return p_WE_; }
  [[nodiscard]] const Eigen::Vector2d& robot() const { return p_WR_; }
  [[nodiscard]] const std::vector<WrapPoint>& wrap_points() const { return wraps_; }
  /// The last fixed point of the tether: the last wrap point, or the entry.
  [[nodiscard]] const Eigen::Vector2d& anchor() const {
    return wraps_.empty() ? p_WE_ : wraps_.back().p_W;
  }
  /// Taut length on the floor, from the entry through the wrap points to the robot.
  [[nodiscard]] double length_m() const { return fixed_length_m_ + (p_WR_ - anchor()).norm(); }
  /// The tether as a polyline: entry, wrap points, robot.
  [[nodiscard]] std::vector<Eigen::Vector2d> polyline() const;

 private:
  std::shared_ptr<const TetherCorners> corners_;
  Eigen::Vector2d p_WE_;
  Eigen::Vector2d p_WR_;
  std::vector<WrapPoint> wraps_;
  double fixed_length_m_ = 0.0;  ///< entry to the last wrap point
  void update_fixed_length();
};

/// The way back along a taut tether: its wrap points from the robot's end to the
/// entry's, each pushed `offset_m` off its corner to the outside of the tether's bend
/// (a robot there clears the corner). Driving robot -> these -> entry keeps the path in
/// the tether's homotopy class, so the tether only shortens on the way; retracing the
/// driven path would do the same over the whole history.
[[nodiscard]] std::vector<Eigen::Vector2d> way_back_along_tether(const TautTether& tether,
                                                                 double offset_m);

/// The released tether l_0 + taut length must not exceed L (paper sect. III-A:
/// l_t in [l_0, L] during hidden-space operations).
[[nodiscard]] inline bool tether_length_ok(double taut_length_m, const TetherParams& tether) {
  return tether.entry_offset_m + taut_length_m <= tether.total_length_m;
}

}  // namespace ferret
