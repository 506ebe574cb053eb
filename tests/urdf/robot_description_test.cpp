#include "ferret/urdf/robot_description.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <numbers>

#include "ferret/core/error.hpp"
#include "urdf/robot_mission_yaml.hpp"

namespace ferret {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTol = 1e-9;

std::string models(const std::string& name) {
  return std::string(FERRET_SOURCE_DIR) + "/urdf/models/" + name;
}

/// A robot around a body box, with extra XML inside <robot>.
std::string robot_xml(const std::string& extra) {
  return R"(<?xml version="1.0"?>
<robot name="t">
  <link name="base_link"><collision><geometry><box size="0.2 0.1 0.05"/></geometry></collision></link>
  <link name="sensor_link"/>
  <joint name="sensor_joint" type="fixed"><parent link="base_link"/><child link="sensor_link"/>
    <origin xyz="0.1 0 0.02" rpy="0 0 0"/></joint>
)" + extra +
         "</robot>\n";
}

RobotDescription from(const std::string& xml, const RobotMissionSettings& mission = {}) {
  return robot_description_from_string(xml, "t.urdf", mission);
}

void expect_vec(const Eigen::Vector3d& got, const Eigen::Vector3d& want, double tol = kTol) {
  EXPECT_NEAR(got.x(), want.x(), tol);
  EXPECT_NEAR(got.y(), want.y(), tol);
  EXPECT_NEAR(got.z(), want.z(), tol);
}

// ---------------------------------------------------------------- shipped models

TEST(MiniUgvModel, EnvelopeIsThePapers130By120By55mm) {
  const auto r = load_robot_description(models("miniugv.urdf"));
  EXPECT_EQ(r.name, "miniugv");
  EXPECT_EQ(r.kind, RobotKind::kUgv);
  EXPECT_EQ(r.base_link, "base_link");
  expect_vec(r.bounding_box_B.min(), {-0.065, -0.060, 0.0});
  expect_vec(r.bounding_box_B.max(), {0.065, 0.060, 0.055});
  // Body (1) + four wheels + the EPM housing.
  ASSERT_EQ(r.collision_shapes.size(), 6u);
  int wheels = 0;
  for (const auto& s : r.collision_shapes) wheels += s.type == CollisionShape::Type::kCylinder;
  EXPECT_EQ(wheels, 4);
  // The farthest point in the plane is a wheel's outer rim corner: (0.062, 0.060).
  EXPECT_NEAR(r.circumscribed_radius_m, std::hypot(0.062, 0.060), 1e-6);
}

