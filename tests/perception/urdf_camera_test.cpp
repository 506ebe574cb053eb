// Cameras from URDF Gazebo blocks: the optional <distortion> and <lens><intrinsics>
// blocks become the camera model's plumb_bob coefficients and pinhole, the model's
// ray() and project() invert each other over the whole distorted image, and every bad
// value is an InputError naming the file, the line and the element.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

/// A robot with one Gazebo camera; `calibration` goes inside its <camera>.
std::string camera_urdf(const std::string& calibration, int width = 640, int height = 480) {
  return R"(<?xml version="1.0"?>
<robot name="t">
  <link name="base_link"><collision><geometry><box size="0.2 0.1 0.05"/></geometry></collision></link>
  <link name="cam_link"/>
  <joint name="cam_joint" type="fixed"><parent link="base_link"/><child link="cam_link"/>
    <origin xyz="0.1 0 0.02" rpy="0 0 0"/></joint>
  <gazebo reference="cam_link">
    <sensor type="camera" name="cam">
      <ferret role="marker_camera"/>
      <camera>
        <horizontal_fov>1.2</horizontal_fov>
        <image><width>)" +
         std::to_string(width) + "</width><height>" + std::to_string(height) +
         R"(</height></image>
        <clip><near>0.1</near><far>10</far></clip>
)" + calibration +
         R"(
      </camera>
    </sensor>
  </gazebo>
</robot>
)";
}

RobotDescription load(const std::string& xml) {
  return robot_description_from_string(xml, "cam.urdf");
}

const char* const kDistortion = R"(<distortion>
          <k1>-0.25</k1><k2>0.08</k2><k3>-0.01</k3><p1>0.001</p1><p2>-0.0005</p2>
          <center>0.5 0.5</center>
        </distortion>)";
const char* const kIntrinsics = R"(<lens><intrinsics>
          <fx>512.5</fx><fy>511.25</fy><cx>322.75</cx><cy>236.5</cy><s>0</s>
        </intrinsics></lens>)";

TEST(UrdfCamera, NoCalibrationBlocksGiveTheIdealPinhole) {
  const RobotDescription r = load(camera_urdf(""));
  const CameraSensor& s = r.marker_camera();
  EXPECT_FALSE(s.distortion.has_value());
  EXPECT_FALSE(s.intrinsics.has_value());
  const CameraModel m = camera_model(s, r.source);
  EXPECT_EQ(m.distortion, DistortionModel::kNone);
  // fx = (640 / 2) / tan(0.6); principal point at the centre, (w - 1) / 2.
  EXPECT_NEAR(m.fx_px, 320.0 / std::tan(0.6), 1e-9);
  EXPECT_EQ(m.fy_px, m.fx_px);
  EXPECT_EQ(m.cx_px, 319.5);
  EXPECT_EQ(m.cy_px, 239.5);
}

TEST(UrdfCamera, DistortionBlockBecomesPlumbBobInCameraInfoOrder) {
  const RobotDescription r = load(camera_urdf(kDistortion));
  const CameraSensor& s = r.marker_camera();
  ASSERT_TRUE(s.distortion.has_value());
  EXPECT_EQ(s.distortion->k1, -0.25);
  EXPECT_EQ(s.distortion->k3, -0.01);
  EXPECT_EQ(s.distortion->p2, -0.0005);
  EXPECT_EQ(s.distortion->center_x, 0.5);
  const CameraModel m = camera_model(s, r.source);
  EXPECT_EQ(m.distortion, DistortionModel::kPlumbBob);
  // camera_info's D order is k1, k2, p1, p2, k3 (Gazebo writes k3 before p1).
  const std::array<double, 5> want{-0.25, 0.08, 0.001, -0.0005, -0.01};
  EXPECT_EQ(m.distortion_coefficients, want);
  EXPECT_NEAR(m.fx_px, 320.0 / std::tan(0.6), 1e-9);  // the pinhole is still the fov's
  EXPECT_NE(r.provenance.at("cameras.cam.distortion").find("cam.urdf:"), std::string::npos);
}

TEST(UrdfCamera, MissingCoefficientsAreZeroAndTheCentreDefaultsToTheMiddle) {
  const RobotDescription r = load(camera_urdf("<distortion><k1>0.1</k1></distortion>"));
  const CameraModel m = camera_model(r.marker_camera(), r.source);
  const std::array<double, 5> want{0.1, 0.0, 0.0, 0.0, 0.0};
  EXPECT_EQ(m.distortion_coefficients, want);
  EXPECT_EQ(r.marker_camera().distortion->center_y, 0.5);
}

TEST(UrdfCamera, IntrinsicsReplaceThePinholeOfTheFov) {
  const RobotDescription r = load(camera_urdf(kIntrinsics));
  const CameraModel m = camera_model(r.marker_camera(), r.source);
  EXPECT_EQ(m.fx_px, 512.5);
  EXPECT_EQ(m.fy_px, 511.25);
  EXPECT_EQ(m.cx_px, 322.75);
  EXPECT_EQ(m.cy_px, 236.5);
  EXPECT_EQ(m.projection(0, 0), 512.5);  // P = [K | 0]
  EXPECT_EQ(m.projection(1, 2), 236.5);
  EXPECT_EQ(m.projection(2, 2), 1.0);
  // The model's fov follows the intrinsics: atan((cx + 0.5) / fx) + atan((w - 0.5 - cx) / fx).
  EXPECT_NEAR(m.horizontal_fov_rad(),
              std::atan(323.25 / 512.5) + std::atan((639.5 - 322.75) / 512.5), 1e-12);
}

