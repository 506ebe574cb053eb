// `ferret config --dump` prints every URDF camera's camera model with where it came
// from; `ferret config --camera-info SENSOR -o FILE` writes that camera as a ROS
// camera_info file; bad input is exit 2, one line naming file and field, no file.

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "support/cli_runner.hpp"

namespace ferret::test {
namespace {

namespace fs = std::filesystem;

constexpr double kDeg = std::numbers::pi / 180.0;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

void expect_bad_input(const CliResult& r, const std::string& source, const std::string& field) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line:\n" << r.err;
  EXPECT_TRUE(contains(r.err, source)) << r.err;
  EXPECT_TRUE(contains(r.err, field)) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

/// The camera model entry named `name` of a dump's robot.camera_models.
YAML::Node camera_model(const YAML::Node& dump, const std::string& name) {
  for (const auto& c : dump["robot"]["camera_models"])
    if (c["name"].as<std::string>() == name) return c;
  ADD_FAILURE() << "no camera model " << name;
  return {};
}

/// A robot with one Gazebo camera whose <camera> holds `calibration`.
std::string camera_urdf(const std::string& calibration) {
  return R"(<?xml version="1.0"?>
<robot name="cal">
  <link name="base_link"><collision><geometry><box size="0.2 0.1 0.05"/></geometry></collision></link>
  <link name="cam_link"/>
  <joint name="cam_joint" type="fixed"><parent link="base_link"/><child link="cam_link"/></joint>
  <gazebo reference="cam_link">
    <sensor type="camera" name="cam">
      <ferret role="marker_camera"/>
      <camera>
        <horizontal_fov>1.0</horizontal_fov>
        <image><width>800</width><height>600</height></image>
        <clip><near>0.1</near><far>10</far></clip>
        )" +
         calibration +
         R"(
      </camera>
    </sensor>
  </gazebo>
</robot>
)";
}

TEST(ConfigCamera, DumpGivesEachCameraModelOfTheM100) {
  const auto r = run_cli("config --dump --robot m100");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node dump = YAML::Load(r.out);
  ASSERT_EQ(dump["robot"]["camera_models"].size(), 2u) << r.out;
  // The marker camera: 1280 x 720, horizontal fov 78 deg (1.3613568165555772 rad).
  const YAML::Node m = camera_model(dump, "marker_camera");
  EXPECT_EQ(m["image_px"][0].as<int>(), 1280);
  EXPECT_EQ(m["image_px"][1].as<int>(), 720);
  const double fx = 640.0 / std::tan(39.0 * kDeg);
  EXPECT_NEAR(m["fx_px"].as<double>(), fx, 1e-6);
  EXPECT_NEAR(m["fy_px"].as<double>(), fx, 1e-6);
  EXPECT_EQ(m["cx_px"].as<double>(), 639.5);
  EXPECT_EQ(m["cy_px"].as<double>(), 359.5);
  EXPECT_EQ(m["distortion_model"].as<std::string>(), "none");
  EXPECT_NEAR(m["horizontal_fov_deg"].as<double>(), 78.0, 1e-6);
  EXPECT_NEAR(m["vertical_fov_deg"].as<double>(), 2.0 * std::atan(360.0 / fx) / kDeg, 1e-6);
  EXPECT_EQ(m["roles"][0].as<std::string>(), "marker_camera");
  EXPECT_TRUE(contains(m["provenance"]["pinhole"].as<std::string>(), "urdf:urdf/models/m100.urdf:"))
      << r.out;
  EXPECT_TRUE(contains(m["provenance"]["distortion"].as<std::string>(), "default")) << r.out;
  // The depth camera is listed too, with its own fov (65 deg).
  const YAML::Node d = camera_model(dump, "depth_camera");
  EXPECT_NEAR(d["fx_px"].as<double>(), 640.0 / std::tan(32.5 * kDeg), 1e-6);
  EXPECT_EQ(d["roles"][0].as<std::string>(), "depth_camera");
}

