#include "ferret/mapping/map_render.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "ferret/core/error.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "support/cli_runner.hpp"

namespace ferret {
namespace {
using test::TempDir;

bool same(Rgb a, Rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

// 3 x 2 cells at 1 m, origin (10, 20): bottom row occupied, free, unknown; top row free.
OccupancyMap2D tiny_map() {
  OccupancyMap2D m = OccupancyMap2D::filled(GridGeometry{10.0, 20.0, 1.0, 3, 2}, CellState::kFree);
  m.at({0, 0}) = CellState::kOccupied;
  m.at({2, 0}) = CellState::kUnknown;
  return m;
}

TEST(MapCanvas, CellColoursAndRowOrder) {
  RenderOptions o;
  o.pixels_per_cell = 10;
  o.scale_bar = false;
  o.frame = false;
  const MapCanvas canvas(tiny_map(), o);
  const RgbImage img = canvas.image();
  ASSERT_EQ(img.width_px, 30);
  ASSERT_EQ(img.height_px, 20);
  // Map row j = 0 is the bottom of the picture (rows 10..19).
  EXPECT_TRUE(same(pixel(img, 5, 15), o.occupied));
  EXPECT_TRUE(same(pixel(img, 15, 15), o.free));
  EXPECT_TRUE(same(pixel(img, 25, 15), o.unknown));
  EXPECT_TRUE(same(pixel(img, 5, 5), o.free));
  // World (10, 22) is the top-left corner; (13, 20) the bottom-right.
  EXPECT_TRUE(canvas.to_pixel({10.0, 22.0}).isApprox(Eigen::Vector2d(0, 0)));
  EXPECT_TRUE(canvas.to_pixel({13.0, 20.0}).isApprox(Eigen::Vector2d(30, 20)));
}

TEST(MapCanvas, AutomaticScaleReachesMinimumSize) {
  const MapCanvas canvas(tiny_map());  // 3 cells wide, at least 800 px -> 16 px a cell (the cap)
  EXPECT_EQ(canvas.pixels_per_cell(), 16);
  const auto big = OccupancyMap2D::filled(GridGeometry{0, 0, 0.05, 300, 100}, CellState::kFree);
  EXPECT_EQ(MapCanvas(big).pixels_per_cell(), 3);  // ceil(800 / 300)
}

TEST(MapCanvas, OverlaysLandOnTheirCells) {
  RenderOptions o;
  o.pixels_per_cell = 10;
  o.scale_bar = false;
  o.frame = false;
  MapCanvas canvas(tiny_map(), o);
  // A finer grid (0.5 m) drawn over the map: its cell (2, 3) is world [11, 11.5] x [21.5, 22].
  const GridGeometry fine{10.0, 20.0, 0.5, 6, 4};
  canvas.draw_cells(fine, {Cell{2, 3}}, Rgb{0, 0, 255});
  // Half-transparent red over a free (white) cell gives (255, 128, 128).
  canvas.draw_cells(tiny_map().geometry, {Cell{1, 0}}, Rgb{255, 0, 0}, 0.5);
  canvas.draw_field(fine, std::vector<double>(24, -1.0), Rgb{}, Rgb{});  // all skipped
  const RgbImage img = canvas.image();
  EXPECT_TRUE(same(pixel(img, 12, 2), Rgb{0, 0, 255}));
  EXPECT_TRUE(same(pixel(img, 17, 2), Rgb{255, 255, 255}));
  const Rgb blended = pixel(img, 15, 15);
  EXPECT_EQ(blended.r, 255);
  EXPECT_NEAR(blended.g, 128, 1);
  EXPECT_NEAR(blended.b, 128, 1);
  EXPECT_THROW(canvas.draw_field(fine, {0.5}, Rgb{}, Rgb{}), InputError);
}

TEST(MapCanvas, PngRoundTripAndScaleBar) {
  TempDir dir;
  RenderOptions o;
  o.pixels_per_cell = 100;
  o.frame = false;
  MapCanvas canvas(tiny_map(), o);
  canvas.draw_path({{10.5, 20.5}, {12.5, 21.5}}, Rgb{0, 200, 0});
  canvas.save_png(dir / "m.png");
  const RgbImage back = read_rgb_image(dir / "m.png");
  const RgbImage img = canvas.image();
  ASSERT_EQ(back.width_px, 300);
  ASSERT_EQ(back.height_px, 200);
  EXPECT_EQ(back.data, img.data);
  // The scale bar is black on white in the lower-left corner, over the occupied cell.
  bool white_seen = false;
  for (int c = 0; c < 60; ++c)
    white_seen = white_seen || same(pixel(back, c, 180), Rgb{255, 255, 255});
  EXPECT_TRUE(white_seen);
  EXPECT_THROW(canvas.save_png(dir / "m.jpg"), InputError);
  EXPECT_EQ(dir.count(), 1u);
}

TEST(MapCanvas, WorldAnnotationsMarkObjectsAndDropZone) {
  const WorldSpec world = load_world(FERRET_SOURCE_DIR "/examples/worlds/small.yaml");
  SliceOptions at_floor;
  at_floor.z_m = 0.03;
  RenderOptions o;
  o.pixels_per_cell = 4;
  o.scale_bar = false;
  MapCanvas canvas(slice_octree(*build_world_octree(world), at_floor), o);
  draw_world_annotations(canvas, world);
  const RgbImage img = canvas.image();
  auto at_m = [&](double x, double y) {
    const Eigen::Vector2d p = canvas.to_pixel({x, y});
    return ferret::pixel(img, static_cast<int>(std::lround(p.x())),
                         static_cast<int>(std::lround(p.y())));
  };
  EXPECT_TRUE(same(at_m(1.0, -0.7), Rgb{220, 20, 20}));     // the canister
  EXPECT_TRUE(same(at_m(-2.0, -2.5), Rgb{255, 140, 0}));    // bottom of the drop zone's circle
  EXPECT_TRUE(same(at_m(-0.601, -1.0), Rgb{30, 80, 230}));  // the cellar's marker
  EXPECT_TRUE(same(at_m(-0.3, -1.0), Rgb{0, 160, 0}));      // the entry heading, into the cellar

  // The legend lists what the picture shows: the whole world has the drop zone (orange),
  // a window on the cellar does not.
  const auto orange_in_legend = [](const MapCanvas& c) {
    const RgbImage im = c.image();
    const PixelRect l = c.legend_area();
    int n = 0;
    for (int r = l.y; r < l.y + l.height; ++r)
      for (int col = l.x; col < l.x + l.width; ++col)
        n += same(ferret::pixel(im, col, r), Rgb{255, 140, 0});
    return n;
  };
  EXPECT_GT(orange_in_legend(canvas), 5);
  at_floor.window_m = hidden_space_window(world, "cellar", 0.5, "--space");
  MapCanvas cellar(slice_octree(*build_world_octree(world), at_floor), o);
  draw_world_annotations(cellar, world);
  EXPECT_EQ(orange_in_legend(cellar), 0);
  EXPECT_GT(cellar.legend_area().height, 0);  // entry, marker, object
}

bool dark(Rgb c) { return c.r < 128 && c.g < 128 && c.b < 128; }
bool white(Rgb c) { return same(c, Rgb{255, 255, 255}); }

// 40 x 20 cells at 0.25 m from (-2, 1): 10 x 5 m, 10 px a cell -> a 400 x 200 px map.
OccupancyMap2D field_map() {
  return OccupancyMap2D::filled(GridGeometry{-2.0, 1.0, 0.25, 40, 20}, CellState::kFree);
}

TEST(MapCanvas, FrameHasTitleMetreAxesAndLegend) {
  RenderOptions o;
  o.pixels_per_cell = 10;
  o.scale_bar = false;
  MapCanvas canvas(field_map(), o);
  const Rgb swatch{200, 0, 160};
  canvas.set_title("field, slice z = 0.03 m");
  canvas.add_legend("plan path", swatch, LegendMark::kSwatch);
  const RgbImage img = canvas.image();
  const PixelRect m = canvas.map_area();
  ASSERT_EQ(m.width, 400);
  ASSERT_EQ(m.height, 200);
  ASSERT_GT(m.x, 0);
  ASSERT_GT(m.y, 0);
  EXPECT_GT(img.width_px, m.x + m.width);  // the legend's panel
  EXPECT_GT(img.height_px, m.y + m.height);
  // World (-2, 6) is the map's top-left corner; (8, 1) its bottom-right.
  EXPECT_TRUE(canvas.to_pixel({-2.0, 6.0}).isApprox(Eigen::Vector2d(m.x, m.y)));
  EXPECT_TRUE(canvas.to_pixel({8.0, 1.0}).isApprox(Eigen::Vector2d(m.x + 400, m.y + 200)));
  EXPECT_TRUE(white(pixel(img, m.x + 5, m.y + 5)));  // the map itself is unchanged
  // The title: ink above the map.
  int title_ink = 0;
  for (int r = 0; r < m.y; ++r)
    for (int c = 0; c < img.width_px; ++c) title_ink += dark(pixel(img, c, r));
  EXPECT_GT(title_ink, 50);
  // x ticks: 10 m / 8 = 1.25 m rounds up to a 2 m step, so the tick at x = 0 m is
  // 2 m / 0.25 m * 10 px = 80 px right of the map's left edge and x = 1 m has none.
  EXPECT_TRUE(dark(pixel(img, m.x + 80, m.y + m.height + 3)));
  EXPECT_FALSE(dark(pixel(img, m.x + 120, m.y + m.height + 3)));
  // y ticks: y = 2 m is 4 m / 0.25 m * 10 px = 160 px below the map's top edge.
  EXPECT_TRUE(dark(pixel(img, m.x - 3, m.y + 160)));
  // Tick labels: ink in the margins left of and below the map.
  int left_ink = 0, bottom_ink = 0;
  for (int r = m.y; r < m.y + m.height; ++r)
    for (int c = 0; c < m.x - 8; ++c) left_ink += dark(pixel(img, c, r));
  for (int r = m.y + m.height + 8; r < img.height_px; ++r)
    for (int c = m.x; c < m.x + m.width; ++c) bottom_ink += dark(pixel(img, c, r));
  EXPECT_GT(left_ink, 30);
  EXPECT_GT(bottom_ink, 30);
  // The legend's swatch: its exact colour inside the legend box, nowhere on the map.
  const PixelRect l = canvas.legend_area();
  ASSERT_GT(l.width, 0);
  EXPECT_GE(l.x, m.x + m.width);
  int in_box = 0;
  for (int r = l.y; r < l.y + l.height; ++r)
    for (int c = l.x; c < l.x + l.width; ++c) in_box += same(pixel(img, c, r), swatch);
  EXPECT_GT(in_box, 50);
  EXPECT_EQ(canvas.colour_bar_area().width, 0);  // none set

  o.frame = false;  // the map alone, pixel for pixel
  const MapCanvas bare(field_map(), o);
  EXPECT_EQ(bare.image().width_px, 400);
  EXPECT_EQ(bare.map_area().x, 0);
}

TEST(MapCanvas, ColourBarRunsFromLowToHighWithThresholdsMarked) {
  RenderOptions o;
  o.pixels_per_cell = 10;
  MapCanvas canvas(field_map(), o);
  const Rgb low{50, 80, 200}, high{255, 220, 0};
  canvas.set_colour_bar({"P(object) per cell", low, high, {{0.10, "lambda1"}, {0.95, "lambda2"}}});
  // A field of 0.5 everywhere takes the bar's middle colour.
  canvas.draw_field(field_map().geometry, std::vector<double>(800, 0.5), low, high, 1.0);
  const RgbImage img = canvas.image();
  const PixelRect b = canvas.colour_bar_area();
  ASSERT_GT(b.height, 100);
  ASSERT_GT(b.width, 5);
  const int c = b.x + b.width / 2;
  const auto row_of = [&](double v) {
    return b.y + static_cast<int>(std::lround((1 - v) * (b.height - 1)));
  };
  EXPECT_TRUE(same(pixel(img, c, row_of(0.0)), low));
  EXPECT_TRUE(same(pixel(img, c, row_of(1.0)), high));
  // Bottom to top: red and green never fall, blue never rises (the marks' rows excepted).
  Rgb prev = low;
  int samples = 0;
  for (int r = b.y + b.height - 1; r >= b.y; --r) {
    if (std::abs(r - row_of(0.10)) <= 2 || std::abs(r - row_of(0.95)) <= 2) continue;
    const Rgb p = pixel(img, c, r);
    EXPECT_GE(p.r, prev.r) << r;
    EXPECT_GE(p.g, prev.g) << r;
    EXPECT_LE(p.b, prev.b) << r;
    prev = p;
    ++samples;
  }
  EXPECT_GT(samples, 100);
  // The thresholds are dark lines across the bar.
  EXPECT_TRUE(dark(pixel(img, c, row_of(0.10))));
  EXPECT_TRUE(dark(pixel(img, c, row_of(0.95))));
  // The field's p = 0.5 is the bar's colour half way up.
  const Rgb mid = pixel(img, canvas.map_area().x + 200, canvas.map_area().y + 100);
  const Rgb bar_mid = pixel(img, c, b.y + (b.height - 1) / 2);
  EXPECT_NEAR(mid.r, bar_mid.r, 2);
  EXPECT_NEAR(mid.g, bar_mid.g, 2);
  EXPECT_NEAR(mid.b, bar_mid.b, 2);
  EXPECT_THROW(canvas.set_colour_bar({"p", low, high, {{1.5, "x"}}}), InputError);
}

TEST(MapServerImage, PngThroughOpenCv) {
  TempDir dir;
  RgbImage img(2, 1);
  img.data = {0, 0, 0, 252, 255, 255};  // black; grey average 254 -> free
  write_png(img, dir / "m.png");
  std::ofstream(dir / "m.yaml") << "image: m.png\nresolution: 0.1\norigin: [0, 0, 0]\n";
  const OccupancyMap2D map = load_map_server(dir / "m.yaml");
  ASSERT_EQ(map.geometry.width, 2);
  EXPECT_EQ(map.at({0, 0}), CellState::kOccupied);
  EXPECT_EQ(map.at({1, 0}), CellState::kFree);
}

}  // namespace
}  // namespace ferret
