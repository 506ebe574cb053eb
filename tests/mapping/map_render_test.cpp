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
  const MapCanvas canvas(tiny_map(), o);
  const RgbImage img = canvas.image();
  ASSERT_EQ(img.width, 30);
  ASSERT_EQ(img.height, 20);
  // Map row j = 0 is the bottom of the picture (rows 10..19).
  EXPECT_TRUE(same(img.at(5, 15), o.occupied));
  EXPECT_TRUE(same(img.at(15, 15), o.free));
  EXPECT_TRUE(same(img.at(25, 15), o.unknown));
  EXPECT_TRUE(same(img.at(5, 5), o.free));
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
  MapCanvas canvas(tiny_map(), o);
  // A finer grid (0.5 m) drawn over the map: its cell (2, 3) is world [11, 11.5] x [21.5, 22].
  const GridGeometry fine{10.0, 20.0, 0.5, 6, 4};
  canvas.draw_cells(fine, {Cell{2, 3}}, Rgb{0, 0, 255});
  // Half-transparent red over a free (white) cell gives (255, 128, 128).
  canvas.draw_cells(tiny_map().geometry, {Cell{1, 0}}, Rgb{255, 0, 0}, 0.5);
  canvas.draw_field(fine, std::vector<double>(24, -1.0), Rgb{}, Rgb{});  // all skipped
  const RgbImage img = canvas.image();
  EXPECT_TRUE(same(img.at(12, 2), Rgb{0, 0, 255}));
  EXPECT_TRUE(same(img.at(17, 2), Rgb{255, 255, 255}));
  const Rgb blended = img.at(15, 15);
  EXPECT_EQ(blended.r, 255);
  EXPECT_NEAR(blended.g, 128, 1);
  EXPECT_NEAR(blended.b, 128, 1);
  EXPECT_THROW(canvas.draw_field(fine, {0.5}, Rgb{}, Rgb{}), InputError);
}

TEST(MapCanvas, PngRoundTripAndScaleBar) {
  TempDir dir;
  RenderOptions o;
  o.pixels_per_cell = 100;
  MapCanvas canvas(tiny_map(), o);
  canvas.draw_path({{10.5, 20.5}, {12.5, 21.5}}, Rgb{0, 200, 0});
  canvas.save_png(dir / "m.png");
  const RgbImage back = read_rgb_image(dir / "m.png");
  const RgbImage img = canvas.image();
  ASSERT_EQ(back.width, 300);
  ASSERT_EQ(back.height, 200);
  EXPECT_EQ(back.data, img.data);
  // The scale bar is black on white in the lower-left corner, over the occupied cell.
  bool white_seen = false;
  for (int c = 0; c < 60; ++c) white_seen = white_seen || same(back.at(c, 180), Rgb{255, 255, 255});
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
  auto pixel = [&](double x, double y) {
    const Eigen::Vector2d p = canvas.to_pixel({x, y});
    return img.at(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y())));
  };
  EXPECT_TRUE(same(pixel(1.0, -0.7), Rgb{220, 20, 20}));     // the canister
  EXPECT_TRUE(same(pixel(-2.0, -2.5), Rgb{255, 140, 0}));    // bottom of the drop zone's circle
  EXPECT_TRUE(same(pixel(-0.601, -1.0), Rgb{30, 80, 230}));  // the cellar's marker
  EXPECT_TRUE(same(pixel(-0.3, -1.0), Rgb{0, 160, 0}));      // the entry heading, into the cellar
}

TEST(MapServerImage, PngThroughOpenCv) {
  TempDir dir;
  RgbImage img{2, 1, {0, 0, 0, 252, 255, 255}};  // black; grey average 254 -> free
  write_png(img, dir / "m.png");
  std::ofstream(dir / "m.yaml") << "image: m.png\nresolution: 0.1\norigin: [0, 0, 0]\n";
  const OccupancyMap2D map = load_map_server(dir / "m.yaml");
  ASSERT_EQ(map.geometry.width, 2);
  EXPECT_EQ(map.at({0, 0}), CellState::kOccupied);
  EXPECT_EQ(map.at({1, 0}), CellState::kFree);
}

}  // namespace
}  // namespace ferret