TEST(MiniUgvModel, CameraAndIrMatchThePaperExperiments) {
  const auto r = load_robot_description(models("miniugv.urdf"));
  const auto& cam = r.object_camera();
  EXPECT_FALSE(cam.depth);
  EXPECT_NEAR(cam.horizontal_fov_rad, kPi / 2, kTol);  // alpha = 90 deg
  EXPECT_EQ(cam.image_width_px, 640);
  EXPECT_EQ(cam.image_height_px, 480);
  EXPECT_NEAR(cam.vertical_fov_rad, 2 * std::atan(0.75), kTol);  // tan(45 deg) * 480/640
  EXPECT_DOUBLE_EQ(cam.range_max_m, 4.0);                        // D_cam
  expect_vec(cam.X_BS.translation(), {0.062, 0.0, 0.045});
  expect_vec(cam.X_BS.linear().col(0), {1, 0, 0});  // looks forward

  const IrArray ir = r.ir_array();
  EXPECT_NEAR(ir.fov_rad, kPi / 6, 1e-12);  // beta = 30 deg
  EXPECT_NEAR(ir.center_yaw_B_rad, 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(ir.range_max_m, 4.0);  // D_IR = D_cam
  EXPECT_DOUBLE_EQ(ir.range_min_m, 0.02);
  ASSERT_EQ(ir.beams.size(), 9u);
  double lo = 1, hi = -1;
  for (const auto& b : ir.beams) {
    lo = std::min(lo, b.yaw_B_rad);
    hi = std::max(hi, b.yaw_B_rad);
    EXPECT_NEAR(b.p_BO.x(), 0.065, kTol);
  }
  EXPECT_NEAR(lo, -kPi / 12, 1e-12);
  EXPECT_NEAR(hi, kPi / 12, 1e-12);
}

TEST(MiniUgvModel, EpmImuTetherAndLimits) {
  const auto r = load_robot_description(models("miniugv.urdf"));
  ASSERT_TRUE(r.epm);
  expect_vec(r.epm->X_BF.translation(), {-0.065, 0.0, 0.030});
  expect_vec(r.epm->X_BF.linear().col(0), {-1, 0, 0});  // faces backwards
  ASSERT_TRUE(r.imu);
  ASSERT_EQ(r.tether_attachments.size(), 2u);
  EXPECT_EQ(r.tether_attachments[0].name, "tether_attach_front_link");
  expect_vec(r.tether_attachments[0].X_BF.translation(), {0.045, 0, 0.055});
  expect_vec(r.tether_attachments[1].X_BF.translation(), {-0.045, 0, 0.055});
  EXPECT_FALSE(r.winch_spool);
  // 105 rad/s x 0.02 m wheels: above the mission's 2 m/s, so it does not cap it.
  ASSERT_TRUE(r.wheel_speed_limit_mps);
  EXPECT_NEAR(*r.wheel_speed_limit_mps, 2.1, 1e-12);
  EXPECT_DOUBLE_EQ(r.limits.max_velocity_mps, 2.0);
}

TEST(MiniUgvModel, WheelLimitCapsAFasterMission) {
  RobotMissionSettings mission;
  mission.ugv_limits.max_velocity_mps = 3.0;
  mission.ugv_limits.max_yaw_rate_radps = 1.25;
  const auto r = load_robot_description(models("miniugv.urdf"), mission);
  EXPECT_NEAR(r.limits.max_velocity_mps, 2.1, 1e-12);
  EXPECT_DOUBLE_EQ(r.limits.max_yaw_rate_radps, 1.25);
}

TEST(M100Model, RotorsDepthCameraAndWinch) {
  const auto r = load_robot_description(models("m100.urdf"));
  EXPECT_EQ(r.kind, RobotKind::kUav);
  EXPECT_DOUBLE_EQ(r.limits.max_velocity_mps, RobotMissionSettings{}.uav_limits.max_velocity_mps);
  // 650 mm motor to motor across the diagonal.
  const auto d = r.frame("rotor_front_left_link").translation() -
                 r.frame("rotor_rear_right_link").translation();
  EXPECT_NEAR(d.norm(), 0.65, 1e-9);
  int props = 0;
  for (const auto& s : r.collision_shapes)
    if (s.type == CollisionShape::Type::kCylinder && s.link.rfind("rotor", 0) == 0) {
      ++props;
      EXPECT_NEAR(s.radius_m, 13 * 0.0254 / 2, 1e-6);  // 13-inch propellers
    }
  EXPECT_EQ(props, 4);
  // The prop discs reach 0.325 + 0.1651 from the centre.
  EXPECT_NEAR(r.circumscribed_radius_m, 0.325 + 0.1651, 1e-5);

  const auto& depth = r.depth_camera();
  EXPECT_EQ(depth.name, "depth_camera");
  EXPECT_NEAR(depth.horizontal_fov_rad, 65 * kPi / 180, 1e-12);
  EXPECT_NEAR(depth.vertical_fov_rad * 180 / kPi, 39.43, 0.01);  // D415: ~65 x 40 deg
  EXPECT_EQ(depth.image_width_px, 1280);
  EXPECT_EQ(depth.image_height_px, 720);
  EXPECT_DOUBLE_EQ(depth.range_min_m, 0.3);
  EXPECT_DOUBLE_EQ(depth.range_max_m, 10.0);
  expect_vec(depth.X_BS.linear().col(0), {0, 0, -1});  // looks straight down

  const auto& marker = r.marker_camera();
  EXPECT_FALSE(marker.depth);
  // Forward, pitched 30 deg down.
  expect_vec(marker.X_BS.linear().col(0), {std::cos(kPi / 6), 0, -std::sin(kPi / 6)});

  ASSERT_TRUE(r.winch_spool);
  expect_vec(r.winch_spool->X_BF.linear().col(2), {0, 1, 0});  // spool axis along y
  ASSERT_EQ(r.tether_attachments.size(), 1u);
  // 20 mm along the rotated spool frame's y, which is B's -z: below the spool axis.
  expect_vec(r.tether_attachments[0].X_BF.translation(), {0, 0.04, -0.09});
}

// ---------------------------------------------------------------- kinematics, geometry

TEST(RobotDescription, ComposesJointOriginsThroughTheTree) {
  const auto r = from(R"(<robot name="chain">
    <link name="a"/>
    <link name="b"/>
    <link name="c"><collision><origin xyz="0 0 1"/><geometry><sphere radius="0.5"/></geometry></collision></link>
    <joint name="ab" type="revolute"><parent link="a"/><child link="b"/>
      <origin xyz="1 0 0" rpy="0 0 1.5707963267948966"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <joint name="bc" type="fixed"><parent link="b"/><child link="c"/><origin xyz="1 0 0"/></joint>
  </robot>)");
  EXPECT_EQ(r.base_link, "a");
  // X_Bb = T(1,0,0) Rz(90); b's x axis is B's y, so c sits at (1, 1, 0) and its shape 1 m above.
  expect_vec(r.frame("c").translation(), {1, 1, 0});
  ASSERT_EQ(r.collision_shapes.size(), 1u);
  expect_vec(r.collision_shapes[0].X_BS.translation(), {1, 1, 1});
  expect_vec(r.bounding_box_B.min(), {0.5, 0.5, 0.5});
  expect_vec(r.bounding_box_B.max(), {1.5, 1.5, 1.5});
  EXPECT_EQ(r.kind, RobotKind::kUav);  // no wheels
}

TEST(CollisionShape, CylinderBoundingBoxFollowsItsAxis) {
  CollisionShape c;
  c.type = CollisionShape::Type::kCylinder;
  c.radius_m = 0.5;
  c.length_m = 4.0;
  c.X_BS = Pose3(Eigen::AngleAxisd(kPi / 2, Eigen::Vector3d::UnitY()));  // axis along x
  expect_vec(c.aabb_B().max(), {2.0, 0.5, 0.5});
  c.X_BS = Pose3(Eigen::AngleAxisd(kPi / 4, Eigen::Vector3d::UnitY()));  // axis tilted 45 deg in xz
  // |a_x| L/2 + r sqrt(1 - a_x^2) = 0.7071 * 2 + 0.5 * 0.7071
  const double h = std::sqrt(0.5) * 2.0 + 0.5 * std::sqrt(0.5);
  expect_vec(c.aabb_B().max(), {h, 0.5, h});
}

TEST(CollisionShape, PlanarReach) {
  CollisionShape box;
  box.box_size_m = {2.0, 1.0, 1.0};
  box.X_BS = Pose3(Eigen::Translation3d(1, 0, 0));
  EXPECT_NEAR(box.xy_reach_m(), std::hypot(2.0, 0.5), 1e-12);
  CollisionShape cyl;
  cyl.type = CollisionShape::Type::kCylinder;
  cyl.radius_m = 1.0;
  cyl.length_m = 0.1;
  cyl.X_BS = Pose3(Eigen::Translation3d(3, 0, 0));
  EXPECT_NEAR(cyl.xy_reach_m(), 4.0, 1e-5);
  CollisionShape ball;
  ball.type = CollisionShape::Type::kSphere;
  ball.radius_m = 0.5;
  ball.X_BS = Pose3(Eigen::Translation3d(0, 2, 7));
  EXPECT_NEAR(ball.xy_reach_m(), 2.5, 1e-12);
}

// ---------------------------------------------------------------- sensors

TEST(Sensors, UrdfdomSensorElementWithParentAttribute) {
  // urdfdom 3.0's own parser wants parent_link_name; the ROS wiki a <parent> child.
  const auto r = from(robot_xml(R"(
    <sensor name="cam" update_rate="10" parent_link_name="sensor_link">
      <origin xyz="0 0 0.01" rpy="0 0.5 0"/>
      <camera><image width="320" height="320" hfov="1.2" format="L8" near="0.1" far="3"/></camera>
    </sensor>)"));
  const auto& c = r.camera("cam");
  EXPECT_EQ(c.link, "sensor_link");
  EXPECT_DOUBLE_EQ(c.horizontal_fov_rad, 1.2);
  EXPECT_DOUBLE_EQ(c.vertical_fov_rad, 1.2);  // square image
  EXPECT_DOUBLE_EQ(c.update_rate_hz, 10.0);
  expect_vec(c.X_BS.translation(), {0.1, 0, 0.03});
  expect_vec(c.X_BS.linear().col(0), {std::cos(0.5), 0, -std::sin(0.5)});
  expect_vec(r.frame("cam").translation(), {0.1, 0, 0.03});
}

TEST(Sensors, UrdfdomRayWithRangeExtension) {
  const auto r = from(robot_xml(R"(
    <sensor name="ir_a"><parent link="sensor_link"/>
      <ray><horizontal samples="5" min_angle="-0.2" max_angle="0.2"/><range min="0.1" max="2.5"/></ray>
    </sensor>)"));
  const auto* s = r.find_range_sensor("ir_a");
  ASSERT_NE(s, nullptr);
  EXPECT_EQ(s->samples, 5);
  EXPECT_NEAR(s->fov_rad(), 0.4, 1e-12);
  EXPECT_NEAR(s->beam_angle_rad(0), -0.2, 1e-12);
  EXPECT_NEAR(s->beam_angle_rad(1), -0.1, 1e-12);
  EXPECT_NEAR(s->beam_angle_rad(4), 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(s->range_max_m, 2.5);
}

TEST(Sensors, GazeboBlocksWithPose) {
  const auto r = from(robot_xml(R"(
    <gazebo reference="sensor_link">
      <sensor type="depth" name="d">
        <ferret role="depth_camera"/>
        <pose>0 0 -0.01 0 1.5707963267948966 0</pose>
        <camera><horizontal_fov>1.0</horizontal_fov><image><width>200</width><height>100</height></image>
          <clip><near>0.2</near><far>8</far></clip></camera>
      </sensor>
      <sensor type="gpu_ray" name="lidar">
        <ray><scan><horizontal><samples>1</samples><min_angle>0</min_angle><max_angle>0</max_angle></horizontal></scan>
          <range><min>0.05</min><max>12</max></range></ray>
      </sensor>
    </gazebo>
    <gazebo reference="base_link"><material>Gazebo/Grey</material></gazebo>)"));
  const auto& d = r.depth_camera();
  EXPECT_TRUE(d.depth);
  EXPECT_NEAR(d.vertical_fov_rad, 2 * std::atan(std::tan(0.5) * 0.5), 1e-12);
  expect_vec(d.X_BS.translation(), {0.1, 0, 0.01});
  expect_vec(d.X_BS.linear().col(0), {0, 0, -1});
  const auto* lidar = r.find_range_sensor("lidar");
  ASSERT_NE(lidar, nullptr);
  EXPECT_EQ(lidar->fov_rad(), 0.0);  // a single beam
  EXPECT_EQ(lidar->beam_angle_rad(0), 0.0);
  EXPECT_THROW((void)r.ir_array(), InputError);  // no sensor with the role ir
}

TEST(Sensors, UrdfAndGazeboDeclarationsOfOneSensorMerge) {
  // urdfdom <sensor> gives the fov and image; the Gazebo block adds the type "depth".
  const auto r = from(robot_xml(R"(
    <sensor name="cam" parent_link_name="sensor_link">
      <camera><image width="640" height="480" hfov="1.5" near="0.3" far="6"/></camera>
    </sensor>
    <gazebo reference="sensor_link"><sensor type="depth" name="cam"><update_rate>30</update_rate>
      <camera><horizontal_fov>1.5</horizontal_fov></camera></sensor></gazebo>)"));
  ASSERT_EQ(r.cameras.size(), 1u);
  EXPECT_TRUE(r.cameras[0].depth);
  EXPECT_DOUBLE_EQ(r.cameras[0].update_rate_hz, 30.0);
  EXPECT_DOUBLE_EQ(r.cameras[0].range_max_m, 6.0);
}

TEST(Sensors, IrArrayAcrossTheRearWrapsAroundPi) {
  // Two rear IR sensors aimed at 170 and -170 deg, each +-10 deg: fov 40 deg around 180.
  const auto r = from(robot_xml(R"(
    <link name="l1"/><joint name="j1" type="fixed"><parent link="base_link"/><child link="l1"/>
      <origin rpy="0 0 2.9670597283903604"/></joint>
    <link name="l2"/><joint name="j2" type="fixed"><parent link="base_link"/><child link="l2"/>
      <origin rpy="0 0 -2.9670597283903604"/></joint>
    <sensor name="ir1" parent_link_name="l1"><ferret role="ir"/><ray><horizontal samples="2" min_angle="-0.17453292519943295"
      max_angle="0.17453292519943295"/><range min="0" max="3"/></ray></sensor>
    <sensor name="ir2" parent_link_name="l2"><ferret role="ir"/><ray><horizontal samples="2" min_angle="-0.17453292519943295"
      max_angle="0.17453292519943295"/><range min="0.1" max="2"/></ray></sensor>)"));
  const IrArray ir = r.ir_array();
  EXPECT_NEAR(ir.fov_rad, 40 * kPi / 180, 1e-9);
  EXPECT_NEAR(std::abs(ir.center_yaw_B_rad), kPi, 1e-9);
  EXPECT_EQ(ir.beams.size(), 4u);
  EXPECT_DOUBLE_EQ(ir.range_min_m, 0.1);  // the most restrictive of the two
  EXPECT_DOUBLE_EQ(ir.range_max_m, 2.0);
}

TEST(RobotDescription, MissingRolesAreNamedErrors) {
  const auto r = from(robot_xml(""));
  EXPECT_EQ(r.find_camera("front_camera"), nullptr);
  try {
    (void)r.camera("front_camera");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "t.urdf");
    EXPECT_NE(std::string(e.what()).find("front_camera"), std::string::npos);
  }
  EXPECT_THROW((void)r.depth_camera(), InputError);
  EXPECT_THROW((void)r.frame("nowhere"), InputError);
  EXPECT_FALSE(r.epm);
  EXPECT_TRUE(r.tether_attachments.empty());
}

// ---------------------------------------------------------------- YAML summary

TEST(RobotDescription, YamlSummaryReadsBackTheValues) {
  const auto r = load_robot_description(models("miniugv.urdf"));
  const YAML::Node y = YAML::Load(robot_description_to_yaml(r));
  EXPECT_EQ(y["name"].as<std::string>(), "miniugv");
  EXPECT_EQ(y["kind"].as<std::string>(), "ugv");
  EXPECT_DOUBLE_EQ(y["cameras"][0]["horizontal_fov_deg"].as<double>(), 90.0);
  EXPECT_NEAR(y["cameras"][0]["horizontal_fov_rad"].as<double>(), kPi / 2, 1e-9);
  EXPECT_DOUBLE_EQ(y["cameras"][0]["range_max_m"].as<double>(), 4.0);
  EXPECT_DOUBLE_EQ(y["ir_array"]["fov_deg"].as<double>(), 30.0);
  EXPECT_EQ(y["ir_array"]["beams"].as<int>(), 9);
  EXPECT_EQ(y["collision_shapes"].size(), r.collision_shapes.size());
  EXPECT_DOUBLE_EQ(y["bounding_box_m"]["size"][0].as<double>(), 0.13);
  EXPECT_DOUBLE_EQ(y["epm"]["X_BF"]["xyz_m"][0].as<double>(), -0.065);
  EXPECT_EQ(y["frames"]["front_camera"]["xyz_m"][2].as<double>(), 0.045);
}

TEST(FindModel, FindsShippedModelsAndNamesThePlacesTried) {
  EXPECT_TRUE(std::filesystem::is_regular_file(find_model("m100.urdf")));
  try {
    (void)find_model("no_such_robot.urdf");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("urdf/models/no_such_robot.urdf"), std::string::npos);
  }
}

}  // namespace
}  // namespace ferret

// ---------------------------------------------------------------- roles

namespace ferret {
namespace {

std::string rover() { return std::string(FERRET_SOURCE_DIR) + "/tests/data/robots/rover.urdf"; }

TEST(RoverModel, SensorsAndFramesComeFromTheirRolesNotTheirNames) {
  const auto r = load_robot_description(rover());
  const CameraSensor& cam = r.object_camera();
  EXPECT_EQ(cam.name, "cam_main");
  EXPECT_DOUBLE_EQ(cam.horizontal_fov_rad, 1.2);
  EXPECT_EQ(cam.image_width_px, 320);
  EXPECT_DOUBLE_EQ(cam.range_max_m, 3.0);
  // Two fans of +-10 deg aimed at +-15 deg: from -25 to +25 deg, 2 x 5 beams, 2.5 m.
  const IrArray ir = r.ir_array();
  EXPECT_NEAR(ir.fov_rad, 50 * kPi / 180, 1e-9);
  EXPECT_NEAR(ir.center_yaw_B_rad, 0.0, 1e-9);
  EXPECT_EQ(ir.beams.size(), 10u);
  EXPECT_DOUBLE_EQ(ir.range_max_m, 2.5);
  ASSERT_TRUE(r.epm);
  EXPECT_EQ(r.epm->name, "magnet");
  expect_vec(r.epm->X_BF.linear().col(0), {-1, 0, 0});
  ASSERT_EQ(r.tether_attachments.size(), 1u);
  EXPECT_EQ(r.tether_attachments[0].name, "tow_point");
  EXPECT_FALSE(r.imu);
  EXPECT_THROW((void)r.depth_camera(), InputError);  // a ground robot has none
  // 12.5 rad/s x 0.04 m caps the mission's 2 m/s.
  EXPECT_DOUBLE_EQ(r.limits.max_velocity_mps, 0.5);
}

TEST(RoverModel, GroundOffsetAndFootprintFollowTheCollisionGeometry) {
  const auto r = load_robot_description(rover());
  // Wheels: centres 0.03 m below B, radius 0.04: the lowest point is 0.07 m below B.
  EXPECT_NEAR(r.ground_offset_m, 0.07, 1e-12);
  const Eigen::AlignedBox2d f = r.footprint_B();
  // Body +-0.15 in x; wheels at y = +-0.115, 0.03 wide: +-0.13 in y.
  EXPECT_NEAR(f.min().x(), -0.15, 1e-12);
  EXPECT_NEAR(f.max().x(), 0.15, 1e-12);
  EXPECT_NEAR(f.min().y(), -0.13, 1e-12);
  EXPECT_NEAR(f.max().y(), 0.13, 1e-12);
  // The miniUGV's base frame is on the ground.
  EXPECT_NEAR(load_robot_description(models("miniugv.urdf")).ground_offset_m, 0.0, 1e-12);
}

TEST(RoverModel, ProvenanceNamesTheUrdfLinesAndTheMission) {
  const auto r = load_robot_description(rover());
  auto from = [&](const std::string& key) {
    const auto it = r.provenance.find(key);
    return it == r.provenance.end() ? std::string("(none)") : it->second;
  };
  // The role marker of cam_main is on line 38 of rover.urdf, its fov on line 41.
  EXPECT_EQ(from("roles.object_camera"), "urdf:" + rover() + ":38");
  EXPECT_EQ(from("cameras.cam_main.horizontal_fov"), "urdf:" + rover() + ":41");
  EXPECT_EQ(from("motion_limits.max_velocity_mps").rfind("urdf:" + rover() + ":", 0), 0u)
      << from("motion_limits.max_velocity_mps");
  EXPECT_EQ(from("motion_limits.max_yaw_rate_radps"), "default");
  const RobotMissionSettings mission = test::robot_mission_from_yaml(
      "ugv_limits: {max_yaw_rate_radps: 1.5, max_velocity_mps: 0.3}", "m.yaml");
  const auto m = load_robot_description(rover(), mission);
  EXPECT_EQ(m.provenance.at("motion_limits.max_yaw_rate_radps"), "mission:m.yaml");
  // The mission's 0.3 m/s is below the wheels' 0.5: the mission's value holds.
  EXPECT_DOUBLE_EQ(m.limits.max_velocity_mps, 0.3);
  EXPECT_EQ(m.provenance.at("motion_limits.max_velocity_mps"), "mission:m.yaml");
}

TEST(Roles, TheMissionNamesSensorsForRolesAndOverridesMarkers) {
  const std::string sensors = R"(
    <sensor name="c1" parent_link_name="sensor_link">
      <camera><image width="100" height="100" hfov="1.0" near="0.1" far="2"/></camera></sensor>
    <sensor name="r1" parent_link_name="sensor_link"><ferret role="ir"/>
      <ray><horizontal samples="3" min_angle="-0.1" max_angle="0.1"/><range min="0" max="1.5"/></ray></sensor>
    <sensor name="r2" parent_link_name="sensor_link">
      <ray><horizontal samples="2" min_angle="-0.3" max_angle="0.3"/><range min="0" max="1"/></ray></sensor>)";
  const auto plain = from(robot_xml(sensors));
  EXPECT_EQ(plain.find_object_camera(), nullptr);  // no marker, no mission: no role
  EXPECT_EQ(plain.ir_array().beams.size(), 3u);

  const RobotMissionSettings mission = test::robot_mission_from_yaml(
      "roles: {t: {object_camera: c1, ir: [r2], epm: sensor_link}, other: {ir: x}}", "m.yaml");
  const auto r = from(robot_xml(sensors), mission);
  EXPECT_EQ(r.object_camera().name, "c1");
  EXPECT_EQ(r.provenance.at("roles.object_camera"), "mission:m.yaml");
  // The mission's ir replaces r1's marker.
  const IrArray ir = r.ir_array();
  EXPECT_EQ(ir.beams.size(), 2u);
  EXPECT_NEAR(ir.fov_rad, 0.6, 1e-12);
  EXPECT_DOUBLE_EQ(ir.range_max_m, 1.0);
  ASSERT_TRUE(r.epm);
  EXPECT_EQ(r.epm->name, "sensor_link");
}

TEST(Roles, AMissingRoleNamesTheUrdfTheRoleAndHowToDeclareIt) {
  const auto r = from(robot_xml(""));
  try {
    (void)r.object_camera();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "t.urdf");
    EXPECT_EQ(e.field(), "role[object_camera]");
    EXPECT_NE(e.expected().find("<ferret role=\"object_camera\"/>"), std::string::npos);
    EXPECT_NE(e.expected().find("roles: {t: {object_camera: NAME}}"), std::string::npos);
  }
  try {
    (void)r.ir_array();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "role[ir]");
  }
  EXPECT_THROW((void)r.marker_camera(), InputError);
  EXPECT_FALSE(r.has_ir());
}

TEST(Roles, OldNameConventionsNoLongerGiveRoles) {
  // A sensor named front_camera and ray sensors named ir_* without markers play no role.
  const auto r = from(robot_xml(R"(
    <sensor name="front_camera" parent_link_name="sensor_link">
      <camera><image width="100" height="100" hfov="1.0" near="0.1" far="2"/></camera></sensor>
    <sensor name="ir_a" parent_link_name="sensor_link">
      <ray><horizontal samples="3" min_angle="-0.1" max_angle="0.1"/><range min="0" max="1.5"/></ray></sensor>
    <link name="epm_link"/><joint name="e" type="fixed"><parent link="base_link"/><child link="epm_link"/></joint>)"));
  EXPECT_EQ(r.find_object_camera(), nullptr);
  EXPECT_FALSE(r.has_ir());
  EXPECT_FALSE(r.epm);
}

TEST(Roles, ShippedModelsCarryEveryRoleTheirConsumersNeed) {
  const auto ugv = load_robot_description(models("miniugv.urdf"));
  EXPECT_EQ(ugv.object_camera().name, "front_camera");
  EXPECT_EQ(ugv.ir_array().beams.size(), 9u);
  EXPECT_TRUE(ugv.epm && ugv.imu);
  const auto uav = load_robot_description(models("m100.urdf"));
  EXPECT_EQ(uav.marker_camera().name, "marker_camera");
  EXPECT_TRUE(uav.depth_camera().depth);
  EXPECT_TRUE(uav.winch_spool);
  EXPECT_EQ(uav.tether_attachments.size(), 1u);
}

TEST(LoadRobot, ShippedNamesAndPathsGiveTheSameDescription) {
  const auto by_name = load_robot("miniugv");
  const auto by_file = load_robot(models("miniugv.urdf"));
  EXPECT_EQ(by_name.name, "miniugv");
  EXPECT_EQ(by_file.object_camera().image_width_px, by_name.object_camera().image_width_px);
  EXPECT_EQ(load_robot(rover()).name, "rover");
  EXPECT_THROW((void)load_robot("/no/such/robot.urdf"), InputError);
}

}  // namespace
}  // namespace ferret
