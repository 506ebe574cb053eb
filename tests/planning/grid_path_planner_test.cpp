// The path field kept from cycle to cycle (which cells may be crossed is refreshed only
// where the grid's labels changed) against a field computed by a new planner each time.

#include "ferret/planning/grid_path_planner.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <random>
#include <vector>

#include "ferret/mapping/ir_grid.hpp"

namespace ferret {
namespace {

void expect_same_field(const GridPathPlanner& kept, const GridPathPlanner& fresh,
                       const GridGeometry& geo, int step) {
  const auto a = kept.distances_m(), b = fresh.distances_m();
  ASSERT_EQ(a.size(), b.size());
  int differ = 0;
  for (std::size_t k = 0; k < a.size(); ++k) differ += a[k] == b[k] ? 0 : 1;
  EXPECT_EQ(differ, 0) << "step " << step;
  // The same paths too (the same parents, the same shortcuts over crossable cells).
  for (std::size_t k = 0; k < a.size(); k += 97) {
    const Cell c = geo.cell_of_index(k);
    EXPECT_EQ(kept.path_to(c), fresh.path_to(c))
        << "step " << step << " cell " << c.i << "," << c.j;
  }
}

// A grid with that clearance, every cell given to `label` once, row by row.
IrGrid labelled_grid(const GridGeometry& geo, double clearance_m,
                     const std::function<void(IrGrid&, Cell)>& label) {
  IrGrid::Options o;
  o.clearance_m = clearance_m;
  IrGrid g(geo, o);
  for (int j = 0; j < geo.height; ++j)
    for (int i = 0; i < geo.width; ++i) label(g, {i, j});
  return g;
}

TEST(GridPathPlanner, AFieldKeptAcrossMapChangesEqualsOneComputedAfresh) {
  // 70 x 50 cells: several 16-cell blocks, a clearance of 3 cells that reaches across
  // their edges.
  const GridGeometry geo{0.0, 0.0, 0.05, 70, 50};
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> ui(0, geo.width - 1), uj(0, geo.height - 1);
  IrGrid g = labelled_grid(geo, 0.15, [&](IrGrid& grid, Cell c) {
    if (ui(rng) < 60) grid.update_cell(c, false);  // most ground known free
  });
  GridPathPlanner kept(geo);
  for (int step = 0; step < 60; ++step) {
    // A few walls appear and some disappear (free rays through them), anywhere: also
    // on block edges, where only the clearance reaches into the next block.
    for (int n = 0; n < 6; ++n) {
      const Cell c{ui(rng), uj(rng)};
      const bool hit = n % 3 != 2;
      for (int k = 0; k < 6; ++k) g.update_cell(c, hit);
      g.update_cell({c.i, std::min(c.j + 1, geo.height - 1)}, hit);
    }
    const Cell start{ui(rng), uj(rng)};
    const auto traversal = step % 7 == 6 ? GridPathPlanner::Traversal::kNotOccupied
                                         : GridPathPlanner::Traversal::kKnownFree;
    const double escape_m = step % 3 == 0 ? 0.0 : 0.3;
    kept.compute(g, start, traversal, escape_m);
    GridPathPlanner fresh(geo);
    fresh.compute(g, start, traversal, escape_m);
    expect_same_field(kept, fresh, geo, step);
  }
}

TEST(GridPathPlanner, QuestionsInAnyOrderGetTheWholeFieldsAnswers) {
  // The field grows only as far as it is asked about: near cells first, far ones, an
  // unreachable one, paths, in random order, each answer the whole field's.
  const GridGeometry geo{0.0, 0.0, 0.05, 60, 45};
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> ui(0, geo.width - 1), uj(0, geo.height - 1);
  IrGrid g = labelled_grid(geo, 0.1, [&](IrGrid& grid, Cell c) {
    grid.update_cell(c, ui(rng) < 2);  // scattered walls
  });
  for (int j = 0; j < geo.height; ++j) g.update_cell({40, j}, true);  // a wall cutting off x > 40
  for (int round = 0; round < 20; ++round) {
    const Cell start{ui(rng) % 38, uj(rng)};
    const double escape_m = round % 2 == 0 ? 0.0 : 0.3;
    GridPathPlanner whole(geo), asked(geo);
    whole.compute(g, start, GridPathPlanner::Traversal::kKnownFree, escape_m);
    const auto all = whole.distances_m();
    asked.compute(g, start, GridPathPlanner::Traversal::kKnownFree, escape_m);
    for (int q = 0; q < 40; ++q) {
      // Mostly near the start, sometimes anywhere (also beyond the wall).
      const Cell c = q % 4 != 3 ? Cell{std::clamp(start.i + ui(rng) % 9 - 4, 0, geo.width - 1),
                                       std::clamp(start.j + uj(rng) % 9 - 4, 0, geo.height - 1)}
                                : Cell{ui(rng), uj(rng)};
      switch (q % 3) {
        case 0:
          EXPECT_EQ(asked.distance_m(c), all[geo.index(c)]) << round << " " << q;
          break;
        case 1:
          EXPECT_EQ(asked.reachable(c), all[geo.index(c)] != kUnreachable) << round << " " << q;
          break;
        default:
          EXPECT_EQ(asked.path_to(c), whole.path_to(c)) << round << " " << q;
          break;
      }
    }
    const auto rest = asked.distances_m();
    EXPECT_TRUE(std::equal(rest.begin(), rest.end(), all.begin(), all.end())) << round;
  }
}

TEST(GridPathPlanner, AnotherGridIsNotTakenForTheOneBefore) {
  const GridGeometry geo{0.0, 0.0, 0.05, 40, 40};
  IrGrid::Options o;
  o.clearance_m = 0.1;
  IrGrid open(geo, o), walled(geo, o);
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i) {
      open.update_cell({i, j}, false);
    }
  // `walled` ends at as many revisions as `open`: by its revisions alone it would pass
  // for `open` unchanged.
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i) walled.update_cell({i, j}, i == 20);
  GridPathPlanner kept(geo);
  kept.compute(open, {5, 5}, GridPathPlanner::Traversal::kKnownFree);
  EXPECT_TRUE(kept.reachable({35, 5}));
  kept.compute(walled, {5, 5}, GridPathPlanner::Traversal::kKnownFree);
  EXPECT_FALSE(kept.reachable({35, 5}));
  // A copy is another grid too: a wall added to the copy only.
  IrGrid copy = open;
  kept.compute(open, {5, 5}, GridPathPlanner::Traversal::kKnownFree);
  for (int j = 0; j < 40; ++j) copy.update_cell({20, j}, true);
  kept.compute(copy, {5, 5}, GridPathPlanner::Traversal::kKnownFree);
  GridPathPlanner fresh(geo);
  fresh.compute(copy, {5, 5}, GridPathPlanner::Traversal::kKnownFree);
  expect_same_field(kept, fresh, geo, 0);
}

