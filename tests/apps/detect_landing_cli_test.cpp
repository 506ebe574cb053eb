// `ferret detect landing`: every path, on depth frames of the M100's depth camera
// computed here (flat ground under a known pose: the answer is known).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "ferret/core/pose.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/image.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "support/cli_runner.hpp"

namespace ferret {
namespace {

using test::run_cli;
using test::TempDir;

const std::string kUrdf = std::string(FERRET_SOURCE_DIR) + "/urdf/models/m100.urdf";

void write_bytes(const std::filesystem::path& p, const std::vector<std::uint8_t>& bytes) {
  std::ofstream f(p, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

// The M100's depth camera over flat ground (its 40 degree vertical field of view needs
// about 3.5 m of height to see a footprint with its clearance ring) at height `ground_z`, base_link
// at (x, y, z) with yaw only: the depth of each pixel by intersecting its ray.
DepthImageMm flat_frame(double x, double y, double z, double yaw, double ground_z) {
  const RobotDescription robot = load_robot_description(kUrdf);
  const CameraSensor& s = robot.depth_camera();
  const CameraModel cam = camera_model(s, robot.source);
  Pose3 X_WB = Pose3::Identity();
  X_WB.translation() = Eigen::Vector3d(x, y, z);
  X_WB.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Pose3 X_WC = X_WB * s.X_BS * X_SC();
  DepthImageMm img(cam.width_px, cam.height_px, 0);
  for (int v = 0; v < cam.height_px; ++v)
    for (int u = 0; u < cam.width_px; ++u) {
      const Eigen::Vector3d d_W = X_WC.linear() * cam.ray({u, v});
      const double t = (ground_z - X_WC.translation().z()) / d_W.z();  // ray z_C = 1: t is depth
      img.at(u, v) = static_cast<std::uint16_t>(std::lround(t * 1000.0));
    }
  return img;
}

// A path in single quotes, for the shell the CLI runs in.
std::string quoted(const std::filesystem::path& p) {
  std::string s(1, '\'');
  s += p.string();
  s += '\'';
  return s;
}

std::string pose_arg(double x, double y, double z, double yaw) {
  return "--pose " + std::to_string(x) + "," + std::to_string(y) + "," + std::to_string(z) +
         ",0,0," + std::to_string(yaw);
}

TEST(DetectLandingCli, FlatGroundGivesZonesBestFirstAsJson) {
  TempDir dir;
  const auto depth = dir.path() / "depth.png";
  write_bytes(depth, encode_png(flat_frame(2.0, -1.0, 4.0, 0.3, 0.25)));
  const auto r = run_cli("detect landing '" + depth.string() + "' --robot m100 " +
                         pose_arg(2.0, -1.0, 4.0, 0.3) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("zones"));
  const auto& zones = j["zones"];
  ASSERT_FALSE(zones.empty());
  double last = 1e9;
  for (const auto& z : zones) {
    // Exactly the documented keys.
    EXPECT_EQ(z.size(), 5u) << z.dump();
    for (const char* k : {"center_m", "slope_deg", "roughness_m", "clearance_m", "score"})
      EXPECT_TRUE(z.contains(k)) << k;
    EXPECT_NEAR(z["center_m"][2].get<double>(), 0.25, 0.01);
    EXPECT_LT(z["slope_deg"].get<double>(), 0.5);
    EXPECT_LE(z["score"].get<double>(), last);
    last = z["score"].get<double>();
  }
  // The camera sits 0.10 m ahead of base_link: the nadir of the optical centre is the
  // preferred zone, within a cell.
  const double cx = 2.0 + 0.10 * std::cos(0.3), cy = -1.0 + 0.10 * std::sin(0.3);
  EXPECT_NEAR(zones[0]["center_m"][0].get<double>(), cx, 0.12);
  EXPECT_NEAR(zones[0]["center_m"][1].get<double>(), cy, 0.12);
}

TEST(DetectLandingCli, WritesTheOverlayAndASummary) {
  TempDir dir;
  const auto depth = dir.path() / "depth.png";
  write_bytes(depth, encode_png(flat_frame(0, 0, 4.0, 0, 0)));
  const auto overlay = dir.path() / "overlay.png";
  const auto r = run_cli("detect landing '" + depth.string() + "' --robot '" + kUrdf + "' " +
                         pose_arg(0, 0, 4.0, 0) + " -o '" + overlay.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("landing zone"), std::string::npos) << r.out;
  const RgbImage img = read_rgb_image(overlay);
  EXPECT_EQ(img.width_px, 1280);
  EXPECT_EQ(img.height_px, 720);
  // The chosen zone is ringed in white somewhere.
  bool white = false;
  for (std::size_t k = 0; k + 2 < img.data.size() && !white; k += 3)
    white = img.data[k] == 255 && img.data[k + 1] == 255 && img.data[k + 2] == 255;
  EXPECT_TRUE(white);
}

TEST(DetectLandingCli, NoReturnsGiveAnEmptyListWithAReason) {
  TempDir dir;
  const auto depth = dir.path() / "empty.png";
  write_bytes(depth, encode_png(DepthImageMm(1280, 720, 0)));
  const auto r =
      run_cli("detect landing '" + depth.string() + "' " + pose_arg(0, 0, 3, 0) + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["zones"].empty());
  EXPECT_NE(j["reason"].get<std::string>().find("no safe zone"), std::string::npos);
}

TEST(DetectLandingCli, AnOpeningOutOfReachLeavesNoZone) {
  TempDir dir;
  const auto depth = dir.path() / "depth.png";
  write_bytes(depth, encode_png(flat_frame(0, 0, 4, 0, 0)));
  const auto r = run_cli("detect landing '" + depth.string() + "' " + pose_arg(0, 0, 4, 0) +
                         " --opening 9,0,0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["zones"].empty());
  EXPECT_NE(j["reason"].get<std::string>().find("out of reach"), std::string::npos) << r.out;
  // Within reach (l_0 = 1 m by default), the zones are at most 1 m from it.
  const auto near = run_cli("detect landing '" + depth.string() + "' " + pose_arg(0, 0, 4, 0) +
                            " --opening 0.8,0.3,0 --json");
  ASSERT_EQ(near.exit_code, 0) << near.err;
  const auto jn = nlohmann::json::parse(near.out);
  ASSERT_FALSE(jn["zones"].empty());
  for (const auto& z : jn["zones"])
    EXPECT_LE(std::hypot(z["center_m"][0].get<double>() - 0.8,
                         z["center_m"][1].get<double>() + 0.04 - 0.3),  // winch 0.04 m to the left
              1.0 + 1e-9);
}

// Frames of one hover: fused pixel by pixel. One frame reads every depth 60 mm long,
// the other 60 mm short: alone, each puts the ground about 6 cm off; fused, on it.
TEST(DetectLandingCli, SeveralFramesOfOneHoverAreFused) {
  TempDir dir;
  DepthImageMm far = flat_frame(0, 0, 4.0, 0, 0.25), near = far;
  for (auto& mm : far.data) mm = static_cast<std::uint16_t>(mm + 60);
  for (auto& mm : near.data) mm = static_cast<std::uint16_t>(mm - 60);
  write_bytes(dir.path() / "far.png", encode_png(far));
  write_bytes(dir.path() / "near.png", encode_png(near));
  const auto best_z = [&](const std::string& frames) {
    const auto r = run_cli("detect landing " + frames + " " + pose_arg(0, 0, 4.0, 0) + " --json");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    return j["zones"].empty() ? std::nan("") : j["zones"][0]["center_m"][2].get<double>();
  };
  const std::string f = quoted(dir.path() / "far.png"), n = quoted(dir.path() / "near.png");
  EXPECT_NEAR(best_z(f), 0.25 - 0.06, 0.01);
  EXPECT_NEAR(best_z(n), 0.25 + 0.06, 0.01);
  EXPECT_NEAR(best_z(f + " " + n), 0.25, 0.005);
}

// Bad input: exit 2, one line naming the file or option, and no overlay written.
void expect_bad(const std::string& args, const std::filesystem::path& overlay,
                const std::vector<std::string>& words) {
  const auto r = run_cli(args + " -o '" + overlay.string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_FALSE(std::filesystem::exists(overlay));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  for (const auto& w : words) EXPECT_NE(r.err.find(w), std::string::npos) << w << " in " << r.err;
}

TEST(DetectLandingCli, AnEightBitPngIsBadInputNamingTheBitDepth) {
  TempDir dir;
  const auto depth = dir.path() / "eight_bit.png";
  write_bytes(depth, encode_png(GrayImage(1280, 720, 100)));
  expect_bad("detect landing '" + depth.string() + "' " + pose_arg(0, 0, 3, 0),
             dir.path() / "o.png", {"eight_bit.png", "8"});
}

TEST(DetectLandingCli, AFileThatIsNotAnImageIsBadInput) {
  TempDir dir;
  const auto depth = dir.path() / "notes.png";
  std::ofstream(depth) << "this is not a PNG\n";
  expect_bad("detect landing '" + depth.string() + "' " + pose_arg(0, 0, 3, 0),
             dir.path() / "o.png", {"notes.png"});
}

TEST(DetectLandingCli, AFrameOfAnotherSizeThanTheCameraIsBadInput) {
  TempDir dir;
  const auto depth = dir.path() / "small.png";
  write_bytes(depth, encode_png(DepthImageMm(640, 480, 3000)));
  expect_bad("detect landing '" + depth.string() + "' " + pose_arg(0, 0, 3, 0),
             dir.path() / "o.png", {"small.png", "1280 x 720", "640 x 480"});
}

TEST(DetectLandingCli, ABadSecondFrameIsNamedAndSixtyFiveFramesAreTooMany) {
  TempDir dir;
  const auto good = dir.path() / "good.png";
  write_bytes(good, encode_png(flat_frame(0, 0, 4.0, 0, 0)));
  const auto eight = dir.path() / "second_eight_bit.png";
  write_bytes(eight, encode_png(GrayImage(1280, 720, 100)));
  const auto small = dir.path() / "second_small.png";
  write_bytes(small, encode_png(DepthImageMm(640, 480, 3000)));
  const auto o = dir.path() / "o.png";
  const std::string g = quoted(good) + " ";
  expect_bad("detect landing " + g + quoted(eight) + " " + pose_arg(0, 0, 4, 0), o,
             {"second_eight_bit.png", "8"});
  expect_bad("detect landing " + g + quoted(small) + " " + pose_arg(0, 0, 4, 0), o,
             {"second_small.png", "640 x 480"});
  std::string many;
  for (int k = 0; k < 65; ++k) many += g;
  expect_bad("detect landing " + many + pose_arg(0, 0, 4, 0), o, {"DEPTH", "64", "65"});
}

TEST(DetectLandingCli, BadPosesAndOpeningsAreBadInput) {
  TempDir dir;
  const auto depth = dir.path() / "depth.png";
  write_bytes(depth, encode_png(DepthImageMm(1280, 720, 3000)));
  const std::string base = "detect landing '" + depth.string() + "' ";
  const auto o = dir.path() / "o.png";
  expect_bad(base + "--pose 0,0,nan,0,0,0", o, {"--pose"});
  expect_bad(base + "--pose 0,0,3,0,0", o, {"--pose"});
  expect_bad(base + "--pose 0,0,1e300,0,0,0", o, {"--pose"});
  expect_bad(base + "--pose 0,0,3,0,0,99", o, {"--pose"});
  expect_bad(base + "--pose 0,0,3,0,0,0 --opening 1,inf,0", o, {"--opening"});
  expect_bad(base + "--pose 0,0,3,0,0,0 --robot nosuchrobot", o, {"nosuchrobot"});
}

TEST(DetectLandingCli, AnOverlayPathThatIsADirectoryIsRefusedBeforeWork) {
  TempDir dir;
  const auto depth = dir.path() / "depth.png";
  write_bytes(depth, encode_png(DepthImageMm(1280, 720, 3000)));
  const auto r = run_cli("detect landing '" + depth.string() + "' " + pose_arg(0, 0, 3, 0) +
                         " -o '" + dir.path().string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const auto txt = run_cli("detect landing '" + depth.string() + "' " + pose_arg(0, 0, 3, 0) +
                           " -o '" + (dir.path() / "o.txt").string() + "'");
  EXPECT_EQ(txt.exit_code, 2);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "o.txt"));
}

}  // namespace
}  // namespace ferret
