#include "ferret/perception/camera_model.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <vector>

#include "ferret/core/data_path.hpp"
#include "ferret/core/error.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {
using ::testing::HasSubstr;

constexpr double kPi = std::numbers::pi;

CameraModel distorted_camera() {
  CameraModel m = CameraModel::from_fov("test", 640, 480, 70.0 * kPi / 180.0);
  m.fy_px = m.fx_px * 1.01;
  m.cx_px = 322.7;
  m.cy_px = 236.1;
  m.distortion = DistortionModel::kPlumbBob;
  m.distortion_coefficients = {-0.28, 0.09, 0.0012, -0.0008, -0.012};
  return m;
}

TEST(CameraModel, FromFovIsTheGazeboPinhole) {
  const CameraModel m = CameraModel::from_fov("cam", 640, 480, kPi / 2);
  EXPECT_DOUBLE_EQ(m.fx_px, 320.0);  // (640 / 2) / tan(45 deg)
  EXPECT_DOUBLE_EQ(m.fy_px, 320.0);
  EXPECT_DOUBLE_EQ(m.cx_px, 319.5);
  EXPECT_DOUBLE_EQ(m.cy_px, 239.5);
  EXPECT_NEAR(m.horizontal_fov_rad(), kPi / 2, 1e-12);
  EXPECT_NEAR(m.vertical_fov_rad(), 2 * std::atan(240.0 / 320.0), 1e-12);
  EXPECT_FALSE(m.has_distortion());
  EXPECT_DOUBLE_EQ(m.projection(0, 0), 320.0);
  EXPECT_DOUBLE_EQ(m.projection(1, 2), 239.5);
  EXPECT_DOUBLE_EQ(m.projection(2, 2), 1.0);
  EXPECT_DOUBLE_EQ(m.projection(0, 3), 0.0);
}

TEST(CameraModel, ProjectsByHand) {
  const CameraModel m = CameraModel::from_fov("cam", 640, 480, kPi / 2);
  const auto px = m.project({1.0, 0.5, 2.0});
  ASSERT_TRUE(px.has_value());
  EXPECT_DOUBLE_EQ(px->x(), 320.0 * 0.5 + 319.5);
  EXPECT_DOUBLE_EQ(px->y(), 320.0 * 0.25 + 239.5);
  EXPECT_FALSE(m.project({0.0, 0.0, 0.0}).has_value());
  EXPECT_FALSE(m.project({0.1, 0.0, -1.0}).has_value());
  EXPECT_TRUE(m.in_image({-0.5, -0.5}));
  EXPECT_FALSE(m.in_image({639.5, 0.0}));
  EXPECT_FALSE(m.in_image({10.0, 10.0}, 10.6));
}

TEST(CameraModel, PlumbBobByHand) {
  CameraModel m = CameraModel::from_fov("cam", 640, 480, kPi / 2);
  m.distortion = DistortionModel::kPlumbBob;
  m.distortion_coefficients = {-0.2, 0.05, 0.01, 0.02, 0.0};
  // r^2 = 0.25; radial = 1 + 0.25 (-0.2 + 0.25 * 0.05) = 0.953125.
  const Eigen::Vector2d d = m.distort({0.3, 0.4});
  EXPECT_NEAR(d.x(), 0.3 * 0.953125 + 2 * 0.01 * 0.3 * 0.4 + 0.02 * (0.25 + 2 * 0.09), 1e-15);
  EXPECT_NEAR(d.y(), 0.4 * 0.953125 + 0.01 * (0.25 + 2 * 0.16) + 2 * 0.02 * 0.3 * 0.4, 1e-15);
}

TEST(CameraModel, AgreesWithOpenCvProjectPoints) {
  const CameraModel m = distorted_camera();
  std::vector<cv::Point3d> points;
  for (double x = -1.0; x <= 1.0; x += 0.25)
    for (double y = -0.7; y <= 0.7; y += 0.35) points.emplace_back(x, y, 1.6 + 0.2 * x);
  cv::Mat K(3, 3, CV_64F), D(1, 5, CV_64F);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) K.at<double>(r, c) = m.K()(r, c);
  for (int i = 0; i < 5; ++i)
    D.at<double>(0, i) = m.distortion_coefficients[static_cast<std::size_t>(i)];
  std::vector<cv::Point2d> expected;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D, expected);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto px = m.project({points[i].x, points[i].y, points[i].z});
    ASSERT_TRUE(px.has_value());
    EXPECT_NEAR(px->x(), expected[i].x, 1e-9) << i;
    EXPECT_NEAR(px->y(), expected[i].y, 1e-9) << i;
  }
}

