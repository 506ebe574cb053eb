// End-to-end tests of `ferret detect object`: frames drawn here (an orange patch of
// known pixel size on a textured background), the miniUGV's object camera (640 x 480,
// 90 deg: fx = 320 px, cx = 319.5, cy = 239.5).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "ferret/perception/camera_info.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/image.hpp"
#include "support/cli_runner.hpp"
#include "ugv/object_frames.hpp"

namespace ferret::test {
namespace {
using ::testing::HasSubstr;

void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

void write(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The object 16 x 10 px centred on the optical axis: its near face at z = 0.05 * 320 /
// 10 = 1.6 m, its centre (the canister's 8 cm footprint) 2 * 0.08 / pi further.
constexpr double kRange = 1.6 + 2 * 0.08 / 3.141592653589793;
std::string object_frame(const TempDir& dir, const std::string& name = "frame.png") {
  RgbImage img = textured_background(640, 480, 5);
  fill_rect(img, 312, 235, 16, 10, kOrange);
  add_noise(img, 3.0, 6);
  write_bytes(dir / name, encode_png(img));
  return dir / name;
}

TEST(DetectObjectCli, JsonGivesBearingDistanceAndConfidence) {
  TempDir dir;
  const auto r = run_cli("detect object " + object_frame(dir) + " --robot miniugv --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.at("detections").size(), 1u);
  const auto& d = j["detections"][0];
  EXPECT_NEAR(d.at("distance_m").get<double>(), kRange, 1e-9);
  EXPECT_NEAR(d.at("bearing_rad").get<double>(), 0.0, 1e-12);
  EXPECT_NEAR(d.at("confidence").get<double>(), 1.0 / kRange, 1e-9);  // eta / d, eta = 1 m
  EXPECT_NEAR(d.at("centroid_px")[0].get<double>(), 319.5, 1e-9);
  EXPECT_NEAR(d.at("centroid_px")[1].get<double>(), 239.5, 1e-9);
  EXPECT_EQ(d.at("size_px").get<double>(), 10.0);
}

TEST(DetectObjectCli, MissionEtaAndSummaryLine) {
  TempDir dir;
  write(dir / "m.yaml", "object_search: {eta_m: 0.8, conf_floor: 0.52}\n");
  const std::string frame = object_frame(dir);
  const auto j =
      run_cli("detect object " + frame + " --robot miniugv --json --mission " + (dir / "m.yaml"));
  ASSERT_EQ(j.exit_code, 0) << j.err;
  // 0.8 / 1.65 = 0.48, below the floor 0.52.
  EXPECT_NEAR(nlohmann::json::parse(j.out)["detections"][0]["confidence"].get<double>(), 0.52,
              1e-9);
  const auto s = run_cli("detect object " + frame + " --robot miniugv");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  EXPECT_THAT(s.out, HasSubstr("1 object "));
  EXPECT_THAT(s.out, HasSubstr("distance 1.651 m"));
}

TEST(DetectObjectCli, ACameraInfoFileGivesTheCamera) {
  // A calibration with fy = 400 px (fx 320): the 10 px height now reads z = 0.05 * 400 /
  // 10 = 2 m, and the centre 2 * 0.08 / pi further.
  TempDir dir;
  CameraModel cam = CameraModel::from_fov("calibrated", 640, 480, 1.5707963267948966);
  cam.fy_px = 400.0;
  cam.projection(1, 1) = 400.0;
  write(dir / "cam.yaml", camera_info_yaml(cam));
  const auto r =
      run_cli("detect object " + object_frame(dir) + " --camera " + (dir / "cam.yaml") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.at("detections").size(), 1u);
  EXPECT_NEAR(j["detections"][0]["distance_m"].get<double>(), 2.0 + 2 * 0.08 / 3.141592653589793,
              1e-9);
}

TEST(DetectObjectCli, AnotherObjectSize) {
  // A 16 x 16 x 10 cm object over the same 10 px: z = 0.10 * 320 / 10 = 3.2 m, its
  // centre 2 * 0.16 / pi further.
  TempDir dir;
  const auto r = run_cli("detect object " + object_frame(dir) +
                         " --robot miniugv --json --object-width-m 0.16 --object-height-m 0.1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(nlohmann::json::parse(r.out)["detections"][0]["distance_m"].get<double>(),
              3.2 + 2 * 0.16 / 3.141592653589793, 1e-9);
}

TEST(DetectObjectCli, AFrameWithoutTheObjectGivesAnEmptyList) {
  TempDir dir;
  RgbImage img = textured_background(640, 480, 8);
  fill_rect(img, 100, 100, 30, 20, {230, 20, 10});  // red: not the object
  write_bytes(dir / "empty.png", encode_png(img));
  const auto r = run_cli("detect object " + (dir / "empty.png") + " --robot miniugv --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out), nlohmann::json::parse(R"({"detections": []})"));
}

TEST(DetectObjectCli, OverlayShowsTheBox) {
  TempDir dir;
  const auto r =
      run_cli("detect object " + object_frame(dir) + " --robot miniugv -o " + (dir / "o.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const RgbImage over = read_rgb_image(dir / "o.png");
  ASSERT_EQ(over.width_px, 640);
  ASSERT_EQ(over.height_px, 480);
  // The box is drawn one pixel outside the blob (columns 312..327): column 311 green.
  EXPECT_EQ(over.at(311, 240, 0), 0);
  EXPECT_EQ(over.at(311, 240, 1), 255);
  EXPECT_EQ(over.at(311, 240, 2), 0);
}

TEST(DetectObjectCli, BadInputsExitTwoWithoutOutput) {
  TempDir dir;
  write(dir / "text.png", "not a PNG at all\n");
  write_bytes(dir / "small.png", encode_png(RgbImage(320, 240)));
  const std::string frame = object_frame(dir);
  write(dir / "cam.yaml", camera_info_yaml(CameraModel::from_fov("c", 640, 480, 1.5707963)));
  const std::string bad =
      "image_width: 640\nimage_height: 480\ncamera_name: c\ncamera_matrix:\n  rows: 3\n  "
      "cols: 3\n  data: [nan, 0, 319.5, 0, 320, 239.5, 0, 0, 1]\ndistortion_model: "
      "plumb_bob\ndistortion_coefficients:\n  rows: 1\n  cols: 5\n  data: [0, 0, 0, 0, 0]\n";
  write(dir / "bad_cam.yaml", bad);
  const std::string overlay = dir / "o.png";
  struct Case {
    std::string args, source, field;
  };
  const std::vector<Case> cases = {
      {"detect object " + (dir / "text.png") + " --robot miniugv -o " + overlay, dir / "text.png",
       ""},
      {"detect object " + (dir / "small.png") + " --robot miniugv -o " + overlay, dir / "small.png",
       "size"},
      {"detect object " + (dir / "missing.png") + " --robot miniugv -o " + overlay,
       dir / "missing.png", ""},
      {"detect object " + frame + " -o " + overlay, "--camera", ""},
      {"detect object " + frame + " --robot miniugv --camera " + (dir / "cam.yaml") + " -o " +
           overlay,
       "--camera", ""},
      {"detect object " + frame + " --camera " + (dir / "bad_cam.yaml") + " -o " + overlay,
       dir / "bad_cam.yaml", "camera_matrix.data[0]"},
      {"detect object " + frame + " --robot miniugv --object-height-m 0 -o " + overlay,
       "--object-height-m", ""},
      {"detect object " + frame + " --robot miniugv --object-width-m nan -o " + overlay,
       "--object-width-m", ""},
      {"detect object " + frame + " --robot miniugv -o " + (dir / "o.jpg"), "--out", ""},
      {"detect object " + frame + " --robot m100 -o " + overlay, "object_camera", ""},
  };
  for (const auto& c : cases) {
    const auto r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.source)) << c.args;
    if (!c.field.empty()) {
      EXPECT_THAT(r.err, HasSubstr(": " + c.field + ":")) << r.err;
    }
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(overlay)) << c.args;
    EXPECT_FALSE(std::filesystem::exists(dir / "o.jpg")) << c.args;
  }
  // Nothing but the inputs in the directory: no staging left behind.
  EXPECT_EQ(dir.count(), 5u);
}

}  // namespace
}  // namespace ferret::test
