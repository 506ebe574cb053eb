#pragma once
// A 2D occupancy map in the ROS map_server convention: a grid of cells that are
// free, occupied or unknown, with the map's origin at the lower-left corner of
// cell (0, 0). Loaded from and saved to map_server YAML + PGM.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "ferret/core/grid.hpp"

namespace ferret {

enum class CellState : std::uint8_t { kFree = 0, kOccupied = 1, kUnknown = 2 };

struct OccupancyMap2D {
  GridGeometry geometry;
  std::vector<CellState> cells;  ///< geometry.size() entries, index = j * width + i

  [[nodiscard]] CellState at(Cell c) const { return cells[geometry.index(c)]; }
  [[nodiscard]] bool is_free(Cell c) const { return geometry.contains(c) && at(c) == CellState::kFree; }
};

/// Thresholds of a map_server YAML (defaults are map_server's).
struct MapServerMeta {
  std::filesystem::path image;  ///< PGM/PNG path, relative to the YAML
  double resolution_m = 0.05;
  double origin_x_m = 0.0, origin_y_m = 0.0, origin_yaw_rad = 0.0;
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
};

/// Loads a map_server YAML and its image. Throws InputError naming the file and
/// field for anything malformed (missing keys, bad thresholds, truncated PGM, a
/// non-zero origin yaw, which map_server also does not support).
[[nodiscard]] OccupancyMap2D load_map_server(const std::filesystem::path& yaml_path);

/// Writes `<stem>.yaml` and `<stem>.pgm` (trinary: 0 occupied, 254 free, 205
/// unknown) atomically. `yaml_path` must end in .yaml.
void save_map_server(const OccupancyMap2D& map, const std::filesystem::path& yaml_path);

}  // namespace ferret