TEST(UrdfCamera, RayAndProjectInvertEachOtherOverTheWholeDistortedImage) {
  // Barrel distortion of a wide lens with decentring terms, calibrated intrinsics:
  // every pixel (corners and edges included) maps to a ray and back to itself.
  // No <center>: the distortion is about the calibrated principal point.
  const RobotDescription r = load(camera_urdf(
      "<distortion><k1>-0.25</k1><k2>0.08</k2><k3>-0.01</k3><p1>0.001</p1><p2>-0.0005</p2>"
      "</distortion>" +
      std::string(kIntrinsics)));
  const CameraModel m = camera_model(r.marker_camera(), r.source);
  ASSERT_TRUE(m.has_distortion());
  double worst_px = 0.0;
  for (double v = -0.5; v <= m.height_px - 0.5; v += 8.0) {
    for (double u = -0.5; u <= m.width_px - 0.5; u += 8.0) {
      const Eigen::Vector2d pixel(u, v);
      const Eigen::Vector3d ray = m.ray(pixel);
      ASSERT_EQ(ray.z(), 1.0);
      for (const double depth : {0.3, 4.0}) {
        const auto back = m.project(depth * ray);
        ASSERT_TRUE(back.has_value());
        worst_px = std::max(worst_px, (*back - pixel).norm());
      }
    }
  }
  EXPECT_LT(worst_px, 1e-6);
  // Distortion moves the image corner: its ray differs from the ideal pinhole's.
  const Eigen::Vector3d corner = m.ray({-0.5, -0.5});
  EXPECT_GT(std::abs(corner.x() - (-0.5 - m.cx_px) / m.fx_px), 0.01);
}

TEST(UrdfCamera, DistortionMovesPointsAsThePlumbBobFormulaSays) {
  // A point at normalised (0.3, -0.2): hand-evaluated Brown-Conrady with the block's
  // coefficients. r2 = 0.13; radial = 1 - 0.25 r2 + 0.08 r2^2 - 0.01 r2^3.
  const RobotDescription r = load(camera_urdf(kDistortion));
  const CameraModel m = camera_model(r.marker_camera(), r.source);
  const double x = 0.3, y = -0.2, r2 = 0.13;
  const double radial = 1 - 0.25 * r2 + 0.08 * r2 * r2 - 0.01 * r2 * r2 * r2;
  const double xd = x * radial + 2 * 0.001 * x * y + -0.0005 * (r2 + 2 * x * x);
  const double yd = y * radial + 0.001 * (r2 + 2 * y * y) + 2 * -0.0005 * x * y;
  const auto pixel = m.project({x, y, 1.0});
  ASSERT_TRUE(pixel.has_value());
  EXPECT_NEAR(pixel->x(), m.fx_px * xd + m.cx_px, 1e-9);
  EXPECT_NEAR(pixel->y(), m.fy_px * yd + m.cy_px, 1e-9);
}

struct Bad {
  const char* what;
  std::string calibration;
  const char* field;  ///< the end of the field the error must name
};

TEST(UrdfCamera, BadCalibrationBlocksNameFileLineAndElement) {
  const std::vector<Bad> cases{
      {"NaN k1", "<distortion><k1>nan</k1></distortion>", "/camera/distortion/k1"},
      {"text k2", "<distortion><k2>0.1 0.2</k2></distortion>", "/camera/distortion/k2"},
      {"absurd p1", "<distortion><p1>1e9</p1></distortion>", "/camera/distortion/p1"},
      {"off-centre", "<distortion><k1>0.1</k1><center>0.3 0.5</center></distortion>",
       "/camera/distortion/center"},
      {"one centre number", "<distortion><center>0.5</center></distortion>",
       "/camera/distortion/center"},
      {"centre outside", "<distortion><center>1.5 0.5</center></distortion>",
       "/camera/distortion/center"},
      {"missing cy", "<lens><intrinsics><fx>500</fx><fy>500</fy><cx>320</cx></intrinsics></lens>",
       "/lens/intrinsics/cy"},
      {"negative fx",
       "<lens><intrinsics><fx>-500</fx><fy>500</fy><cx>320</cx><cy>240</cy></intrinsics></lens>",
       "/lens/intrinsics/fx"},
      {"inf fy",
       "<lens><intrinsics><fx>500</fx><fy>inf</fy><cx>320</cx><cy>240</cy></intrinsics></lens>",
       "/lens/intrinsics/fy"},
      {"cx outside",
       "<lens><intrinsics><fx>500</fx><fy>500</fy><cx>900</cx><cy>240</cy></intrinsics></lens>",
       "/lens/intrinsics/cx"},
      {"centre not at the intrinsics' principal point",
       std::string("<distortion><k1>0.1</k1><center>0.5 0.5</center></distortion>") +
           "<lens><intrinsics><fx>500</fx><fy>500</fy><cx>100</cx><cy>240</cy></intrinsics></lens>",
       "/camera/distortion/center"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    try {
      (void)load(camera_urdf(c.calibration));
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.source().rfind("cam.urdf:", 0), 0u) << e.source();  // file:line
      const std::string field = e.field();
      EXPECT_TRUE(field.size() >= std::string(c.field).size() &&
                  field.compare(field.size() - std::string(c.field).size(), std::string::npos,
                                c.field) == 0)
          << field << "; " << e.what();
      EXPECT_NE(field.find("sensor[cam]"), std::string::npos) << field;
    }
  }
}

}  // namespace
}  // namespace ferret
