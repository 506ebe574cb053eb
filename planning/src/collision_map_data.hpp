#pragma once
// Private: what a CollisionMap holds. Only planning/src includes this (FCL stays out
// of the public headers).

#include <fcl/geometry/octree/octree.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "ferret/planning/collision_map.hpp"

namespace ferret {

/// A dense Euclidean distance field over occupied cells, on a grid aligned with the
/// OctoMap keys (cell = resolution * 2^level). Each cell holds the distance between its
/// centre and the nearest occupied cell's centre, in 1/64 cells rounded down (so
/// every bound built on it stays a lower bound), saturating at 1023 cells.
struct DistanceField {
  static constexpr double kUnitsPerCell = 64.0;
  int level = 0;  ///< cell = 2^level voxels along each axis
  double cell_m = 0.0;
  Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();  ///< lower corner of cell (0,0,0)
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();
  std::vector<std::uint16_t> dist;
  bool empty = true;                  ///< nothing occupied (in the region, above the floor cut)
  bool covers_all = true;             ///< every occupied voxel is in the grid (no region was given)
  std::optional<double> floor_cut_z;  ///< voxels wholly below are not in the field

  /// Index of the cell holding p, or -1 outside the grid.
  [[nodiscard]] std::ptrdiff_t cell_index(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d rel = (p - origin_m) / cell_m;
    std::ptrdiff_t idx = 0, stride = 1;
    for (int a = 0; a < 3; ++a) {
      const double f = std::floor(rel[a]);
      if (f < 0 || f >= dims[a]) return -1;
      idx += static_cast<std::ptrdiff_t>(f) * stride;
      stride *= dims[a];
    }
    return idx;
  }
  /// A lower bound on the distance from p to the field's occupied voxels.
  [[nodiscard]] double lower_bound_m(const Eigen::Vector3d& p) const;
  /// True when the ball (c, r) provably touches no occupied voxel of the map.
  [[nodiscard]] bool sphere_free(const Eigen::Vector3d& c, double r) const;
  /// 1: p lies in an occupied voxel; 0: it does not; -1: the field cannot tell.
  [[nodiscard]] int occupied_at(const Eigen::Vector3d& p) const;
};

/// For ground robots: a 2D distance field over the columns of a height band (a
/// column is occupied when any occupied voxel overlaps the band). A part that lies
/// within the band vertically is free when its footprint circle clears the columns.
struct BandField {
  double z_lo = 0.0, z_hi = 0.0;
  double cell_m = 0.0;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();
  Eigen::Vector2i dims = Eigen::Vector2i::Zero();
  std::vector<std::uint16_t> dist;  ///< as DistanceField: 1/64 cells, rounded down

  /// True when the disc (c, r) clears every occupied column of the band.
  [[nodiscard]] bool disc_free(const Eigen::Vector2d& c, double r) const;
  /// True when no occupied column overlaps the closed rectangle [lo, hi] (false when
  /// it reaches outside the grid).
  [[nodiscard]] bool rect_free(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi) const;
};

struct CollisionMap::Data {
  std::shared_ptr<octomap::OcTree> tree;  // heap-owned: FCL keeps a shared_ptr (fcl#602)
  std::shared_ptr<fcl::OcTreed> fcl_tree;
  CollisionMapOptions options;
  std::size_t occupied_leaves = 0;
  DistanceField field;
  std::optional<BandField> band;
};

}  // namespace ferret
