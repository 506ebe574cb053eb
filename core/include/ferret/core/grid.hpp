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
  [[nodiscard]] bool contains(Cell c) const {
    return c.i >= 0 && c.j >= 0 && c.i < width && c.j < height;
  }
  [[nodiscard]] std::size_t index(Cell c) const {
    return static_cast<std::size_t>(c.j) * width + c.i;
  }
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
    g.origin_x_m =
        std::floor((center_W.x() - 0.5 * g.width * resolution_m) / resolution_m) * resolution_m;
    g.origin_y_m =
        std::floor((center_W.y() - 0.5 * g.height * resolution_m) / resolution_m) * resolution_m;
    return g;
  }
};

/// How far the cells `blocked(c)` holds reach into the disc of `radius_m` round `p`:
/// radius_m less the distance from p to the nearest such cell's square, 0 when none
/// reaches in. `blocked` is asked about every cell the disc's bounding box touches,
/// inside the grid or not.
template <class Blocked>
[[nodiscard]] double disc_depth_m(const GridGeometry& g, const Eigen::Vector2d& p, double radius_m,
                                  Blocked&& blocked) {
  if (!(radius_m > 0.0)) return 0.0;
  const double half = 0.5 * g.resolution_m;
  double nearest = radius_m;
  const Cell lo = g.cell_at(p.x() - radius_m, p.y() - radius_m);
  const Cell hi = g.cell_at(p.x() + radius_m, p.y() + radius_m);
  for (int j = lo.j; j <= hi.j; ++j)
    for (int i = lo.i; i <= hi.i; ++i) {
      if (!blocked(Cell{i, j})) continue;
      const Eigen::Vector2d gap = ((g.center({i, j}) - p).cwiseAbs().array() - half).cwiseMax(0.0);
      nearest = std::min(nearest, gap.norm());
    }
  return radius_m - nearest;
}

}  // namespace ferret