TEST(CameraModel, RayInvertsProjectionOverTheWholeImage) {
  const CameraModel m = distorted_camera();
  double worst_px = 0.0;
  for (double u = -0.5; u <= 639.5; u += 31.95)
    for (double v = -0.5; v <= 479.5; v += 23.95) {
      const Eigen::Vector3d r = m.ray({u, v});
      EXPECT_DOUBLE_EQ(r.z(), 1.0);
      const auto back = m.project(2.5 * r);
      ASSERT_TRUE(back.has_value());
      worst_px = std::max(worst_px, (*back - Eigen::Vector2d(u, v)).norm());
    }
  EXPECT_LT(worst_px, 1e-6);
}

TEST(CameraModel, OpticalFrameInSensorFrame) {
  const Pose3 X = X_SC();
  // The optical z (forward) is the sensor's x; optical x (right) is -y (y is left);
  // optical y (down) is -z.
  EXPECT_TRUE((X.linear() * Eigen::Vector3d::UnitZ()).isApprox(Eigen::Vector3d::UnitX()));
  EXPECT_TRUE((X.linear() * Eigen::Vector3d::UnitX()).isApprox(-Eigen::Vector3d::UnitY()));
  EXPECT_TRUE((X.linear() * Eigen::Vector3d::UnitY()).isApprox(-Eigen::Vector3d::UnitZ()));
  EXPECT_NEAR(X.linear().determinant(), 1.0, 1e-15);
  EXPECT_TRUE(X.translation().isZero());
}

void expect_check_fails(CameraModel m, const std::string& field) {
  m.source = "cam.yaml";
  try {
    m.check();
    FAIL() << "expected InputError at " << field;
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "cam.yaml");
    EXPECT_EQ(e.field(), field);
  }
}

TEST(CameraModel, CheckNamesTheBadField) {
  const CameraModel good = distorted_camera();
  EXPECT_NO_THROW(good.check());
  CameraModel m = good;
  m.width_px = 0;
  expect_check_fails(m, "image_width");
  m = good;
  m.height_px = 20000;
  expect_check_fails(m, "image_height");
  m = good;
  m.fx_px = std::nan("");
  expect_check_fails(m, "camera_matrix.fx");
  m = good;
  m.fy_px = -3;
  expect_check_fails(m, "camera_matrix.fy");
  m = good;
  m.cx_px = 700;
  expect_check_fails(m, "camera_matrix.cx");
  m = good;
  m.distortion_coefficients[2] = INFINITY;
  expect_check_fails(m, "distortion_coefficients.data[2]");
  m = good;
  m.rectification(0, 1) = 0.1;
  expect_check_fails(m, "rectification_matrix");
  m = good;
  m.rectification = -Eigen::Matrix3d::Identity();  // orthonormal but a reflection
  expect_check_fails(m, "rectification_matrix");
}

TEST(CameraModel, FromTheUrdfsCameras) {
  const RobotDescription ugv = load_robot_description(data_path("models/miniugv.urdf"));
  const CameraSensor& cam = ugv.object_camera();
  const CameraModel m = camera_model(cam, ugv.source);
  EXPECT_EQ(m.width_px, cam.image_width_px);
  EXPECT_EQ(m.height_px, cam.image_height_px);
  EXPECT_NEAR(m.horizontal_fov_rad(), cam.horizontal_fov_rad, 1e-12);
  // Square pixels: the vertical fov follows from the aspect ratio, as the loader says.
  EXPECT_NEAR(m.vertical_fov_rad(), cam.vertical_fov_rad, 1e-9);
  EXPECT_THAT(m.source, HasSubstr(cam.name));
}

}  // namespace
}  // namespace ferret
