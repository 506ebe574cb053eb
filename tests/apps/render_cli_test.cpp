// End-to-end tests of `ferret render`.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "ferret/mapping/map_render.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "support/cli_runner.hpp"

namespace ferret::test {
namespace {
using ::testing::HasSubstr;

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(RenderCli, MapServerMapToPng) {
  TempDir dir;
  // 2 x 1 map: occupied, free. 50 px a cell, no scale bar: pixel colours are exact.
  write(dir / "m.pgm", std::string("P5\n2 1\n255\n") + std::string{'\x00', '\xfe'});
  write(dir / "m.yaml", "image: m.pgm\nresolution: 0.5\norigin: [0, 0, 0]\n");
  const auto r = run_cli("render " + (dir / "m.yaml") + " -o " + (dir / "out.png") +
                         " --scale 50 --no-scale-bar");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RgbImage img = read_rgb_image(dir / "out.png");
  ASSERT_EQ(img.width, 100);
  ASSERT_EQ(img.height, 50);
  EXPECT_EQ(img.at(25, 25).r, 0);
  EXPECT_EQ(img.at(75, 25).r, 255);
}

TEST(RenderCli, WorldYamlAndOctreeSlices) {
  TempDir dir;
  const auto a = run_cli("render examples/worlds/small.yaml -o " + (dir / "w.png"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_THAT(a.out, HasSubstr("240 x 240 cells at 4 px/cell"));
  ASSERT_EQ(run_cli("world build examples/worlds/small.yaml -o " + (dir / "w.bt")).exit_code, 0);
  // Above the 7.5 cm opening the cellar's wall is closed: its opening cell is black.
  const auto b = run_cli("render " + (dir / "w.bt") + " --z 0.1 --scale 1 --no-scale-bar -o " +
                         (dir / "b.png"));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const RgbImage img = read_rgb_image(dir / "b.png");
  ASSERT_EQ(img.width, 240);
  // World (-0.55, -1.0) is column (x + 3) / 0.025 = 98, row (3 - y) / 0.025 = 160.
  EXPECT_EQ(img.at(98, 160).r, 0);
  EXPECT_EQ(img.at(140, 160).r, 255);  // (0.5, -1.0): the cellar interior
}

TEST(RenderCli, BadInputsExitTwoWithoutOutput) {
  TempDir dir;
  write(dir / "cut.pgm", "P5\n4 4\n255\n" + std::string(10, '\xfe'));
  write(dir / "cut.yaml", "image: cut.pgm\nresolution: 0.5\norigin: [0, 0, 0]\n");
  write(dir / "magic.pgm", "P7\n1 1\n255\n\x01");
  write(dir / "magic.yaml", "image: magic.pgm\nresolution: 0.5\norigin: [0, 0, 0]\n");
  write(dir / "missing.yaml", "image: nowhere.pgm\nresolution: 0.5\norigin: [0, 0, 0]\n");
  write(dir / "scale.yaml", "image: cut.pgm\nresolution: 0.5\norigin: [0, 0, 0]\nmode: scale\n");
  write(dir / "noimage.yaml", "resolution: 0.5\norigin: [0, 0, 0]\n");
  const std::pair<std::string, std::string> cases[] = {{"cut.yaml", "cut.pgm: pixels"},
                                                       {"magic.yaml", "magic.pgm: magic"},
                                                       {"missing.yaml", "missing.yaml: image"},
                                                       {"scale.yaml", "scale.yaml: mode"},
                                                       {"noimage.yaml", "noimage.yaml: image"}};
  const std::size_t before = dir.count();
  for (const auto& [input, message] : cases) {
    const auto r = run_cli("render " + (dir / input) + " -o " + (dir / "out.png"));
    EXPECT_EQ(r.exit_code, 2) << input;
    EXPECT_THAT(r.err, HasSubstr(message));
  }
  auto r = run_cli("render examples/worlds/small.yaml -o " + (dir / "out.jpg"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(dir.count(), before);
}

}  // namespace
}  // namespace ferret::test
