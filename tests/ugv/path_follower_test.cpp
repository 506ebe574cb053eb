#include "ferret/ugv/path_follower.hpp"

#include <gtest/gtest.h>

namespace ferret {
namespace {

// 2.5 cm cells (the miniUGV's G in the shipped worlds), all known free but one.
IrGrid free_grid_with_occupied(Cell occupied) {
  GridGeometry g;
  g.resolution_m = 0.025;
  g.width = 40;
  g.height = 40;
  IrGrid grid(g, IrGrid::Options{});
  grid.mark_free_disk({0.5, 0.5}, 1.0);
  grid.set_probability(occupied, 0.97);
  return grid;
}

// Drives the follower on an ideal unicycle; returns whether it reached the goal, and
// whether it ever stood in `avoid`.
struct Drive {
  bool reached = false;
  bool entered_avoided = false;
  Pose2 end;
};
Drive drive(PathFollower& f, Pose2 pose, const IrGrid& grid, Cell avoid, int steps) {
  Drive out;
  const double dt = 0.05;
  for (int k = 0; k < steps && !out.reached; ++k) {
    const VelocityCommand c = f.step(pose, grid, dt, out.reached);
    pose = integrate_unicycle(pose, c, dt);
    if (grid.geometry().cell_at(pose.x_m, pose.y_m) == avoid) out.entered_avoided = true;
  }
  out.end = pose;
  return out;
}

TEST(PathFollower, ARobotOnACellsEdgeGoesToItsCentreBeforeTheSegmentAndIsNotStuck) {
  // The robot stands on the edge x = 0.5 m of its cell (20, 20), 1.5 cm from the cell's
  // centre; the straight line from there to the next waypoint cuts the occupied
  // neighbour (19, 20) at once, the path's own segment from the centre does not.
  // Refused that step, the follower must go to the centre first. (Two_sites with the object in the
  // kiln, seed 2: the miniUGV stood 160 s at a shelf's corner with a path home, and the
  // return failed.)
  const Cell occupied{19, 20};
  const IrGrid grid = free_grid_with_occupied(occupied);
  ASSERT_EQ(grid.label(occupied), GridLabel::kOccupied);
  const Cell start = grid.geometry().cell_at(0.500, 0.505);
  ASSERT_EQ(start, (Cell{20, 20}));
  PathFollower f(RobotOptions{});
  f.set_path({grid.geometry().center(start), {0.4875, 0.3125}, {0.4875, 0.1125}}, std::nullopt);
  const Drive d = drive(f, Pose2{0.500, 0.505, -1.64}, grid, occupied, 400);
  EXPECT_TRUE(d.reached) << "ended at " << d.end.x_m << ", " << d.end.y_m;
  EXPECT_FALSE(d.entered_avoided);
  EXPECT_NEAR(d.end.x_m, 0.4875, 0.1);
  EXPECT_NEAR(d.end.y_m, 0.1125, 0.1);
}

TEST(PathFollower, AFreePathIsFollowedToItsEndWithoutThePreciseRecovery) {
  // The same grid, a path clear of the occupied cell: reached, never near it.
  const Cell occupied{19, 19};
  const IrGrid grid = free_grid_with_occupied(occupied);
  PathFollower f(RobotOptions{});
  f.set_path({{0.6125, 0.6125}, {0.8125, 0.6125}, {0.8125, 0.8125}}, std::nullopt);
  const Drive d = drive(f, Pose2{0.6125, 0.6125, 0.0}, grid, occupied, 400);
  EXPECT_TRUE(d.reached);
  EXPECT_FALSE(d.entered_avoided);
  EXPECT_NEAR(d.end.x_m, 0.8125, 0.1);
  EXPECT_NEAR(d.end.y_m, 0.8125, 0.1);
}

}  // namespace
}  // namespace ferret
