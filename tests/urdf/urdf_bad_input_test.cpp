// Every way a URDF can be wrong ends in one InputError naming the file (with the line
// of the offending element), the element and what was expected; urdfdom's own
// console output never reaches the user.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

struct Failure {
  std::string source, field, expected, what;
};

/// Loads `xml` as "bad.urdf"; returns the InputError's parts, failing the test if
/// loading succeeds or anything is printed to stderr.
Failure load_failure(const std::string& xml) {
  testing::internal::CaptureStderr();
  Failure f;
  bool threw = false;
  try {
    (void)robot_description_from_string(xml, "bad.urdf");
  } catch (const InputError& e) {
    threw = true;
    f = {e.source(), e.field(), e.expected(), e.what()};
  }
  const std::string printed = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(threw) << "no InputError for:\n" << xml;
  EXPECT_EQ(printed, "") << "the loader printed to the console";
  EXPECT_EQ(f.what.find('\n'), std::string::npos) << "message is not one line: " << f.what;
  return f;
}

std::string robot(const std::string& body) {
  return "<?xml version=\"1.0\"?>\n<robot name=\"bad\">\n"
         "<link name=\"base_link\"><collision><geometry><box size=\"0.1 0.1 0.1\"/></geometry></collision></link>\n"
         "<link name=\"cam_link\"/>\n"
         "<joint name=\"cam_joint\" type=\"fixed\"><parent link=\"base_link\"/><child link=\"cam_link\"/></joint>\n" +
         body + "\n</robot>\n";
}
// Line of the first line of `body` in robot(body).
constexpr int kBodyLine = 6;

std::string gazebo_camera(const std::string& camera) {
  return "<gazebo reference=\"cam_link\"><sensor type=\"camera\" name=\"cam\">" + camera + "</sensor></gazebo>";
}
const std::string kGoodImage = "<image><width>640</width><height>480</height></image>";

TEST(UrdfBadInput, MissingFile) {
  try {
    (void)load_robot_description("/nonexistent/robot.urdf");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "/nonexistent/robot.urdf");
    EXPECT_EQ(e.expected(), "a readable URDF file");
  }
}

TEST(UrdfBadInput, MalformedXmlNamesTheLine) {
  const auto f = load_failure("<robot name=\"x\">\n<link name=\"a\">\n</robot>\n");
  EXPECT_EQ(f.source, "bad.urdf:3");
  EXPECT_EQ(f.field, "xml");
  EXPECT_EQ(f.expected, "well-formed XML");
}

TEST(UrdfBadInput, RootMustBeRobot) {
  const auto f = load_failure("<sdf version=\"1.6\"><model name=\"x\"/></sdf>");
  EXPECT_EQ(f.expected, "a <robot> root element");
  EXPECT_NE(f.what.find("<sdf>"), std::string::npos);
}

TEST(UrdfBadInput, JointNamingAMissingLink) {
  const auto f = load_failure(robot(
      "<joint name=\"j\" type=\"fixed\"><parent link=\"base_link\"/><child link=\"ghost\"/></joint>"));
  EXPECT_EQ(f.source, "bad.urdf:" + std::to_string(kBodyLine));
  EXPECT_EQ(f.field, "joint[j]/child@link");
  EXPECT_EQ(f.expected, "the name of a <link> in this file");
  EXPECT_NE(f.what.find("'ghost'"), std::string::npos);
}

TEST(UrdfBadInput, NegativeAndZeroSizes) {
  auto shape = [](const std::string& geometry) {
    return robot("<link name=\"s\"><collision><geometry>" + geometry + "</geometry></collision></link>");
  };
  auto f = load_failure(shape("<box size=\"0.1 -0.2 0.3\"/>"));
  EXPECT_EQ(f.field, "link[s]/collision[0]/geometry/box@size");
  EXPECT_EQ(f.expected, "3 numbers > 0 (metres)");
  EXPECT_EQ(f.source, "bad.urdf:" + std::to_string(kBodyLine));
  f = load_failure(shape("<box size=\"0.1 0 0.3\"/>"));
  EXPECT_EQ(f.field, "link[s]/collision[0]/geometry/box@size");
  f = load_failure(shape("<box size=\"0.1 0.3\"/>"));
  EXPECT_EQ(f.field, "link[s]/collision[0]/geometry/box@size");
  f = load_failure(shape("<box/>"));
  EXPECT_EQ(f.field, "link[s]/collision[0]/geometry/box@size");
  f = load_failure(shape("<cylinder radius=\"0\" length=\"1\"/>"));
  EXPECT_EQ(f.field, "link[s]/collision[0]/geometry/cylinder@radius");
  EXPECT_EQ(f.expected, "a number > 0 (metres)");
  f = load_failure(shape("<cylinder radius=\"0.1\" length=\"-1\"/>"));
  EXPECT_EQ(f.field, "link[s]/collision[0]/geometry/cylinder@length");
  f = load_failure(shape("<sphere radius=\"-0.5\"/>"));
  EXPECT_EQ(f.field, "link[s]/collision[0]/geometry/sphere@radius");
  f = load_failure(shape("<sphere radius=\"big\"/>"));
  EXPECT_NE(f.what.find("'big'"), std::string::npos);
}