TEST(GridPathPlanner, AFieldFromTheSameCellHoldsUntilALabelChanges) {
  const GridGeometry geo{0.0, 0.0, 0.05, 40, 20};
  IrGrid::Options o;
  o.clearance_m = 0.0;
  IrGrid g(geo, o);
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 40; ++i) g.update_cell({i, j}, false);
  GridPathPlanner p(geo);
  p.compute(g, {2, 10}, GridPathPlanner::Traversal::kKnownFree);
  EXPECT_NEAR(p.distance_m({30, 10}), 28 * 0.05, 1e-6);
  g.update_cell({20, 10}, false);  // a miss on free ground: no label changes
  p.compute(g, {2, 10}, GridPathPlanner::Traversal::kKnownFree);
  EXPECT_NEAR(p.distance_m({30, 10}), 28 * 0.05, 1e-6);
  for (int j = 0; j < 19; ++j) g.update_cell({20, j}, true);  // a wall, open at the top
  p.compute(g, {2, 10}, GridPathPlanner::Traversal::kKnownFree);
  GridPathPlanner fresh(geo);
  fresh.compute(g, {2, 10}, GridPathPlanner::Traversal::kKnownFree);
  EXPECT_GT(p.distance_m({30, 10}), 1.5);
  expect_same_field(p, fresh, geo, 0);
  // The same cell with another escape radius or traversal is another field.
  p.compute(g, {2, 10}, GridPathPlanner::Traversal::kNotOccupied, 0.2);
  fresh.compute(g, {2, 10}, GridPathPlanner::Traversal::kNotOccupied, 0.2);
  expect_same_field(p, fresh, geo, 1);
}

TEST(GridPathPlanner, BlockedCellsHoldForTheirFieldOnly) {
  const GridGeometry geo{0.0, 0.0, 0.05, 40, 20};
  IrGrid::Options o;
  o.clearance_m = 0.0;
  IrGrid g(geo, o);
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 40; ++i) g.update_cell({i, j}, false);
  std::vector<std::uint8_t> blocked(geo.size(), 0);
  for (int j = 0; j < 20; ++j) blocked[geo.index({20, j})] = 1;
  GridPathPlanner p(geo);
  p.compute(g, {2, 2}, GridPathPlanner::Traversal::kKnownFree, 0.0, blocked);
  EXPECT_FALSE(p.reachable({30, 2}));
  p.compute(g, {2, 2}, GridPathPlanner::Traversal::kKnownFree);
  EXPECT_NEAR(p.distance_m({30, 2}), 28 * 0.05, 1e-6);
}

