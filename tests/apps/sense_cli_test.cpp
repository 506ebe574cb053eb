// End-to-end tests of `ferret sense`.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ferret/core/error.hpp"
#include "ferret/perception/image.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "support/cli_runner.hpp"

namespace ferret::test {
namespace {
using ::testing::HasSubstr;

// The M100 1.5 m in front of the small world's cellar marker (on its -x wall, at
// x = -0.6 m, y = -1 m), facing it: its marker camera is pitched 30 deg down.
const std::string kUavPose = "-2.1,-1.0,0.8,0,0,0";

TEST(SenseCli, CameraFrameIsAnRgbPngOfTheRolesSizeShowingTheMarker) {
  TempDir dir;
  const auto r = run_cli(
      "sense --world examples/worlds/small.yaml --robot m100 --sensor camera "
      "--pose " +
      kUavPose + " --seed 4 -o " + (dir / "c.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("DICT_4X4_50 7 (100 % visible"));
  const RgbImage img = read_rgb_image(dir / "c.png");
  const RobotDescription m100 = load_robot("m100");  // the camera refers into it
  const CameraSensor& cam = m100.marker_camera();
  EXPECT_EQ(img.width_px, cam.image_width_px);
  EXPECT_EQ(img.height_px, cam.image_height_px);
  // An 8-bit frame, read as 16 bits, is refused: the PNG's depth is 8.
  EXPECT_THROW((void)read_depth_png(dir / "c.png"), InputError);
  // Same seed, same bytes.
  ASSERT_EQ(run_cli("sense --world examples/worlds/small.yaml --robot m100 --pose " + kUavPose +
                    " --seed 4 -o " + (dir / "c2.png"))
                .exit_code,
            0);
  std::ifstream a(dir / "c.png", std::ios::binary), b(dir / "c2.png", std::ios::binary);
  std::stringstream sa, sb;
  sa << a.rdbuf();
  sb << b.rdbuf();
  EXPECT_EQ(sa.str(), sb.str());
}

TEST(SenseCli, DepthFrameIsA16BitPngInMillimetres) {
  TempDir dir;
  // Hovering 2 m over flat open ground: the downward depth camera (0.065 m under the
  // base link) reads about 1.935 m in the middle.
  const auto r = run_cli(
      "sense --world examples/worlds/small.yaml --robot m100 --sensor depth "
      "--pose -1.5,-2.5,2.0,0,0,0 -o " +
      (dir / "d.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const DepthImageMm d = read_depth_png(dir / "d.png");
  const RobotDescription m100 = load_robot("m100");  // the camera refers into it
  const CameraSensor& cam = m100.depth_camera();
  ASSERT_EQ(d.width_px, cam.image_width_px);
  ASSERT_EQ(d.height_px, cam.image_height_px);
  const int centre = d.at(d.width_px / 2, d.height_px / 2);
  EXPECT_NEAR(centre, 1935, 200) << "sigma_z = 0.01 z^2 = 37 mm";
}

TEST(SenseCli, IrRangesAreJsonOfEveryBeam) {
  TempDir dir;
  // The miniUGV facing +x towards the cellar's -x wall (outer face at x = -0.6 m) from
  // x = -1.2 m, 0.4 m beside its opening (at y = -1 m, 15 cm wide): every beam meets
  // the wall (beams nearer the opening would pass through it).
  const auto r = run_cli(
      "sense --world examples/worlds/small.yaml --robot miniugv --sensor ir "
      "--pose -1.2,-0.6,0,0,0,0 -o " +
      (dir / "ir.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(dir / "ir.json");
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j["beams"].size(), load_robot("miniugv").ir_array().beams.size());
  int hits = 0;
  for (const auto& b : j["beams"])
    if (b["hit"].get<bool>()) {
      ++hits;
      const double x0 = b["origin_m"][0].get<double>(), dx = b["direction"][0].get<double>();
      EXPECT_NEAR(x0, -1.2 + 0.065, 1e-9);  // the URDF's sensor pose, not the base's
      EXPECT_NEAR(b["range_m"].get<double>(), (-0.6 - x0) / dx, 0.05);  // 1 cm noise
    }
  EXPECT_GE(hits, 7);  // 2 % dropouts
}

TEST(SenseCli, BadInputsExitTwoNamingTheOptionWithoutOutput) {
  TempDir dir;
  const std::string base = "sense --world examples/worlds/small.yaml --robot m100 ";
  const struct {
    std::string args, named;
  } cases[] = {
      {"--pose nan,0,1,0,0,0 -o " + (dir / "a.png"), "--pose"},
      {"--pose 0,0,1,0,0 -o " + (dir / "a.png"), "--pose"},
      {"--pose 0,0,inf,0,0,0 -o " + (dir / "a.png"), "--pose"},
      {"--pose 0,0,1,0,0,0,0 -o " + (dir / "a.png"), "--pose"},
      {"--sensor lidar --pose 0,0,1,0,0,0 -o " + (dir / "a.png"), "--sensor"},
      {"--sensor depth --pose 0,0,1,0,0,0 -o " + (dir / "a.json"), "--out"},
      {"--sensor depth --camera-role marker_camera --pose 0,0,1,0,0,0 -o " + (dir / "a.png"),
       "--camera-role"},
      {"--camera-role front --pose 0,0,1,0,0,0 -o " + (dir / "a.png"), "--camera-role"},
      {"--sensor ir --pose 0,0,1,0,0,0 -o " + (dir / "a.json"), "m100.urdf: role[ir]"},
      {"--pose 0,0,1,0,0,0 --seed -1 -o " + (dir / "a.png"), "--seed"},
  };
  for (const auto& c : cases) {
    const auto r = run_cli(base + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.named)) << c.args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  // A world that is not a YAML, and a broken one, named as such.
  std::ofstream(dir / "w.yaml")
      << "name: w\nresolution_m: 0.05\nbounds_m: {min: [0, 0, 0], max: [1, 1, nan]}\n";
  const auto broken = run_cli("sense --world " + (dir / "w.yaml") +
                              " --robot m100 --pose 0,0,1,0,0,0 -o " + (dir / "a.png"));
  EXPECT_EQ(broken.exit_code, 2);
  EXPECT_THAT(broken.err, HasSubstr("w.yaml"));
  EXPECT_THAT(broken.err, HasSubstr("bounds_m"));
  EXPECT_EQ(
      run_cli("sense --world x.bt --robot m100 --pose 0,0,1,0,0,0 -o " + (dir / "a.png")).exit_code,
      2);
  EXPECT_EQ(dir.count(), 1u);  // only w.yaml: no frame was written
}

}  // namespace
}  // namespace ferret::test