TEST(UrdfBadInput, MeshCollisionAndMalformedOrigin) {
  auto f = load_failure(robot(
      "<link name=\"m\"><collision><geometry><mesh filename=\"m.stl\"/></geometry></collision></link>"));
  EXPECT_EQ(f.field, "link[m]/collision[0]/geometry");
  EXPECT_NE(f.expected.find("box, cylinder or sphere"), std::string::npos);
  f = load_failure(robot(
      "<link name=\"o\"><collision><origin xyz=\"1 2\"/><geometry><sphere radius=\"1\"/></geometry></collision></link>"));
  EXPECT_EQ(f.field, "link[o]/collision[0]/origin@xyz");
  EXPECT_EQ(f.expected, "three numbers");
}

TEST(UrdfBadInput, DuplicateLinkAndNoCollisionGeometry) {
  auto f = load_failure(robot("<link name=\"cam_link\"/>"));
  EXPECT_EQ(f.field, "link[cam_link]");
  f = load_failure("<robot name=\"x\"><link name=\"a\"/></robot>");
  EXPECT_EQ(f.expected, "at least one <collision> with a box, cylinder or sphere");
}

TEST(UrdfBadInput, UrdfdomRejectionIsCapturedIntoOneLine) {
  // Two roots: only urdfdom's tree building notices; its console message becomes the "got".
  const auto f = load_failure(robot("<link name=\"orphan\"/>"));
  EXPECT_EQ(f.source, "bad.urdf");
  EXPECT_EQ(f.field, "robot");
  EXPECT_EQ(f.expected, "a URDF that urdfdom accepts");
  EXPECT_NE(f.what.find("urdfdom:"), std::string::npos) << f.what;
}

TEST(UrdfBadInput, CameraWithoutRange) {
  const auto f = load_failure(robot(gazebo_camera("<camera><horizontal_fov>1</horizontal_fov>" + kGoodImage +
                                                  "<clip><near>0.1</near></clip></camera>")));
  EXPECT_EQ(f.source, "bad.urdf:" + std::to_string(kBodyLine));
  EXPECT_NE(f.field.find("gazebo[cam_link]/sensor[cam]"), std::string::npos);
  EXPECT_NE(f.field.find("clip far"), std::string::npos);
  EXPECT_NE(f.expected.find("(required)"), std::string::npos);
}

TEST(UrdfBadInput, CameraWithBadFovOrRange) {
  auto f = load_failure(robot(gazebo_camera("<camera><horizontal_fov>-1</horizontal_fov>" + kGoodImage +
                                            "<clip><near>0.1</near><far>4</far></clip></camera>")));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[cam]/camera/horizontal_fov");
  EXPECT_EQ(f.expected, "a horizontal fov in (0, pi) radians");
  f = load_failure(robot(gazebo_camera("<camera><horizontal_fov>3.5</horizontal_fov>" + kGoodImage +
                                       "<clip><near>0.1</near><far>4</far></clip></camera>")));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[cam]/camera/horizontal_fov");
  f = load_failure(robot(gazebo_camera("<camera><horizontal_fov>1</horizontal_fov>" + kGoodImage +
                                       "<clip><near>0.1</near><far>-4</far></clip></camera>")));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[cam]/camera/clip/far");
  f = load_failure(robot(gazebo_camera("<camera><horizontal_fov>1</horizontal_fov>" + kGoodImage +
                                       "<clip><near>5</near><far>4</far></clip></camera>")));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[cam]/camera/clip/far");
  EXPECT_NE(f.expected.find("clip near"), std::string::npos);
  f = load_failure(robot(gazebo_camera("<camera><horizontal_fov>wide</horizontal_fov>" + kGoodImage +
                                       "<clip><near>0.1</near><far>4</far></clip></camera>")));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[cam]/camera/horizontal_fov");
  EXPECT_EQ(f.expected, "a number");
  f = load_failure(robot(
      "<sensor name=\"cam\" parent_link_name=\"cam_link\"><camera><image width=\"0\" height=\"10\" hfov=\"1\" "
      "near=\"0\" far=\"1\"/></camera></sensor>"));
  EXPECT_EQ(f.field, "sensor[cam]/camera/image@width");
}

