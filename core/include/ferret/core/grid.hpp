#pragma once
// Indexing of a regular 2D grid in the plane: cell (i, j) covers
// [origin + i*res, origin + (i+1)*res) in x and likewise in y; row-major storage
// with index = j * width + i (j = 0 is the bottom row, as in map_server's origin).

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace ferret {

struct Cell {
  int i = 0;  ///< column (x)
  int j = 0;  ///< row (y)
  friend bool operator==(const Cell&, const Cell&) = default;
};

struct GridGeometry {
  double origin_x_m = 0.0;  ///< world x of the lower-left corner of cell (0, 0)
  double origin_y_m = 0.0;
  double resolution_m = 0.05;
  int width = 0;   ///< cells along x
  int height = 0;  ///< cells along y

  [[nodiscard]] std::size_t size() const { return static_cast<std::size_t>(width) * height; }
  [[nodiscard]] bool contains(Cell c) const { return c.i >= 0 && c.j >= 0 && c.i < width && c.j < height; }
  [[nodiscard]] std::size_t index(Cell c) const { return static_cast<std::size_t>(c.j) * width + c.i; }
  [[nodiscard]] Cell cell_of_index(std::size_t idx) const {
    return {static_cast<int>(idx % width), static_cast<int>(idx / width)};
  }
  /// Cell containing a world point (may be outside the grid; check contains()).
  [[nodiscard]] Cell cell_at(double x_m, double y_m) const {
    return {static_cast<int>(std::floor((x_m - origin_x_m) / resolution_m)),
            static_cast<int>(std::floor((y_m - origin_y_m) / resolution_m))};
  }
  /// World position of a cell's centre.
  [[nodiscard]] Eigen::Vector2d center(Cell c) const {
    return {origin_x_m + (c.i + 0.5) * resolution_m, origin_y_m + (c.j + 0.5) * resolution_m};
  }
  [[nodiscard]] double width_m() const { return width * resolution_m; }
  [[nodiscard]] double height_m() const { return height * resolution_m; }

  /// A window of size_x_m x size_y_m centred on `center_W`, its cell edges on multiples
  /// of the resolution (so two windows of one resolution share their cells).
  [[nodiscard]] static GridGeometry centred_on(const Eigen::Vector2d& center_W, double size_x_m,
                                               double size_y_m, double resolution_m) {
    GridGeometry g;
    g.resolution_m = resolution_m;
    g.width = std::max(1, static_cast<int>(std::ceil(size_x_m / resolution_m)));
    g.height = std::max(1, static_cast<int>(std::ceil(size_y_m / resolution_m)));
    g.origin_x_m = std::floor((center_W.x() - 0.5 * g.width * resolution_m) / resolution_m) * resolution_m;
    g.origin_y_m = std::floor((center_W.y() - 0.5 * g.height * resolution_m) / resolution_m) * resolution_m;
    return g;
  }
};

}  // namespace ferret