TEST(ConfigCamera, DumpShowsUrdfDistortionAndIntrinsicsWithTheirLines) {
  TempDir dir;
  std::ofstream(dir / "cal.urdf") << camera_urdf(
      "<distortion><k1>-0.2</k1><k2>0.05</k2><k3>0.003</k3><p1>0.0007</p1><p2>-0.0004</p2>"
      "</distortion>\n        "
      "<lens><intrinsics><fx>700.5</fx><fy>701.25</fy><cx>401.5</cx><cy>298.75</cy></intrinsics>"
      "</lens>");
  const auto r = run_cli("config --dump --robot '" + (dir / "cal.urdf") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node m = camera_model(YAML::Load(r.out), "cam");
  EXPECT_EQ(m["fx_px"].as<double>(), 700.5);
  EXPECT_EQ(m["fy_px"].as<double>(), 701.25);
  EXPECT_EQ(m["cx_px"].as<double>(), 401.5);
  EXPECT_EQ(m["cy_px"].as<double>(), 298.75);
  EXPECT_EQ(m["distortion_model"].as<std::string>(), "plumb_bob");
  // camera_info order: k1, k2, p1, p2, k3.
  const double want[5] = {-0.2, 0.05, 0.0007, -0.0004, 0.003};
  for (int i = 0; i < 5; ++i) EXPECT_EQ(m["distortion_coefficients"][i].as<double>(), want[i]) << i;
  EXPECT_NEAR(m["horizontal_fov_deg"].as<double>(),
              (std::atan(402.0 / 700.5) + std::atan((799.5 - 401.5) / 700.5)) / kDeg, 1e-6);
  // <distortion> is on line 13 of the file, <lens> on line 14.
  EXPECT_TRUE(contains(m["provenance"]["distortion"].as<std::string>(), "cal.urdf:13")) << r.out;
  EXPECT_TRUE(contains(m["provenance"]["pinhole"].as<std::string>(), "cal.urdf:14")) << r.out;
}

TEST(ConfigCamera, CameraInfoWritesTheUrdfCameraAsRosCalibration) {
  TempDir dir;
  std::ofstream(dir / "cal.urdf") << camera_urdf(
      "<distortion><k1>-0.2</k1><k2>0.05</k2><k3>0.003</k3><p1>0.0007</p1><p2>-0.0004</p2>"
      "</distortion>");
  const auto r = run_cli("config --robot '" + (dir / "cal.urdf") + "' --camera-info cam -o '" +
                         (dir / "cam.yaml") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node ci = YAML::LoadFile(dir / "cam.yaml");
  EXPECT_EQ(ci["image_width"].as<int>(), 800);
  EXPECT_EQ(ci["image_height"].as<int>(), 600);
  EXPECT_EQ(ci["camera_name"].as<std::string>(), "cam");
  EXPECT_EQ(ci["distortion_model"].as<std::string>(), "plumb_bob");
  // fx = (800 / 2) / tan(0.5) to the last bit; principal point (w - 1) / 2, (h - 1) / 2.
  const double fx = 0.5 * 800 / std::tan(0.5 * 1.0);
  EXPECT_EQ(ci["camera_matrix"]["data"][0].as<double>(), fx);
  EXPECT_EQ(ci["camera_matrix"]["data"][2].as<double>(), 399.5);
  EXPECT_EQ(ci["camera_matrix"]["data"][4].as<double>(), fx);
  EXPECT_EQ(ci["camera_matrix"]["data"][5].as<double>(), 299.5);
  EXPECT_EQ(ci["camera_matrix"]["data"][8].as<double>(), 1.0);
  const double want[5] = {-0.2, 0.05, 0.0007, -0.0004, 0.003};
  ASSERT_EQ(ci["distortion_coefficients"]["data"].size(), 5u);
  for (int i = 0; i < 5; ++i)
    EXPECT_EQ(ci["distortion_coefficients"]["data"][i].as<double>(), want[i]) << i;
  EXPECT_EQ(ci["projection_matrix"]["data"][0].as<double>(), fx);
  EXPECT_EQ(ci["projection_matrix"]["data"][3].as<double>(), 0.0);
  EXPECT_EQ(ci["rectification_matrix"]["data"][4].as<double>(), 1.0);
}

TEST(ConfigCamera, BadSensorNameIsExit2AndNoFile) {
  TempDir dir;
  const auto r =
      run_cli("config --robot m100 --camera-info front_camera -o '" + (dir / "c.yaml") + "'");
  expect_bad_input(r, "--camera-info", "front_camera");
  // The message lists what the robot has.
  EXPECT_TRUE(contains(r.err, "marker_camera")) << r.err;
  EXPECT_EQ(dir.count(), 0u);
}

TEST(ConfigCamera, CameraInfoNeedsAnOutputAndOneAction) {
  TempDir dir;
  expect_bad_input(run_cli("config --robot m100 --camera-info marker_camera"), "--out",
                   "camera_info");
  expect_bad_input(run_cli("config --robot m100 --dump --camera-info marker_camera -o '" +
                           (dir / "c.yaml") + "'"),
                   "--dump", "--camera-info");
  expect_bad_input(
      run_cli("config --robot m100 --camera-info marker_camera -o '" + dir.path().string() + "'"),
      dir.path().string(), "");
  EXPECT_EQ(dir.count(), 0u);
}

TEST(ConfigCamera, BadUrdfCalibrationIsExit2NamingFileAndElement) {
  TempDir dir;
  std::ofstream(dir / "bad.urdf") << camera_urdf(
      "<lens><intrinsics><fx>700</fx><fy>nan</fy><cx>400</cx><cy>300</cy></intrinsics></lens>");
  const auto r = run_cli("config --robot '" + (dir / "bad.urdf") + "' --camera-info cam -o '" +
                         (dir / "c.yaml") + "'");
  expect_bad_input(r, "bad.urdf:13", "lens/intrinsics/fy");
  EXPECT_FALSE(fs::exists(dir / "c.yaml"));
  const auto dump = run_cli("config --dump --robot '" + (dir / "bad.urdf") + "'");
  expect_bad_input(dump, "bad.urdf:13", "lens/intrinsics/fy");
}

}  // namespace
}  // namespace ferret::test