TEST(UrdfBadInput, RaySensorWithBadRangeOrFov) {
  auto ray = [](const std::string& scan, const std::string& range) {
    return robot("<gazebo reference=\"cam_link\"><sensor type=\"ray\" name=\"ir\"><ray><scan><horizontal>" + scan +
                 "</horizontal></scan>" + range + "</ray></sensor></gazebo>");
  };
  const std::string good_scan = "<samples>3</samples><min_angle>-0.1</min_angle><max_angle>0.1</max_angle>";
  auto f = load_failure(ray(good_scan, ""));
  EXPECT_NE(f.field.find("range min"), std::string::npos);
  f = load_failure(ray(good_scan, "<range><min>0.1</min><max>-2</max></range>"));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[ir]/ray/range/max");
  f = load_failure(ray(good_scan, "<range><min>-0.1</min><max>2</max></range>"));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[ir]/ray/range/min");
  f = load_failure(ray("<samples>3</samples><min_angle>0.1</min_angle><max_angle>-0.1</max_angle>",
                       "<range><min>0.1</min><max>2</max></range>"));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[ir]/ray/scan/horizontal/max_angle");
  EXPECT_NE(f.expected.find("fov > 0"), std::string::npos);
  f = load_failure(ray("<samples>2.5</samples><min_angle>-0.1</min_angle><max_angle>0.1</max_angle>",
                       "<range><min>0.1</min><max>2</max></range>"));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[ir]/ray/scan/horizontal/samples");
}

TEST(UrdfBadInput, SensorPlacementAndNames) {
  auto f = load_failure(robot("<gazebo reference=\"nowhere\"><sensor type=\"imu\" name=\"imu\"/></gazebo>"));
  EXPECT_EQ(f.field, "gazebo[nowhere]/sensor[imu]");
  EXPECT_EQ(f.expected, "a sensor on a <link> of this file");
  f = load_failure(robot("<sensor name=\"cam\"><camera><image/></camera></sensor>"));
  EXPECT_EQ(f.field, "sensor[cam]/parent@link");
  f = load_failure(robot("<sensor name=\"cam\" parent_link_name=\"cam_link\"/>"));
  EXPECT_EQ(f.expected, "a <camera> or <ray> element");
  f = load_failure(robot("<gazebo reference=\"cam_link\"><sensor type=\"imu\" name=\"cam_link\"/></gazebo>"));
  EXPECT_EQ(f.expected, "a sensor name that is not also a link name");
  f = load_failure(robot("<gazebo reference=\"cam_link\"><sensor type=\"imu\" name=\"a\"/><sensor type=\"imu\" "
                         "name=\"a\"/></gazebo>"));
  EXPECT_EQ(f.expected, "a unique sensor name");
}

TEST(UrdfBadInput, ConflictingUrdfAndGazeboDeclarations) {
  const auto f = load_failure(robot(
      "<sensor name=\"cam\" parent_link_name=\"cam_link\"><camera><image width=\"640\" height=\"480\" hfov=\"1.5\" "
      "near=\"0.1\" far=\"4\"/></camera></sensor>\n" +
      gazebo_camera("<camera><horizontal_fov>1.2</horizontal_fov></camera>")));
  EXPECT_EQ(f.source, "bad.urdf:" + std::to_string(kBodyLine + 1));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[cam]/camera/horizontal_fov");
  EXPECT_NE(f.expected.find("sensor[cam]/camera/image@hfov"), std::string::npos) << f.expected;
}

}  // namespace
}  // namespace ferret
