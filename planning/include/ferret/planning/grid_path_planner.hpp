#pragma once
// Shortest paths on the IR grid G for the object search: a Dijkstra field from the
// robot over the cells the robot may cross (8-connected, no corner cutting), from
// which path distances to every frontier and the path to any goal follow. The
// tether-aware OMPL planner (planning issue) replaces the path, not the field.
//
// Costs are integers (5 per straight step, 7 per diagonal: sqrt(2) to 1%) so the
// search runs with a bucket queue in time linear in the cells it reaches.

#include <Eigen/Core>
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

  explicit GridPathPlanner(GridGeometry geometry);

  /// Computes the field from `start` (`grid` must have this planner's geometry). The robot may stand inside the clearance band of
  /// a wall it has just seen and must be able to leave it: band cells connected to the
  /// start (within `escape_radius_m`) may be crossed at a penalty, but are never
  /// reachable as goals. Cells with `blocked[idx] != 0` are never crossed (may be empty).
  void compute(const IrGrid& grid, Cell start, Traversal traversal, double escape_radius_m = 0.0,
               std::span<const std::uint8_t> blocked = {});

  /// Path distance in metres per cell, kUnreachable where unreachable.
  [[nodiscard]] std::span<const float> distances_m() const { return distance_m_; }
  [[nodiscard]] float distance_m(Cell c) const { return distance_m_[geometry_.index(c)]; }
  [[nodiscard]] bool reachable(Cell c) const {
    return geometry_.contains(c) && distance_m(c) != kUnreachable;
  }
  [[nodiscard]] Cell start() const { return start_; }

  /// Waypoints (cell centres, world frame) from the start to `goal`, shortened by
  /// line-of-sight over crossable cells; empty if unreachable. The first waypoint
  /// is the start cell's centre.
  [[nodiscard]] std::vector<Eigen::Vector2d> path_to(Cell goal) const;

 private:
  /// Index of `c` in the padded layout of cross_ (a ring of never-crossable cells round
  /// the grid, so neighbours need no bounds checks).
  [[nodiscard]] std::size_t padded(Cell c) const {
    return static_cast<std::size_t>(c.j + 1) * padded_width_ + static_cast<std::size_t>(c.i + 1);
  }
  [[nodiscard]] bool line_of_sight(Cell a, Cell b) const;
  void refresh_crossable(const IrGrid& grid, Traversal traversal, std::span<const std::uint8_t> blocked);
  void set_crossable(const IrGrid& grid, Traversal traversal, std::span<const std::uint8_t> blocked, Cell c);

  GridGeometry geometry_;
  std::size_t padded_width_;
  Cell start_;
  // Per cell of the grid, reset through reached_ (the cells the last field reached), so a
  // field costs what it reaches, not the grid's size.
  std::vector<std::int32_t> cost_;
  std::vector<std::int32_t> parent_;
  std::vector<float> distance_m_;
  std::vector<std::size_t> reached_;
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
