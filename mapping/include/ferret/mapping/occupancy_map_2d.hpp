#pragma once
// A 2D occupancy map in the ROS map_server convention: a grid of cells that are
// free, occupied or unknown, with the map's origin at the lower-left corner of
// cell (0, 0). Loaded from and saved to map_server YAML + PGM.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "ferret/core/grid.hpp"

namespace ferret {

enum class CellState : std::uint8_t { kFree = 0, kOccupied = 1, kUnknown = 2 };

struct OccupancyMap2D {
  GridGeometry geometry;
  std::vector<CellState> cells;  ///< geometry.size() entries, index = j * width + i

  /// A map of the given geometry with every cell set to `fill`.
  [[nodiscard]] static OccupancyMap2D filled(const GridGeometry& geometry, CellState fill);

  [[nodiscard]] CellState at(Cell c) const { return cells[geometry.index(c)]; }
  [[nodiscard]] CellState& at(Cell c) { return cells[geometry.index(c)]; }
  [[nodiscard]] bool is_free(Cell c) const {
    return geometry.contains(c) && at(c) == CellState::kFree;
  }
  /// State of the cell holding a world point; kUnknown outside the grid.
  [[nodiscard]] CellState state_at(double x_m, double y_m) const {
    const Cell c = geometry.cell_at(x_m, y_m);
    return geometry.contains(c) ? at(c) : CellState::kUnknown;
  }
  /// Number of cells in `state`.
  [[nodiscard]] std::size_t count(CellState state) const;
};

/// Same geometry (exactly) and the same cell states.
[[nodiscard]] bool operator==(const OccupancyMap2D& a, const OccupancyMap2D& b);

/// How a 2D map becomes a 3D one (extrude_map_2d in world_octree.hpp).
struct Map2DExtrusion {
  double height_m = 0.5;  ///< walls, and known free space, reach this far above the floor
  /// A map needing more voxels (known cells x layers) is refused instead of exhausting
  /// memory and time.
  std::size_t max_voxels = 60'000'000;
};

/// The keys of a map_server YAML (defaults are map_server's).
struct MapServerMeta {
  std::filesystem::path image;  ///< PGM/PNG path, relative to the YAML
  double resolution_m = 0.05;
  double origin_x_m = 0.0, origin_y_m = 0.0, origin_yaw_rad = 0.0;
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  std::string mode = "trinary";  ///< only "trinary" is supported (cells are three-state)
};

/// Reads and checks the keys of a map_server YAML without loading the image.
/// Throws InputError naming the file and field (unknown keys included).
[[nodiscard]] MapServerMeta load_map_server_meta(const std::filesystem::path& yaml_path);
/// The same from the YAML's text (a request body); errors name `source`. The `image`
/// key is read but not opened: the caller supplies the image.
[[nodiscard]] MapServerMeta parse_map_server_meta(const std::string& yaml_text,
                                                  const std::string& source);

/// Does `path` look like a map_server YAML? A .yaml/.yml file with an `image`,
/// `resolution` or `origin` key, which a world YAML never has, so a map_server file
/// that lacks one of them still gets map_server's messages. Throws InputError for a
/// file that is not YAML.
[[nodiscard]] bool is_map_server_yaml(const std::filesystem::path& path);

/// Loads a map_server YAML and its image (binary P5 or ASCII P2 PGM, 8 or 16 bit,
/// or anything OpenCV reads, e.g. PNG). A pixel's occupancy is
/// (255 - v) / 255 with v its grey value scaled to 0..255 (colour channels averaged,
/// alpha ignored), or v / 255 when `negate`; occupancy > occupied_thresh is
/// occupied, < free_thresh free, anything between unknown. The top image row is
/// the map's top (largest y). A `search` mapping (ferret's object-search start and
/// zones, read by `ferret experiment`) is allowed beside map_server's keys. Throws InputError
/// naming the file and field for anything malformed (missing keys, bad thresholds, truncated PGM, a
/// non-zero origin yaw, which map_server also does not honour, a mode other than trinary).
[[nodiscard]] OccupancyMap2D load_map_server(const std::filesystem::path& yaml_path);

/// Writes `<stem>.yaml` and `<stem>.pgm` (trinary: 0 occupied, 254 free, 205
/// unknown; thresholds 0.65/0.196, negate 0) as one output set: both appear or
/// neither. `yaml_path` must end in .yaml; InputError for a YAML or PGM path that is a
/// directory, a FIFO or a device.
/// `extra_yaml`: top-level keys appended to the YAML (the object search's `search`).
void save_map_server(const OccupancyMap2D& map, const std::filesystem::path& yaml_path,
                     const std::string& extra_yaml = "");

/// A greyscale image: rows top to bottom, `width * height` 8-bit values.
struct GreyImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  ///< index = row * width + column, row 0 at the top
};

/// Reads a binary (P5) or ASCII (P2) PGM, scaling samples to 0..255 when maxval is
/// not 255. Throws InputError naming the file and the header field or the pixel
/// data for a wrong magic, a malformed header, or fewer samples than width*height.
[[nodiscard]] GreyImage read_pgm(const std::filesystem::path& path);
/// The same for a PGM's bytes already in memory; errors name `source`.
[[nodiscard]] GreyImage parse_pgm(std::string bytes, const std::string& source);
/// A map image's bytes: PGM (P5 or P2) by its magic, PNG by its signature (through
/// libpng), anything else OpenCV decodes; as load_map_server() reads them. Errors
/// (unreadable, too large, a pixel depth other than 8 or 16 bit) name `source`.
[[nodiscard]] GreyImage decode_map_image(std::string bytes, const std::string& source);
/// A map_server map from its keys and its image, by the rules of load_map_server().
[[nodiscard]] OccupancyMap2D map_from_image(const MapServerMeta& meta, const GreyImage& image);

/// Writes a binary PGM (P5, maxval 255) atomically.
void write_pgm(const GreyImage& image, const std::filesystem::path& path);

}  // namespace ferret
