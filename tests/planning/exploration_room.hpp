#pragma once
// The exploration setting shared by the policy and frontier-sampler tests.

#include <Eigen/Core>
#include <optional>

#include "ferret/planning/exploration_policy.hpp"

namespace ferret::test {

/// A 4 x 2 m room at 0.05 m, left half seen free, right half unknown: the frontier is
/// the column x = 1.975. The robot stands at (0.5, 1) facing +x, at rest.
struct HalfSeenRoom {
  GridGeometry geo{0.0, 0.0, 0.05, 80, 40};
  IrGrid grid{geo, {}};
  ObjectMap objects{geo, {}};
  FrontierTracker tracker{geo};
  GridPathPlanner paths{geo};
  FrontierSets sets;
  Pose2 pose{0.5, 1.0, 0.0};
  Eigen::Vector2d v{0.0, 0.0};

  HalfSeenRoom() {
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 40; ++i) grid.update_cell({i, j}, false);
    refresh();
  }
  /// Frontiers and path distances again, after the grid or the pose changed.
  void refresh() {
    tracker.update(grid);
    paths.compute(grid, geo.cell_at(pose.x_m, pose.y_m), GridPathPlanner::Traversal::kKnownFree);
    sets = tracker.extract(paths.distances_m(), pose, deg_to_rad(60), 4.0);
  }
  [[nodiscard]] ExplorationState state() const {
    return {grid, objects, tracker, sets, paths, pose, v, deg_to_rad(60), 4.0, std::nullopt};
  }
};

}  // namespace ferret::test
