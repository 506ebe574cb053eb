#pragma once
// Shortest paths on the IR grid G for the object search: a Dijkstra field from the
// robot over the cells the robot may cross (8-connected, no corner cutting), from
// which path distances to every frontier and the path to any goal follow. The
// tether-aware OMPL planner (planning issue) replaces the path, not the field.
//
// Costs are integers (5 per straight step, 7 per diagonal: sqrt(2) to 1%) so the
// search runs with a bucket queue in time linear in the cells it reaches.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "ferret/core/grid.hpp"
#include "ferret/mapping/frontier.hpp"
#include "ferret/mapping/ir_grid.hpp"

namespace ferret {

class GridPathPlanner {
 public:
  enum class Traversal {
    kKnownFree,    ///< known free and clear of occupied cells (frontier exploration)
    kNotOccupied,  ///< also through unknown cells, still clear of occupied ones (the oracle)
  };

  /// `body_radius_m`: half the robot's width. The escape band (below) waives the
  /// clearance's margin, never the body: a band cell with an occupied cell's centre
  /// within body_radius_m plus half a cell of its own is not crossed, unless the start
  /// is such a cell too and the band cell lies within body_radius_m of it and no nearer
  /// the occupied cells (a robot already touching a wall backs off). 0: a point robot,
  /// the whole clearance waived.
  explicit GridPathPlanner(GridGeometry geometry, double body_radius_m = 0.0);

  /// Sets up the field from `start` (`grid` must have this planner's geometry). The
  /// robot may stand inside the clearance band of a wall it has just seen and must be
  /// able to leave it: band cells connected to the start (within `escape_radius_m`) may
  /// be crossed at a penalty, but are never reachable as goals. Cells with
  /// `blocked[idx] != 0` are never crossed (may be empty).
  ///
  /// The field is grown as far as it is asked about, in the order a whole Dijkstra
  /// would settle it: a distance, path or reachability question settles the cells up
  /// to that cell's cost (an unreachable cell, everything), so a decision that only
  /// looks near the robot costs what lies near it. The answers are those of the whole
  /// field. Not for concurrent readers (asking grows the field).
  void compute(const IrGrid& grid, Cell start, Traversal traversal, double escape_radius_m = 0.0,
               std::span<const std::uint8_t> blocked = {});

  /// Path distance in metres per cell, kUnreachable where unreachable (the whole field).
  [[nodiscard]] std::span<const float> distances_m() const {
    settle_all();
    return distance_m_;
  }
  [[nodiscard]] float distance_m(Cell c) const {
    const std::size_t idx = geometry_.index(c);
    // Only the start and crossable cells (not the band) are ever given a distance: a
    // question about a wall or unknown cell need not grow the field.
    if (cross_[padded(c)] == 1 || c == start_) settle(idx);
    return distance_m_[idx];
  }
  [[nodiscard]] bool reachable(Cell c) const {
    return geometry_.contains(c) && distance_m(c) != kUnreachable;
  }
  [[nodiscard]] Cell start() const { return start_; }

  /// Waypoints (cell centres, world frame) from the start to `goal`, shortened by
  /// line-of-sight over crossable cells; empty if unreachable. The first waypoint
  /// is the start cell's centre.
  [[nodiscard]] std::vector<Eigen::Vector2d> path_to(Cell goal) const;

 private:
  static constexpr int kBuckets = 18;  // the dearest step (a diagonal into the band) + 1
  struct Entry {
    std::uint32_t grid, padded;  // the cell's index in the grid and in the padded layout
  };
  /// Grows the field until the cell at `idx` has its final cost (or nothing is open).
  void settle(std::size_t idx) const {
    while (open_ > 0 && !(cost_[idx] >= 0 && cost_[idx] < current_)) expand_bucket();
  }
  void settle_all() const {
    while (open_ > 0) expand_bucket();
  }
  /// Settles every open cell of cost current_, then moves on to the next cost.
  void expand_bucket() const;
  /// Index of `c` in the padded layout of cross_ (a ring of never-crossable cells round
  /// the grid, so neighbours need no bounds checks).
  [[nodiscard]] std::size_t padded(Cell c) const {
    return static_cast<std::size_t>(c.j + 1) * padded_width_ + static_cast<std::size_t>(c.i + 1);
  }
  [[nodiscard]] bool line_of_sight(Cell a, Cell b) const;
  /// The squared distance (in cells) from `c` to the nearest occupied cell of `grid`
  /// within the body's reach, kNoneNear if there is none.
  static constexpr int kNoneNear = 1 << 30;
  [[nodiscard]] int nearest_occupied2(const IrGrid& grid, Cell c) const;
  void refresh_crossable(const IrGrid& grid, Traversal traversal,
                         std::span<const std::uint8_t> blocked);
  void set_crossable(const IrGrid& grid, Traversal traversal, std::span<const std::uint8_t> blocked,
                     Cell c);

  GridGeometry geometry_;
  double body_radius_m_;
  std::vector<Cell> body_offsets_;  // the cells within the body's reach of a cell
  std::size_t padded_width_;
  Cell start_;
  // The Dijkstra state, per cell of the grid, grown on demand by the const questions and
  // reset through reached_ (the cells the last field reached): a field costs what it
  // reaches, not the grid's size.
  mutable std::vector<std::int32_t> cost_;
  mutable std::vector<std::int32_t> parent_;
  mutable std::vector<float> distance_m_;
  mutable std::vector<std::size_t> reached_;
  mutable std::array<std::vector<Entry>, kBuckets> buckets_;
  mutable std::int32_t current_ = 0;
  mutable std::size_t open_ = 0;
  std::array<std::ptrdiff_t, 8> grid_step_{}, padded_step_{};
  // Padded: 0 never crossed, 1 crossable, 2 the escape band (crossed at a penalty).
  // Kept from field to field and refreshed where the grid's labels changed since.
  std::vector<std::uint8_t> cross_;
  std::vector<std::size_t> band_cells_;  // padded indices set to 2 by the last field
  struct CrossableSource {
    std::uint64_t lineage = 0, revision = 0;
    Traversal traversal = Traversal::kKnownFree;
    bool valid = false;
  } crossable_from_;
  std::vector<std::uint8_t> seen_;
  std::vector<std::size_t> seen_cells_;
};

}  // namespace ferret
