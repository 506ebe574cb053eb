// End-to-end tests of `ferret detect marker`.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/image.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "support/cli_runner.hpp"
#include "uav/marker_test_frames.hpp"

namespace ferret::test {
namespace {
using ::testing::HasSubstr;

constexpr double kDeg = M_PI / 180.0;

CameraModel m100_marker_camera() {
  const auto path = std::string(FERRET_SOURCE_DIR) + "/urdf/models/m100.urdf";
  return camera_model(load_robot(path).marker_camera(), path);
}

void write_bytes(const std::filesystem::path& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

MarkerScene apriltag_scene() {
  MarkerScene s;
  s.dictionary = dictionary(MarkerFamily::kAprilTag, "tag36h11");
  s.id = 17;
  s.size_m = 0.2;
  s.X_CM = marker_ahead(1.5, 25 * kDeg, 10 * kDeg, {0.2, -0.1});
  return s;
}

TEST(DetectMarkerCli, JsonGivesIdCornersAndPoseOfTheMarker) {
  TempDir dir;
  const CameraModel camera = m100_marker_camera();
  const MarkerScene s = apriltag_scene();
  write_bytes(dir / "frame.png", encode_png(render_marker_frame(camera, s)));
  const auto r = run_cli("detect marker " + (dir / "frame.png") +
                         " --robot m100 --family apriltag --marker-size-m 0.2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.size(), 1u);
  ASSERT_EQ(j.at("detections").size(), 1u);
  const auto& d = j["detections"][0];
  EXPECT_EQ(d.size(), 5u);  // id, corners_px, t_CM_m, R_CM, reprojection_error_px
  EXPECT_EQ(d.at("id").get<int>(), 17);
  const auto truth = true_corners_px(camera, s);
  ASSERT_EQ(d.at("corners_px").size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(d["corners_px"][k][0].get<double>(), truth[k].x(), 1.0);
    EXPECT_NEAR(d["corners_px"][k][1].get<double>(), truth[k].y(), 1.0);
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(d.at("t_CM_m")[i].get<double>(), s.X_CM.translation()[i], 0.01);
    ASSERT_EQ(d.at("R_CM")[i].size(), 3u);
    for (int c = 0; c < 3; ++c)  // row-major: R_CM[row][column]
      EXPECT_NEAR(d["R_CM"][i][c].get<double>(), s.X_CM.linear()(i, c), 0.03);
  }
  EXPECT_LT(d.at("reprojection_error_px").get<double>(), 1.0);
}

TEST(DetectMarkerCli, NoMarkerGivesAnEmptyListAndOverlayIsWritten) {
  TempDir dir;
  const CameraModel camera = m100_marker_camera();
  MarkerScene s = apriltag_scene();
  s.draw_marker = false;
  write_bytes(dir / "empty.png", encode_png(render_marker_frame(camera, s)));
  const auto r =
      run_cli("detect marker " + (dir / "empty.png") +
              " --robot m100 --family aruco --marker-size-m 0.2 --json -o " + (dir / "o.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out), nlohmann::json::parse(R"({"detections": []})"));
  const RgbImage overlay = read_rgb_image(dir / "o.png");
  EXPECT_EQ(overlay.width_px, camera.width_px);
  EXPECT_EQ(overlay.height_px, camera.height_px);
}

TEST(DetectMarkerCli, OverlayOutlinesTheMarkerInGreen) {
  TempDir dir;
  const CameraModel camera = m100_marker_camera();
  MarkerScene s;
  s.dictionary = dictionary(MarkerFamily::kAruco, "DICT_4X4_50");
  s.id = 11;
  s.X_CM = marker_ahead(1.0, 0.0);
  write_bytes(dir / "f.png", encode_png(render_marker_frame(camera, s)));
  const auto r = run_cli("detect marker " + (dir / "f.png") +
                         " --robot m100 --family aruco --marker-size-m 0.2 -o " + (dir / "o.png"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("id 11"));
  const RgbImage overlay = read_rgb_image(dir / "o.png");
  // The middle of the top edge lies on the outline (grey input: any green is drawn).
  const auto c = true_corners_px(camera, s);
  const Eigen::Vector2d mid = (c[0] + c[1]) / 2;
  const int x = static_cast<int>(std::lround(mid.x())), y = static_cast<int>(std::lround(mid.y()));
  EXPECT_GT(overlay.at(x, y, 1), 200);
  EXPECT_LT(overlay.at(x, y, 0), 60);
}

TEST(DetectMarkerCli, BadInputsExitTwoWithoutOutput) {
  TempDir dir;
  const CameraModel camera = m100_marker_camera();
  write_bytes(dir / "frame.png", encode_png(render_marker_frame(camera, apriltag_scene())));
  std::ofstream(dir / "text.png") << "this is not an image\n";
  write_bytes(dir / "small.png", encode_png(GrayImage(64, 48, 128)));
  const std::string frame = (dir / "frame.png"), out = (dir / "o.png");
  struct Case {
    std::string args, names;
  };
  for (const Case& c : {
           Case{(dir / "text.png") + " --robot m100 --family apriltag --marker-size-m 0.2",
                "text.png"},
           Case{(dir / "missing.png") + " --robot m100 --family apriltag --marker-size-m 0.2",
                "missing.png"},
           Case{(dir / "small.png") + " --robot m100 --family apriltag --marker-size-m 0.2",
                "small.png: size"},
           Case{frame +
                    " --robot m100 --family apriltag --dictionary DICT_4X4_50 --marker-size-m 0.2",
                "--dictionary"},
           Case{frame + " --robot m100 --family aruco --dictionary DICT_9X9_1 --marker-size-m 0.2",
                "--dictionary"},
           Case{frame + " --robot m100 --family qr --marker-size-m 0.2", "--family"},
           Case{frame + " --robot m100 --family apriltag --marker-size-m 0", "--marker-size-m"},
           Case{frame + " --robot m100 --family apriltag --marker-size-m -0.2", "--marker-size-m"},
           Case{frame + " --robot m100 --family apriltag --marker-size-m nan", "--marker-size-m"},
           Case{frame + " --robot m100 --family apriltag --marker-size-m inf", "--marker-size-m"},
           Case{frame + " --robot m100 --family apriltag --marker-size-m 1e9", "--marker-size-m"},
           Case{frame + " --family apriltag --marker-size-m 0.2", "--camera"},
           Case{frame + " --robot nosuchrobot --family apriltag --marker-size-m 0.2", "--robot"},
       }) {
    const auto r = run_cli("detect marker " + c.args + " -o " + out);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.names)) << c.args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.args;
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                            std::filesystem::directory_iterator{}),
              3)
        << "a staging file was left behind: " << c.args;
  }
}

TEST(DetectMarkerCli, DetectGroupListsMarker) {
  const auto r = run_cli("detect --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("marker"));
}

}  // namespace
}  // namespace ferret::test
