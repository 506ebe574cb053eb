// End-to-end tests of `ferret render`.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "ferret/mapping/map_render.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "support/cli_runner.hpp"

namespace ferret::test {
namespace {
using ::testing::HasSubstr;
using ::testing::Not;

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

TEST(RenderCli, MapServerMapToPng) {
  TempDir dir;
  // 2 x 1 map: occupied, free. 50 px a cell, no scale bar: pixel colours are exact.
  write(dir / "m.pgm", std::string("P5\n2 1\n255\n") + std::string{'\x00', '\xfe'});
  write(dir / "m.yaml", "image: m.pgm\nresolution: 0.5\norigin: [0, 0, 0]\n");
  const auto r = run_cli("render " + (dir / "m.yaml") + " -o " + (dir / "out.png") +
                         " --scale 50 --no-scale-bar --no-frame");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RgbImage img = read_rgb_image(dir / "out.png");
  ASSERT_EQ(img.width_px, 100);
  ASSERT_EQ(img.height_px, 50);
  EXPECT_EQ(pixel(img, 25, 25).r, 0);
  EXPECT_EQ(pixel(img, 75, 25).r, 255);
}

TEST(RenderCli, WorldYamlAndOctreeSlices) {
  TempDir dir;
  const auto a = run_cli("render examples/worlds/small.yaml -o " + (dir / "w.png"));
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_THAT(a.out, HasSubstr("240 x 240 cells at 4 px/cell"));
  ASSERT_EQ(run_cli("world build examples/worlds/small.yaml -o " + (dir / "w.bt")).exit_code, 0);
  // Above the 7.5 cm opening the cellar's wall is closed: its opening cell is black.
  const auto b = run_cli("render " + (dir / "w.bt") +
                         " --z 0.1 --scale 1 --no-scale-bar --no-frame -o " + (dir / "b.png"));
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const RgbImage img = read_rgb_image(dir / "b.png");
  ASSERT_EQ(img.width_px, 240);
  // World (-0.55, -1.0) is column (x + 3) / 0.025 = 98, row (3 - y) / 0.025 = 160.
  EXPECT_EQ(pixel(img, 98, 160).r, 0);
  EXPECT_EQ(pixel(img, 140, 160).r, 255);  // (0.5, -1.0): the cellar interior
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

// 40 x 20 free cells at 0.1 m from (1, 2): 4 x 2 m, drawn at 10 px a cell.
void write_free_map(const TempDir& dir) {
  write(dir / "f.pgm", "P5\n40 20\n255\n" + std::string(800, '\xfe'));
  write(dir / "f.yaml", "image: f.pgm\nresolution: 0.1\norigin: [1, 2, 0]\n");
}

TEST(RenderCli, PlanDrawnWhereItsPosesProject) {
  TempDir dir;
  write_free_map(dir);
  // A CSV plan (t,x,y,z,yaw): east along y = 3 from x = 1.5 to 4.5.
  write(dir / "p.csv", "t,x,y,z,yaw\n0,1.5,3,0,0\n1,3,3,0,0\n2,4.5,3,0,0\n");
  const auto r = run_cli("render " + (dir / "f.yaml") + " --plan " + (dir / "p.csv") +
                         " --scale 10 --no-frame --no-scale-bar -o " + (dir / "bare.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RgbImage img = read_rgb_image(dir / "bare.png");
  ASSERT_EQ(img.width_px, 400);
  ASSERT_EQ(img.height_px, 200);
  // World (x, y) is column (x - 1) / 0.1 * 10, row (2 + 2 - y) / 0.1 * 10, by hand.
  const auto is = [&](int c, int row, Rgb want) {
    const Rgb p = pixel(img, c, row);
    return p.r == want.r && p.g == want.g && p.b == want.b;
  };
  // The overlay's colours (PlanOverlayStyle, docs/maps_and_worlds.md).
  const struct { Rgb path{200, 0, 160}, start{0, 190, 0}, goal{120, 40, 230}; } style;
  EXPECT_TRUE(is(225, 100, style.path));         // (3.75, 3): mid second segment
  EXPECT_TRUE(is(50, 100, style.start));         // (1.5, 3)
  EXPECT_TRUE(is(350, 100, style.goal));         // (4.5, 3)
  EXPECT_TRUE(is(225, 60, Rgb{255, 255, 255}));  // (3.75, 3.4): off the path, free

  // Framed: the same picture with a title above, axes and the legend to the right.
  const auto f = run_cli("render " + (dir / "f.yaml") + " --plan " + (dir / "p.csv") +
                         " --scale 10 -o " + (dir / "framed.png"));
  ASSERT_EQ(f.exit_code, 0) << f.err;
  EXPECT_THAT(f.out, HasSubstr("plan: 3 states, 3.0 m"));
  const RgbImage framed = read_rgb_image(dir / "framed.png");
  ASSERT_GT(framed.width_px, 400 + 150);
  int title_ink = 0, legend_path = 0;
  for (int row = 0; row < 20; ++row)
    for (int c = 0; c < framed.width_px; ++c) title_ink += pixel(framed, c, row).r < 100;
  // Right of the path: it ends 367 px (goal plus its heading tick) into the map, whose
  // left margin is below 80 px.
  for (int row = 0; row < framed.height_px; ++row)
    for (int c = 367 + 80; c < framed.width_px; ++c) {
      const Rgb p = pixel(framed, c, row);
      legend_path += p.r == style.path.r && p.g == style.path.g && p.b == style.path.b;
    }
  EXPECT_GT(title_ink, 30);
  EXPECT_GT(legend_path, 20);
}

TEST(RenderCli, PlanPartlyOutsideTheMapIsDrawnAndSaid) {
  TempDir dir;
  write_free_map(dir);
  write(dir / "p.csv", "t,x,y,z,yaw\n0,2,3,0,0\n1,4,3,0,0\n2,9,3,0,0\n3,9,9,0,0\n");
  const auto r = run_cli("render " + (dir / "f.yaml") + " --plan " + (dir / "p.csv") + " -o " +
                         (dir / "o.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("2 of 4 states outside the map"));
  EXPECT_TRUE(std::filesystem::is_regular_file(dir / "o.png"));
}

// A plan far out: a waypoint at 4e9 m is bad input (the plan format's +-1e5 m bound),
// named by file and cell, without a PNG; one at the bound is drawn (clipped) at once.
TEST(RenderCli, FarPlanIsBadInputOrClippedNeverABlowUp) {
  TempDir dir;
  write_free_map(dir);
  write(dir / "far.csv", "t,x,y,z,yaw\n0,2,3,0,0\n1,4e9,3,0,0\n");
  const auto r = run_cli("render " + (dir / "f.yaml") + " --plan " + (dir / "far.csv") + " -o " +
                         (dir / "o.png"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("far.csv: line 3 column 2 (x): expected a coordinate within"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "o.png"));
  write(dir / "edge.csv", "t,x,y,z,yaw\n0,2,3,0,0\n1,100000,-100000,0,0\n");
  const auto e = run_cli("render " + (dir / "f.yaml") + " --plan " + (dir / "edge.csv") + " -o " +
                         (dir / "o.png"));
  ASSERT_EQ(e.exit_code, 0) << e.err;
  EXPECT_THAT(e.out, HasSubstr("1 of 2 states outside the map"));
}

// A window cuts the picture, not the obstacles the tether wraps on: the same plan gives
// the same tether whether the block it bends round is in the picture or not.
TEST(RenderCli, TetherOfAPlanDoesNotDependOnTheWindow) {
  TempDir dir;
  const std::string world = "examples/scenarios/tether_detour.yaml";
  const auto plan = run_cli("plan ugv --world " + world +
                            " --driven \"1,6.5;10,6.5\" --from 10,4.5,-1.57 --to 10,1.5,-1.57 "
                            "--tether 12.5 --seed 1 -o " +
                            (dir / "p.json"));
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  const auto tether_of = [](const std::string& out) {
    const std::size_t a = out.find("tether "), b = out.find(" taut", a);
    return a == std::string::npos || b == std::string::npos ? std::string() : out.substr(a, b - a);
  };
  const auto whole =
      run_cli("render " + world + " --plan " + (dir / "p.json") + " -o " + (dir / "whole.png"));
  const auto window = run_cli("render " + world + " --plan " + (dir / "p.json") +
                              " --window 5,0,13,8 -o " + (dir / "window.png"));
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  ASSERT_EQ(window.exit_code, 0) << window.err;
  EXPECT_THAT(plan.out, HasSubstr(tether_of(whole.out).substr(7)));  // as the planner said
  EXPECT_FALSE(tether_of(whole.out).empty());
  EXPECT_EQ(tether_of(window.out), tether_of(whole.out));
  EXPECT_THAT(window.out, HasSubstr("states outside the map"));
}

TEST(RenderCli, BadPlanExitsTwoNamingTheFileWithoutPng) {
  TempDir dir;
  write_free_map(dir);
  write(dir / "nan.csv", "t,x,y,z,yaw\n0,1.5,3,0,0\n1,nan,3,0,0\n");
  write(dir / "broken.json", "{\"robot\": \"ugv\", \"states\": [");
  const std::size_t before = dir.count();
  for (const std::string bad : {"nan.csv", "broken.json", "absent.csv"}) {
    const auto r = run_cli("render " + (dir / "f.yaml") + " --plan " + (dir / bad) + " -o " +
                           (dir / "out.png"));
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_THAT(r.err, HasSubstr(bad));
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_EQ(dir.count(), before);  // no out.png
}

// --space and --window cut 3D slices; on a map_server map they would be ignored, so a
// user who thought the picture was cut is told instead.
TEST(RenderCli, SliceOnlyOptionsOnAMapServerMapAreBadInput) {
  TempDir dir;
  write_free_map(dir);
  const std::size_t before = dir.count();
  for (const std::string option : {"--space house_void", "--window 0,0,1,1"}) {
    const auto r =
        run_cli("render " + (dir / "f.yaml") + " " + option + " -o " + (dir / "out.png"));
    EXPECT_EQ(r.exit_code, 2) << option;
    EXPECT_THAT(r.err, HasSubstr(option.substr(0, option.find(' '))));
  }
  EXPECT_EQ(dir.count(), before);
}

TEST(RenderCli, OutFollowsTheCliConvention) {
  TempDir dir;
  write_free_map(dir);
  // --out and the old --output both work; a missing one is bad input naming --out.
  EXPECT_EQ(run_cli("render " + (dir / "f.yaml") + " --out " + (dir / "a.png")).exit_code, 0);
  EXPECT_EQ(run_cli("render " + (dir / "f.yaml") + " --output " + (dir / "b.png")).exit_code, 0);
  const auto missing = run_cli("render " + (dir / "f.yaml"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("--out"));
  const auto help = run_cli("render --help");
  EXPECT_THAT(help.out, HasSubstr("--plan"));
  EXPECT_THAT(help.out, HasSubstr("-o,--out"));
  EXPECT_THAT(help.out, Not(HasSubstr("--output")));  // hidden alias
  EXPECT_THAT(run_cli("render " + (dir / "f.yaml") + " --z nan -o " + (dir / "c.png")).exit_code,
              2);
}

}  // namespace
}  // namespace ferret::test
