#pragma once
// Private: what a CollisionMap holds. Only planning/src includes this (FCL stays out
// of the public headers).

#include <fcl/geometry/octree/octree.h>
#include <octomap/OcTree.h>

#include <vector>

#include "ferret/planning/collision_map.hpp"

namespace ferret {

/// A dense Euclidean distance field over occupied cells, on a grid aligned with the
/// OctoMap keys (cell = resolution * 2^level). dist_cells holds, per cell, the
/// distance between its centre and the nearest occupied cell's centre, in cells.
struct DistanceField {
  int level = 0;                ///< cell = 2^level voxels along each axis
  double cell_m = 0.0;
  Eigen::Vector3d origin_m = Eigen::Vector3d::Zero();  ///< lower corner of cell (0,0,0)
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();
  std::vector<float> dist_cells;
  bool empty = true;  ///< nothing occupied

  [[nodiscard]] double lower_bound_m(const Eigen::Vector3d& p) const;
};

struct CollisionMap::Data {
  std::shared_ptr<octomap::OcTree> tree;  // heap-owned: FCL keeps a shared_ptr (fcl#602)
  std::shared_ptr<fcl::OcTreed> fcl_tree;
  CollisionMapOptions options;
  std::size_t occupied_leaves = 0;
  DistanceField field;
};

}  // namespace ferret
