// A downstream program: writes a small map with ferret::mapping and reads it back.
#include <cstdio>
#include <ferret/core/error.hpp>
#include <ferret/mapping/occupancy_map_2d.hpp>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  ferret::OccupancyMap2D map;
  map.geometry = ferret::GridGeometry{0.0, 0.0, 0.1, 4, 3};
  map.cells.assign(map.geometry.size(), ferret::CellState::kFree);
  map.cells[map.geometry.index({2, 1})] = ferret::CellState::kOccupied;
  try {
    ferret::save_map_server(map, argv[1]);
    const auto back = ferret::load_map_server(argv[1]);
    int occupied = 0;
    for (auto c : back.cells) occupied += c == ferret::CellState::kOccupied;
    std::printf("consumer ok: %dx%d cells, %d occupied\n", back.geometry.width,
                back.geometry.height, occupied);
  } catch (const ferret::InputError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
