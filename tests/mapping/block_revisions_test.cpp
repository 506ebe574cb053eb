// Which blocks of a grid changed since a revision: the record the Bayesian viewpoint
// search keeps its views by (a change it misses would keep a stale view).
#include "ferret/mapping/block_revisions.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "ferret/mapping/ir_grid.hpp"
#include "ferret/mapping/object_map.hpp"

namespace ferret {
namespace {

const GridGeometry kGeo{0.0, 0.0, 0.05, 100, 60};  // 5 x 3 m; 4-cell blocks: 25 x 15 of them

TEST(BlockRevisions, ATouchedCellChangesItsBlockOnly) {
  BlockRevisions r(kGeo, 4);
  EXPECT_EQ(r.revision(), 0u);
  EXPECT_TRUE(r.unchanged_since(0, {0, 0}, {99, 59}));
  const std::uint64_t before = r.revision();
  r.touch(kGeo.index({10, 21}));  // block (2, 5): cells i 8..11, j 20..23
  EXPECT_EQ(r.revision(), 1u);
  EXPECT_FALSE(r.unchanged_since(before, {0, 0}, {99, 59}));
  EXPECT_FALSE(r.unchanged_since(before, {11, 23}, {11, 23}));  // the block's last cell
  EXPECT_FALSE(r.unchanged_since(before, {8, 20}, {8, 20}));    // and its first
  EXPECT_TRUE(r.unchanged_since(before, {12, 0}, {99, 59}));    // the blocks east of it
  EXPECT_TRUE(r.unchanged_since(before, {0, 24}, {99, 59}));    // north of it
  EXPECT_TRUE(r.unchanged_since(before, {0, 0}, {7, 59}));      // west of it
  // Since the touch, nothing changed anywhere.
  EXPECT_TRUE(r.unchanged_since(r.revision(), {0, 0}, {99, 59}));
  // A region reaching beyond the grid is clipped to it.
  EXPECT_FALSE(r.unchanged_since(before, {-50, -50}, {200, 200}));
  EXPECT_TRUE(r.unchanged_since(before, {-50, -50}, {7, 19}));
}

TEST(BlockRevisions, TheLastBlocksOfARaggedGridAreCounted) {
  BlockRevisions r(kGeo, 16);  // 100 / 16: 7 blocks, the last 4 cells wide
  r.touch(kGeo.index({99, 59}));
  EXPECT_FALSE(r.unchanged_since(0, {96, 48}, {99, 59}));
  EXPECT_TRUE(r.unchanged_since(0, {0, 0}, {95, 59}));
  EXPECT_THROW(BlockRevisions(kGeo, 0), std::invalid_argument);
}

TEST(BlockRevisions, TheMapsTouchWhatAViewDependsOn) {
  IrGrid grid(kGeo, {});
  const std::uint64_t g0 = grid.label_revisions().revision();
  grid.update_cell({50, 30}, false);  // unknown -> free: a label change
  EXPECT_FALSE(grid.label_revisions().unchanged_since(g0, {50, 30}, {50, 30}));
  const std::uint64_t g1 = grid.label_revisions().revision();
  grid.update_cell({50, 30}, false);  // free again: the label holds, nothing to tell
  EXPECT_EQ(grid.label_revisions().revision(), g1);

  ObjectMap objects(kGeo, {});
  const std::uint64_t o0 = objects.revisions().revision();
  CameraFrame frame;
  frame.view.X_WS = {1.0, 1.5, 0.0};
  frame.view.max_range_m = 1.0;
  for (int k = -10; k <= 10; ++k) frame.view.beams.push_back({deg_to_rad(2.0 * k), 1.0});
  objects.integrate_frame(frame);  // cells east of (1, 1.5) looked at without a detection
  EXPECT_FALSE(
      objects.revisions().unchanged_since(o0, kGeo.cell_at(1.5, 1.5), kGeo.cell_at(1.5, 1.5)));
  EXPECT_TRUE(
      objects.revisions().unchanged_since(o0, kGeo.cell_at(3.5, 0.0), kGeo.cell_at(5.0, 3.0)));
  const std::uint64_t o1 = objects.revisions().revision();
  objects.set_cell(kGeo.cell_at(4.0, 2.5), 0.2, 0.0);
  EXPECT_FALSE(
      objects.revisions().unchanged_since(o1, kGeo.cell_at(4.0, 2.5), kGeo.cell_at(4.0, 2.5)));
}

}  // namespace
}  // namespace ferret
