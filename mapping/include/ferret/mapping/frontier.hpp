#pragma once
// Frontiers of the IR grid G (paper sect. IV-B, after Cieslewski et al. 2017):
// a frontier cell is a known-free cell with an unknown 8-neighbour.
//  - F_g: every frontier cell the robot can reach (finite path distance), not
//    blacklisted, clustered into 8-connected groups;
//  - F_v: the cells of F_g inside the IR field of view (beta, D_IR) of the pose.
// The tracker keeps the frontier flag of every cell up to date incrementally from
// the cells whose label changed (IrGrid::take_changed_cells), so one extraction
// costs a pass over the frontier cells, not over the grid.
//
// Blacklist: goals that were reached but are still frontier (grazing rays leave
// unknown cells inside walls that no viewpoint resolves) are blacklisted with a
// small radius; without it explorers return to them forever.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "ferret/core/grid.hpp"
#include "ferret/core/pose.hpp"
#include "ferret/mapping/ir_grid.hpp"

namespace ferret {

struct FrontierCluster {
  std::vector<Cell> cells;
  Eigen::Vector2d centroid_W = Eigen::Vector2d::Zero();
  Cell representative;  ///< the member nearest the centroid
};

struct FrontierSets {
  std::vector<Cell> global;               ///< F_g (reachable, not blacklisted)
  std::vector<Cell> visible;              ///< F_v, a subset of F_g
  std::vector<FrontierCluster> clusters;  ///< F_g grouped 8-connected
};

/// The infinite path distance of an unreachable cell.
inline constexpr float kUnreachable = std::numeric_limits<float>::infinity();

class FrontierTracker {
 public:
  struct Options {
    double blacklist_radius_m = 0.15;
  };

  explicit FrontierTracker(GridGeometry geometry) : FrontierTracker(geometry, Options{}) {}
  FrontierTracker(GridGeometry geometry, Options options);

  /// Re-evaluates the cells changed in G since the last call, and their neighbours.
  void update(IrGrid& grid);
  /// Re-evaluates every cell (after building a tracker on a grid with content).
  void rebuild(const IrGrid& grid);

  /// @param path_distance_m per cell, the path distance from the robot (kUnreachable if none)
  /// @param X_WS            the IR sensor pose; F_v is the part of F_g within
  ///                        |bearing| <= ir_fov_rad / 2 and distance <= ir_range_m
  [[nodiscard]] FrontierSets extract(std::span<const float> path_distance_m, const Pose2& X_WS,
                                     double ir_fov_rad, double ir_range_m) const;

  [[nodiscard]] bool is_frontier(Cell c) const { return flag_[geometry_.index(c)] != 0; }
  [[nodiscard]] std::size_t frontier_count() const { return cells_.size(); }
  /// Every frontier cell, blacklisted or not, reachable or not.
  [[nodiscard]] const std::vector<std::size_t>& frontier_cells() const { return cells_; }

  /// Blacklists the cells within blacklist_radius_m of c. `kind` (1..255) tells marks
  /// apart so that one kind can be lifted later (clear_blacklist); a cell keeps the
  /// first kind it was marked with.
  void blacklist(Cell c, std::uint8_t kind = 1);
  /// Lifts every mark of `kind`.
  void clear_blacklist(std::uint8_t kind);
  [[nodiscard]] bool blacklisted(Cell c) const { return blacklist_[geometry_.index(c)] != 0; }
  [[nodiscard]] bool blacklisted_at(std::size_t idx) const { return blacklist_[idx] != 0; }

 private:
  void refresh(const IrGrid& grid, std::size_t idx);

  GridGeometry geometry_;
  Options options_;
  std::vector<std::uint8_t> flag_;
  std::vector<std::int32_t> pos_;  ///< index into cells_, -1 if not a frontier
  std::vector<std::size_t> cells_;
  std::vector<std::uint8_t> blacklist_;
  // extract()'s scratch, all zero between calls (so extract() is not thread-safe).
  mutable std::vector<std::uint8_t> cluster_marks_;
};

}  // namespace ferret