TEST(GridPathPlanner, AGridOfAnotherSizeIsRefused) {
  const GridGeometry geo{0.0, 0.0, 0.05, 40, 20}, other{0.0, 0.0, 0.05, 20, 40};
  IrGrid g(other, IrGrid::Options{});
  GridPathPlanner p(geo);
  EXPECT_THROW(p.compute(g, {1, 1}, GridPathPlanner::Traversal::kKnownFree), std::invalid_argument);
}

// 2.5 cm cells, clearance 0.15 m, a wall along y = 0.75-0.775 m with a gap of four cells
// (x 0.725-0.825 m, 10 cm: narrower than the miniUGV's 12 cm body).
IrGrid wall_with_gap(const GridGeometry& geo) {
  return labelled_grid(geo, 0.15, [](IrGrid& g, Cell c) {
    const bool wall = c.j == 30 && (c.i < 29 || c.i > 32);
    g.set_probability(c, wall ? 0.97 : 0.12);
  });
}

// The squared distance in cells from `c` to the nearest occupied cell of `g`.
int nearest_occupied2(const IrGrid& g, Cell c) {
  int best = 1 << 30;
  const GridGeometry& geo = g.geometry();
  for (int j = 0; j < geo.height; ++j)
    for (int i = 0; i < geo.width; ++i)
      if (g.label({i, j}) == GridLabel::kOccupied)
        best = std::min(best, (i - c.i) * (i - c.i) + (j - c.j) * (j - c.j));
  return best;
}

TEST(GridPathPlanner, TheEscapeBandWaivesTheClearanceButNeverTheBody) {
  GridGeometry geo;
  geo.resolution_m = 0.025;
  geo.width = geo.height = 60;
  const IrGrid g = wall_with_gap(geo);
  const Cell start = geo.cell_at(0.775, 0.65), goal = geo.cell_at(0.775, 1.0);
  ASSERT_TRUE(g.traversable(geo.index(goal)));
  // A point robot may squeeze through the 10 cm gap in the band (the old rule: the
  // miniUGV's sides went through walls this way).
  GridPathPlanner point(geo);
  point.compute(g, start, GridPathPlanner::Traversal::kKnownFree, 1.0);
  EXPECT_TRUE(point.reachable(goal));
  // A 12 cm body may not: every cell of the gap has a wall cell within 6 cm and half a
  // cell.
  GridPathPlanner body(geo, 0.06);
  body.compute(g, start, GridPathPlanner::Traversal::kKnownFree, 1.0);
  EXPECT_FALSE(body.reachable(goal));
  // It still leaves the band on its own side, keeping the body off the wall.
  const Cell away = geo.cell_at(0.775, 0.3);
  ASSERT_TRUE(body.reachable(away));
  for (const auto& p : body.path_to(away))
    EXPECT_GT(nearest_occupied2(g, geo.cell_at(p.x(), p.y())), 8);  // > 2.9 cells
}

TEST(GridPathPlanner, ABodyTouchingAWallBacksOffNeverCloser) {
  GridGeometry geo;
  geo.resolution_m = 0.025;
  geo.width = geo.height = 60;
  const IrGrid g = wall_with_gap(geo);
  // Two cells below the wall (5 cm between centres): the body touches it.
  const Cell start{10, 28};
  ASSERT_LE(nearest_occupied2(g, start), 8);
  GridPathPlanner body(geo, 0.06);
  body.compute(g, start, GridPathPlanner::Traversal::kKnownFree, 1.0);
  const Cell away{10, 10};
  ASSERT_TRUE(body.reachable(away));
  // Its path's cells lie no nearer the wall than the start, and the way runs straight
  // off it (the shortest way out of the band).
  const int start_gap2 = nearest_occupied2(g, start);
  std::vector<Cell> cells;
  for (const auto& p : body.path_to(away)) cells.push_back(geo.cell_at(p.x(), p.y()));
  ASSERT_GE(cells.size(), 2u);
  for (const Cell& c : cells) EXPECT_GE(nearest_occupied2(g, c), start_gap2);
  // Along the wall, within the band, nothing is a goal, and the far side stays out of reach.
  EXPECT_FALSE(body.reachable({10, 32}));
}

}  // namespace
}  // namespace ferret
