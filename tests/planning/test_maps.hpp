#pragma once
// Small OctoMaps built in code for the planning tests.

#include <octomap/OcTree.h>

#include <Eigen/Core>
#include <memory>

#include "ferret/core/random.hpp"

namespace ferret::test {

/// Marks every voxel whose centre lies in [lo, hi] with `occupied`.
inline void fill_box(octomap::OcTree& tree, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                     bool occupied, bool lazy = false) {
  const double r = tree.getResolution();
  for (double z = lo.z() + 0.5 * r; z <= hi.z(); z += r)
    for (double y = lo.y() + 0.5 * r; y <= hi.y(); y += r)
      for (double x = lo.x() + 0.5 * r; x <= hi.x(); x += r)
        tree.updateNode(x, y, z, occupied, lazy);
}

/// A 6 x 6 x 3 m room at 0.1 m: known free inside, a floor, four walls and a few
/// random boxes and posts (seeded).
inline std::unique_ptr<octomap::OcTree> cluttered_room(std::uint64_t seed, double res = 0.1) {
  auto tree = std::make_unique<octomap::OcTree>(res);
  fill_box(*tree, {-3, -3, 0}, {3, 3, 3}, false);
  fill_box(*tree, {-3, -3, -0.2}, {3, 3, 0}, true);
  fill_box(*tree, {-3.2, -3, 0}, {-3, 3, 3}, true);
  fill_box(*tree, {3, -3, 0}, {3.2, 3, 3}, true);
  fill_box(*tree, {-3, -3.2, 0}, {3, -3, 3}, true);
  fill_box(*tree, {-3, 3, 0}, {3, 3.2, 3}, true);
  Rng rng(seed);
  for (int k = 0; k < 12; ++k) {
    const Eigen::Vector3d c{rng.uniform(-2.5, 2.5), rng.uniform(-2.5, 2.5), rng.uniform(0.0, 2.0)};
    const Eigen::Vector3d h{rng.uniform(0.05, 0.5), rng.uniform(0.05, 0.5), rng.uniform(0.1, 1.0)};
    fill_box(*tree, c - h, c + h, true);
  }
  tree->updateInnerOccupancy();
  return tree;
}

}  // namespace ferret::test

namespace ferret::test {

/// A 12 x 8 m hidden space at 0.05 m with a floor at z = 0, known free up to 0.1 m
/// (the miniUGV's height) except for the blocks given as [x0, x1] x [y0, y1] and the
/// never-observed (unknown) patches.
inline std::unique_ptr<octomap::OcTree> hidden_space(
    const std::vector<Eigen::Vector4d>& blocks, const std::vector<Eigen::Vector4d>& unobserved = {},
    double res = 0.05) {
  auto tree = std::make_unique<octomap::OcTree>(res);
  fill_box(*tree, {0, 0, -res}, {12, 8, 0}, true);
  for (double z = 0.5 * res; z <= 0.1; z += res)
    for (double y = 0.5 * res; y <= 8; y += res)
      for (double x = 0.5 * res; x <= 12; x += res) {
        bool seen = true;
        for (const auto& u : unobserved)
          seen = seen && !(x > u[0] && x < u[1] && y > u[2] && y < u[3]);
        if (seen) tree->updateNode(x, y, z, false);
      }
  for (const auto& b : blocks) fill_box(*tree, {b[0], b[2], 0}, {b[1], b[3], 0.1}, true);
  tree->updateInnerOccupancy();
  return tree;
}

}  // namespace ferret::test
