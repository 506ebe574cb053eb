#include "ferret/mapping/ir_grid.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace ferret {
namespace {

GridGeometry geometry(int w = 40, int h = 20) { return {0.0, 0.0, 0.05, w, h}; }

TEST(IrGrid, LogOddsUpdateMatchesPaperEquation) {
  IrGrid g(geometry(), {});
  const Cell c{3, 3};
  EXPECT_EQ(g.label(c), GridLabel::kUnknown);
  g.update_cell(c, true);
  EXPECT_NEAR(g.probability(c), 0.7, 1e-6);
  EXPECT_EQ(g.label(c), GridLabel::kOccupied);
  g.update_cell(c, true);  // (1 + (0.3/0.7)(0.3/0.7))^-1
  EXPECT_NEAR(g.probability(c), 0.8448276, 1e-6);
  const Cell d{5, 5};
  g.update_cell(d, true);
  g.update_cell(d, false);  // 0.7 then 0.4
  EXPECT_NEAR(g.probability(d), 0.6086957, 1e-6);
  const Cell e{7, 7};
  g.update_cell(e, false);
  EXPECT_NEAR(g.probability(e), 0.4, 1e-6);
  EXPECT_EQ(g.label(e), GridLabel::kFree);
}

TEST(IrGrid, ClampsAtOctoMapDefaults) {
  IrGrid g(geometry(), {});
  for (int k = 0; k < 20; ++k) g.update_cell({1, 1}, true);
  for (int k = 0; k < 20; ++k) g.update_cell({2, 2}, false);
  EXPECT_NEAR(g.probability({1, 1}), 0.97, 1e-5);
  EXPECT_NEAR(g.probability({2, 2}), 0.12, 1e-5);
  g.update_cell({1, 1}, false);  // clamping keeps the map responsive
  EXPECT_NEAR(g.probability({1, 1}), inverse_logit(logit(0.97) + logit(0.4)), 1e-5);
}

TEST(IrGrid, TraceRayVisitsEveryCellInOrderWithoutGaps) {
  const auto geo = geometry();
  std::vector<Cell> cells;
  trace_ray(geo, {0.025, 0.025}, {0.475, 0.275}, [&](Cell c, double) {
    cells.push_back(c);
    return true;
  });
  ASSERT_FALSE(cells.empty());
  EXPECT_EQ(cells.front(), (Cell{0, 0}));
  EXPECT_EQ(cells.back(), (Cell{9, 5}));
  for (std::size_t k = 1; k < cells.size(); ++k)  // 4-connected steps
    EXPECT_EQ(std::abs(cells[k].i - cells[k - 1].i) + std::abs(cells[k].j - cells[k - 1].j), 1);
  EXPECT_EQ(cells.size(), 15u);  // 9 steps in x + 5 in y + the start cell
}

TEST(IrGrid, ScanMarksFreeUpToTheHitAndLeavesTheRestUnknown) {
  IrGrid g(geometry(), {});
  RangeScan scan{{0.025, 0.525, 0.0}, 1.0, {{0.0, 0.5}}};  // one beam along +x, return at 0.5 m
  g.integrate_scan(scan);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(g.label({i, 10}), GridLabel::kFree) << i;
  EXPECT_EQ(g.label({10, 10}), GridLabel::kOccupied);
  EXPECT_EQ(g.label({11, 10}), GridLabel::kUnknown);
  EXPECT_EQ(g.label({5, 11}), GridLabel::kUnknown);
  // No return: free to the maximum range, nothing occupied.
  IrGrid h(geometry(), {});
  h.integrate_scan({{0.025, 0.525, 0.0}, 1.0, {{0.0, 1.0}}});
  for (int i = 0; i <= 20; ++i) EXPECT_EQ(h.label({i, 10}), GridLabel::kFree) << i;
  EXPECT_EQ(h.label({21, 10}), GridLabel::kUnknown);
}

TEST(IrGrid, OneUpdatePerCellPerScanAndHitWins) {
  IrGrid g(geometry(), {});
  // Two beams 1 degree apart share their first cells: each is still one miss.
  g.integrate_scan({{0.025, 0.525, 0.0}, 1.0, {{0.0, 0.5}, {0.017, 0.5}}});
  EXPECT_NEAR(g.probability({1, 10}), 0.4, 1e-6);
  // A beam passing through a cell another beam hits in the same scan leaves it a hit.
  IrGrid h(geometry(), {});
  h.integrate_scan({{0.025, 0.525, 0.0}, 1.0, {{0.0, 0.3}, {0.0, 0.8}}});
  EXPECT_NEAR(h.probability({6, 10}), 0.7, 1e-6);
}

TEST(IrGrid, InflationTracksOccupiedCellsWithinClearance) {
  IrGrid::Options o;
  o.clearance_m = 0.1;  // two cells
  IrGrid g(geometry(), o);
  g.mark_free_disk({0.5, 0.5}, 0.4);
  const auto idx = [&](Cell c) { return g.geometry().index(c); };
  EXPECT_TRUE(g.traversable(idx({10, 10})));
  g.update_cell({12, 10}, true);
  EXPECT_FALSE(g.traversable(idx({10, 10})));                  // 2 cells away
  EXPECT_TRUE(g.traversable(idx({9, 10})));                    // 3 cells away
  for (int k = 0; k < 3; ++k) g.update_cell({12, 10}, false);  // seen free again
  EXPECT_TRUE(g.traversable(idx({10, 10})));
}

TEST(IrGrid, ReportsChangedCellsOnce) {
  IrGrid g(geometry(), {});
  g.update_cell({1, 1}, true);
  g.update_cell({1, 1}, true);
  g.update_cell({2, 1}, false);
  auto changed = g.take_changed_cells();
  EXPECT_EQ(changed.size(), 2u);
  EXPECT_TRUE(g.take_changed_cells().empty());
}

}  // namespace
}  // namespace ferret
