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

  /// Computes the field from `start`. The robot may stand inside the clearance band of
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
  [[nodiscard]] bool crossable(std::size_t idx) const;
  [[nodiscard]] bool line_of_sight(Cell a, Cell b) const;

  GridGeometry geometry_;
  Cell start_;
  std::vector<std::int32_t> cost_;
  std::vector<std::int32_t> parent_;
  std::vector<float> distance_m_;
  std::vector<std::uint8_t> crossable_;
  std::vector<std::uint8_t> band_;
  std::vector<std::uint8_t> seen_;
};

}  // namespace ferret
