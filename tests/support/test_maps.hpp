#pragma once
// Small hidden-space maps built in code for the object-search tests (fast to explore).

#include <filesystem>

#include "ferret/mapping/occupancy_map_2d.hpp"

namespace ferret::test {

/// A 5 x 3 m room at 0.05 m: walls all round, a box at [2.0, 2.4] x [0.0, 1.6] (a
/// partition open above it) and a pillar at [3.5, 3.7] x [1.8, 2.0].
inline OccupancyMap2D small_hidden_space() {
  OccupancyMap2D m;
  m.geometry = {0.0, 0.0, 0.05, 100, 60};
  m.cells.assign(m.geometry.size(), CellState::kFree);
  auto box = [&](double x0, double y0, double x1, double y1) {
    for (int j = 0; j < m.geometry.height; ++j)
      for (int i = 0; i < m.geometry.width; ++i) {
        const auto c = m.geometry.center({i, j});
        if (c.x() >= x0 && c.x() <= x1 && c.y() >= y0 && c.y() <= y1)
          m.cells[m.geometry.index({i, j})] = CellState::kOccupied;
      }
  };
  box(0.0, 0.0, 0.1, 3.0);
  box(4.9, 0.0, 5.0, 3.0);
  box(0.0, 0.0, 5.0, 0.1);
  box(0.0, 2.9, 5.0, 3.0);
  box(2.0, 0.0, 2.4, 1.6);
  box(3.5, 1.8, 3.7, 2.0);
  return m;
}

/// A 4 x 3 m room at 0.05 m with walls all round and a partition whose face is at
/// x = 2.5 m (cells 2.5-2.55 m), for y < 1.5 m.
inline OccupancyMap2D room_with_partition() {
  OccupancyMap2D m;
  m.geometry = {0.0, 0.0, 0.05, 80, 60};
  m.cells.assign(m.geometry.size(), CellState::kFree);
  for (int j = 0; j < 60; ++j)
    for (int i = 0; i < 80; ++i)
      if (i == 0 || j == 0 || i == 79 || j == 59 || (i == 50 && j < 30))
        m.cells[m.geometry.index({i, j})] = CellState::kOccupied;
  return m;
}

}  // namespace ferret::test
