#pragma once
// PNG pictures of 2D maps, with overlays drawn in world coordinates: later stages
// (paths, frontiers, the object map, robot poses) draw on a MapCanvas and save it.
//
//   MapCanvas canvas(map);                       // occupied black, free white, unknown grey
//   canvas.set_title("sparse map, cdos: found in 12.4 s");
//   canvas.draw_path(path_W, Rgb{220, 30, 30});
//   canvas.add_legend("path", Rgb{220, 30, 30}, LegendMark::kLine);
//   canvas.draw_cells(map.geometry, frontier_cells, Rgb{0, 120, 255}, 0.6);
//   canvas.save_png("out.png");                  // atomic; adds the frame and the scale bar
//
// With RenderOptions::frame (the default) the picture is the map in a frame: the title
// above, x and y ticks in metres on the left and below, and on the right the legend
// and (when set) a colour bar. Overlays are clipped to the map.
//
// OpenCV stays inside the implementation.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "ferret/core/grid.hpp"
#include "ferret/core/pose.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/perception/image.hpp"

namespace ferret {

struct WorldSpec;

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

/// The colour of one pixel of an RGB image (perception/image.hpp).
[[nodiscard]] inline Rgb pixel(const RgbImage& image, int column, int row) {
  return {image.at(column, row, 0), image.at(column, row, 1), image.at(column, row, 2)};
}

/// A rectangle of pixels of the picture (column, row of its top-left corner).
struct PixelRect {
  int x = 0, y = 0, width = 0, height = 0;
};

/// How a legend entry shows its colour (the same shapes as the draw_* calls).
enum class LegendMark { kLine, kSwatch, kDot, kSquare, kDiamond, kRing };

/// A colour bar: values 0..1 from `low` (bottom) to `high` (top), as draw_field colours
/// them, with labelled marks (e.g. thresholds) drawn across the bar.
struct ColourBar {
  std::string label;  ///< what the value is, e.g. "P(object) per cell"
  Rgb low, high;
  struct Mark {
    double value = 0.0;  ///< in [0, 1]
    std::string label;
  };
  std::vector<Mark> marks;
};

struct RenderOptions {
  int pixels_per_cell =
      0;  ///< 0: the smallest integer making the longer side >= min_size_px (at most 16)
  int min_size_px = 800;
  double grid_spacing_m = 0.0;  ///< > 0: light grid lines every this many metres
  bool scale_bar = true;        ///< a labelled bar in the lower-left corner
  /// Title, metre axes, legend and colour bar around the map; false: the map alone
  /// (pixel for pixel, e.g. to compare with a map_server image).
  bool frame = true;
  Rgb occupied{0, 0, 0};
  Rgb free{255, 255, 255};
  Rgb unknown{160, 160, 160};
};

class MapCanvas {
 public:
  explicit MapCanvas(const OccupancyMap2D& map, const RenderOptions& options = {});
  ~MapCanvas();
  MapCanvas(MapCanvas&&) noexcept;
  MapCanvas& operator=(MapCanvas&&) noexcept;

  /// A polyline through world points.
  void draw_path(const std::vector<Eigen::Vector2d>& points_W, Rgb color, int thickness_px = 2);
  /// Fills cells of a grid (which need not be the map's) blended with `alpha` in [0, 1].
  void draw_cells(const GridGeometry& grid, const std::vector<Cell>& cells, Rgb color,
                  double alpha = 1.0);
  /// Colours each cell of a grid by a value in [0, 1] between two colours (e.g. the
  /// object map's probabilities); cells whose value is outside [0, 1] are skipped.
  void draw_field(const GridGeometry& grid, const std::vector<double>& values, Rgb low, Rgb high,
                  double alpha = 0.7);
  void draw_point(const Eigen::Vector2d& p_W, Rgb color, int radius_px = 4);
  void draw_circle(const Eigen::Vector2d& center_W, double radius_m, Rgb color,
                   int thickness_px = 2);
  /// A pose as a dot with a heading line `length_m` long.
  void draw_pose(const Pose2& X_W, Rgb color, double length_m = 0.5);
  void draw_text(const Eigen::Vector2d& p_W, const std::string& text, Rgb color);
  /// A marker of `radius_px` at a world point, with a dark outline (kDot, kSquare,
  /// kDiamond filled; kRing an outline; kLine and kSwatch draw a square).
  void draw_marker(const Eigen::Vector2d& p_W, Rgb color, LegendMark shape, int radius_px = 6);

  /// What the picture shows, above the map ('\n' starts a new line); needs `frame`.
  void set_title(std::string title);
  /// A legend entry (in the order added), right of the map; needs `frame`.
  void add_legend(std::string label, Rgb color, LegendMark mark);
  /// A colour bar right of the map, below the legend; needs `frame`.
  void set_colour_bar(ColourBar bar);

  /// Pixel (column, row) of a world point in image(): the map's top-left corner is
  /// map_offset_px(), and a cell is pixels_per_cell() pixels wide.
  [[nodiscard]] Eigen::Vector2d to_pixel(const Eigen::Vector2d& p_W) const;
  /// Where the map lies in image() (without `frame`: at 0, 0, the whole picture).
  [[nodiscard]] PixelRect map_area() const;
  /// Where the legend box and the colour bar's gradient lie in image() (width 0 when
  /// there is none).
  [[nodiscard]] PixelRect legend_area() const;
  [[nodiscard]] PixelRect colour_bar_area() const;
  [[nodiscard]] int pixels_per_cell() const;
  /// True when a world point lies on the map, or within `margin_m` of it.
  [[nodiscard]] bool contains(const Eigen::Vector2d& p_W, double margin_m = 0.0) const;
  /// The picture so far, with the scale bar and the frame when enabled.
  [[nodiscard]] RgbImage image() const;
  /// Writes image() as PNG atomically. The path must end in .png.
  void save_png(const std::filesystem::path& path) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Draws a world's annotations, with legend entries: hidden-space entries with their
/// heading (green), markers (blue, labelled with the space's name and marker id),
/// objects (red), the drop zone (orange circle).
void draw_world_annotations(MapCanvas& canvas, const WorldSpec& world);

/// Writes an RGB image as PNG atomically (path must end in .png).
void write_png(const RgbImage& image, const std::filesystem::path& path);

}  // namespace ferret
