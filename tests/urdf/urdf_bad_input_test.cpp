// Every way a URDF can be wrong ends in one InputError naming the file (with the line
// of the offending element), the element and what was expected; urdfdom's own
// console output never reaches the user.

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "urdf/robot_mission_yaml.hpp"

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
         "<link name=\"base_link\"><collision><geometry><box size=\"0.1 0.1 "
         "0.1\"/></geometry></collision></link>\n"
         "<link name=\"cam_link\"/>\n"
         "<joint name=\"cam_joint\" type=\"fixed\"><parent link=\"base_link\"/><child "
         "link=\"cam_link\"/></joint>\n" +
         body + "\n</robot>\n";
}
// Line of the first line of `body` in robot(body).
constexpr int kBodyLine = 6;

std::string gazebo_camera(const std::string& camera) {
  return "<gazebo reference=\"cam_link\"><sensor type=\"camera\" name=\"cam\">" + camera +
         "</sensor></gazebo>";
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
  EXPECT_EQ(f.source, "bad.urdf");
  EXPECT_EQ(f.field, "line 3 column 9");  // the "</robot>" that closes nothing open
  EXPECT_EQ(f.expected, "an end tag matching the open element");
}

TEST(UrdfBadInput, RootMustBeRobot) {
  const auto f = load_failure("<sdf version=\"1.6\"><model name=\"x\"/></sdf>");
  EXPECT_EQ(f.expected, "a <robot> root element");
  EXPECT_NE(f.what.find("<sdf>"), std::string::npos);
}

TEST(UrdfBadInput, JointNamingAMissingLink) {
  const auto f =
      load_failure(robot("<joint name=\"j\" type=\"fixed\"><parent link=\"base_link\"/><child "
                         "link=\"ghost\"/></joint>"));
  EXPECT_EQ(f.source, "bad.urdf:" + std::to_string(kBodyLine));
  EXPECT_EQ(f.field, "joint[j]/child@link");
  EXPECT_EQ(f.expected, "the name of a <link> in this file");
  EXPECT_NE(f.what.find("'ghost'"), std::string::npos);
}

std::string shape(const std::string& geometry) {
  return robot("<link name=\"s\"><collision><geometry>" + geometry +
               "</geometry></collision></link>");
}

std::string ray(const std::string& scan, const std::string& range) {
  return robot(
      "<gazebo reference=\"cam_link\"><sensor type=\"ray\" name=\"ir\"><ray><scan><horizontal>" +
      scan + "</horizontal></scan>" + range + "</ray></sensor></gazebo>");
}
const std::string kGoodScan =
    "<samples>3</samples><min_angle>-0.1</min_angle><max_angle>0.1</max_angle>";
const std::string kGoodRange = "<range><min>0.1</min><max>2</max></range>";

std::string camera_clip(const std::string& hfov, const std::string& near, const std::string& far) {
  return robot(gazebo_camera("<camera><horizontal_fov>" + hfov + "</horizontal_fov>" + kGoodImage +
                             "<clip><near>" + near + "</near><far>" + far +
                             "</far></clip></camera>"));
}

/// One bad URDF, the field the error must name and a part of what it must expect.
struct BadCase {
  std::string what, xml, field, expected_part;
};

TEST(UrdfBadInput, EachBadValueNamesItsElement) {
  const std::string cam = "gazebo[cam_link]/sensor[cam]/camera/";
  const std::string ir = "gazebo[cam_link]/sensor[ir]/ray/";
  const BadCase cases[] = {
      {"negative box", shape("<box size=\"0.1 -0.2 0.3\"/>"),
       "link[s]/collision[0]/geometry/box@size", "3 numbers > 0 and <= 1000 (metres)"},
      {"zero box", shape("<box size=\"0.1 0 0.3\"/>"), "link[s]/collision[0]/geometry/box@size",
       "> 0"},
      {"short box", shape("<box size=\"0.1 0.3\"/>"), "link[s]/collision[0]/geometry/box@size",
       "3 numbers"},
      {"sizeless box", shape("<box/>"), "link[s]/collision[0]/geometry/box@size", "3 numbers"},
      {"zero radius", shape("<cylinder radius=\"0\" length=\"1\"/>"),
       "link[s]/collision[0]/geometry/cylinder@radius", "a number > 0 and <= 1000 (metres)"},
      {"negative length", shape("<cylinder radius=\"0.1\" length=\"-1\"/>"),
       "link[s]/collision[0]/geometry/cylinder@length", "> 0"},
      {"negative sphere", shape("<sphere radius=\"-0.5\"/>"),
       "link[s]/collision[0]/geometry/sphere@radius", "> 0"},
      {"text radius", shape("<sphere radius=\"big\"/>"),
       "link[s]/collision[0]/geometry/sphere@radius", "> 0"},
      {"negative fov", camera_clip("-1", "0.1", "4"), cam + "horizontal_fov",
       "a horizontal fov in (0, pi) radians"},
      {"fov past pi", camera_clip("3.5", "0.1", "4"), cam + "horizontal_fov", "(0, pi)"},
      {"text fov", camera_clip("wide", "0.1", "4"), cam + "horizontal_fov", "a finite number"},
      {"negative far", camera_clip("1", "0.1", "-4"), cam + "clip/far", "> 0"},
      {"far before near", camera_clip("1", "5", "4"), cam + "clip/far",
       "clip far > clip near (5 m)"},
      {"negative near", camera_clip("1", "-0.1", "4"), cam + "clip/near", ">= 0"},
      {"zero width",
       robot("<sensor name=\"cam\" parent_link_name=\"cam_link\"><camera><image width=\"0\" "
             "height=\"10\" "
             "hfov=\"1\" near=\"0\" far=\"1\"/></camera></sensor>"),
       "sensor[cam]/camera/image@width", "an integer in [1, 100000]"},
      {"ray without range", ray(kGoodScan, ""), "gazebo[cam_link]/sensor[ir]/range_min",
       "required: <ray><range min=..> or Gazebo"},
      {"negative range max", ray(kGoodScan, "<range><min>0.1</min><max>-2</max></range>"),
       ir + "range/max", "> 0"},
      {"negative range min", ray(kGoodScan, "<range><min>-0.1</min><max>2</max></range>"),
       ir + "range/min", ">= 0"},
      {"negative ray fov",
       ray("<samples>3</samples><min_angle>0.1</min_angle><max_angle>-0.1</max_angle>", kGoodRange),
       ir + "scan/horizontal/max_angle", "fov > 0"},
      {"fractional samples",
       ray("<samples>2.5</samples><min_angle>-0.1</min_angle><max_angle>0.1</max_angle>",
           kGoodRange),
       ir + "scan/horizontal/samples", "an integer in [1, 1000000]"},
      {"sensor on a missing link",
       robot("<gazebo reference=\"nowhere\"><sensor type=\"imu\" name=\"imu\"/></gazebo>"),
       "gazebo[nowhere]/sensor[imu]", "a sensor on a <link> of this file"},
      {"sensor without parent", robot("<sensor name=\"cam\"><camera><image/></camera></sensor>"),
       "sensor[cam]/parent@link", "the link"},
      {"sensor without type", robot("<sensor name=\"cam\" parent_link_name=\"cam_link\"/>"),
       "sensor[cam]", "a <camera> or <ray> element"},
      {"sensor named like a link",
       robot("<gazebo reference=\"cam_link\"><sensor type=\"imu\" name=\"cam_link\"/></gazebo>"),
       "gazebo[cam_link]/sensor[cam_link]", "not also a link name"},
      {"two sensors of one name",
       robot("<gazebo reference=\"cam_link\"><sensor type=\"imu\" name=\"a\"/><sensor type=\"imu\" "
             "name=\"a\"/></gazebo>"),
       "gazebo[cam_link]/sensor[a]", "a unique sensor name"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const auto f = load_failure(c.xml);
    EXPECT_EQ(f.field, c.field) << f.what;
    EXPECT_NE(f.expected.find(c.expected_part), std::string::npos) << f.what;
    EXPECT_EQ(f.source.rfind("bad.urdf:", 0), 0u) << "no line number: " << f.source;
  }
}

TEST(UrdfBadInput, ErrorsPointAtTheLine) {
  EXPECT_EQ(load_failure(shape("<box size=\"1 1 -1\"/>")).source,
            "bad.urdf:" + std::to_string(kBodyLine));
  EXPECT_EQ(load_failure(camera_clip("1", "0.1", "-4")).source,
            "bad.urdf:" + std::to_string(kBodyLine));
}

TEST(UrdfBadInput, MissingMeshAndMalformedOrigin) {
  auto f =
      load_failure(robot("<link name=\"m\"><collision><geometry><mesh "
                         "filename=\"no_such_mesh.stl\"/></geometry></collision></link>"));
  EXPECT_EQ(f.source, "bad.urdf:" + std::to_string(kBodyLine));
  EXPECT_EQ(f.field, "link[m]/collision[0]/geometry/mesh@filename");
  EXPECT_NE(f.expected.find("a mesh file that exists"), std::string::npos) << f.expected;
  EXPECT_NE(f.what.find("no_such_mesh.stl"), std::string::npos) << f.what;
  f =
      load_failure(robot("<link name=\"m\"><collision><geometry><cone "
                         "radius=\"1\"/></geometry></collision></link>"));
  EXPECT_EQ(f.field, "link[m]/collision[0]/geometry");
  EXPECT_NE(f.expected.find("box, cylinder, sphere or mesh"), std::string::npos);
  f =
      load_failure(robot("<link name=\"o\"><collision><origin xyz=\"1 2\"/><geometry><sphere "
                         "radius=\"1\"/></geometry></collision></link>"));
  EXPECT_EQ(f.field, "link[o]/collision[0]/origin@xyz");
  EXPECT_EQ(f.expected, "3 numbers >= -1000 and <= 1000 (metres)");
}

TEST(UrdfBadInput, DuplicateLinkAndNoCollisionGeometry) {
  auto f = load_failure(robot("<link name=\"cam_link\"/>"));
  EXPECT_EQ(f.field, "link[cam_link]");
  f = load_failure("<robot name=\"x\"><link name=\"a\"/></robot>");
  EXPECT_EQ(f.expected, "at least one <collision> with a box, cylinder, sphere or mesh");
}

TEST(UrdfBadInput, TwoRootsAndBrokenVisualsAreNamedBeforeUrdfdom) {
  // Two roots: urdfdom's tree building noticed only on its console; ferret names the link.
  auto f = load_failure(robot("<link name=\"orphan\"/>"));
  EXPECT_EQ(f.source, "bad.urdf:" + std::to_string(kBodyLine));
  EXPECT_EQ(f.field, "link[orphan]");
  EXPECT_NE(f.expected.find("one root link"), std::string::npos) << f.what;
  // A <visual> without geometry made urdfdom drop the link's collisions silently.
  f = load_failure(
      "<robot name=\"r\">\n<link name=\"base_link\"><visual><origin/></visual><collision><geometry>"
      "<box size=\"1 1 1\"/></geometry></collision></link>\n</robot>");
  EXPECT_EQ(f.source, "bad.urdf:2");
  EXPECT_EQ(f.field, "link[base_link]/visual[0]/geometry");
  f = load_failure(
      "<robot name=\"r\">\n<link name=\"base_link\"><inertial><origin/></inertial><collision>"
      "<geometry><box size=\"1 1 1\"/></geometry></collision></link>\n</robot>");
  EXPECT_EQ(f.field, "link[base_link]/inertial/mass");
}

TEST(UrdfBadInput, CameraWithoutRange) {
  const auto f =
      load_failure(robot(gazebo_camera("<camera><horizontal_fov>1</horizontal_fov>" + kGoodImage +
                                       "<clip><near>0.1</near></clip></camera>")));
  EXPECT_EQ(f.source, "bad.urdf:" + std::to_string(kBodyLine));
  EXPECT_NE(f.field.find("gazebo[cam_link]/sensor[cam]"), std::string::npos);
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[cam]/clip_far");
  EXPECT_NE(f.expected.find("required: <image far=..> or Gazebo <clip><far>"), std::string::npos)
      << f.expected;
}

TEST(UrdfBadInput, ConflictingUrdfAndGazeboDeclarations) {
  const auto f =
      load_failure(robot("<sensor name=\"cam\" parent_link_name=\"cam_link\"><camera><image "
                         "width=\"640\" height=\"480\" hfov=\"1.5\" "
                         "near=\"0.1\" far=\"4\"/></camera></sensor>\n" +
                         gazebo_camera("<camera><horizontal_fov>1.2</horizontal_fov></camera>")));
  EXPECT_EQ(f.source, "bad.urdf:" + std::to_string(kBodyLine + 1));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[cam]/camera/horizontal_fov");
  EXPECT_NE(f.expected.find("sensor[cam]/camera/image@hfov"), std::string::npos) << f.expected;
}

// ---------------------------------------------------------------- roles

TEST(UrdfBadInput, UnknownRolesAndRolesInTheWrongPlace) {
  auto f = load_failure(
      robot(gazebo_camera("<ferret role=\"front_camera\"/><camera>"
                          "<horizontal_fov>1</horizontal_fov>" +
                          kGoodImage + "<clip><near>0.1</near><far>4</far></clip></camera>")));
  EXPECT_EQ(f.source, "bad.urdf:" + std::to_string(kBodyLine));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[cam]/ferret@role");
  EXPECT_NE(f.expected.find("one of object_camera, ir, marker_camera, depth_camera"),
            std::string::npos)
      << f.expected;
  // A frame role inside a sensor, a sensor role on a link.
  f = load_failure(robot(gazebo_camera("<ferret role=\"epm\"/>")));
  EXPECT_EQ(f.field, "gazebo[cam_link]/sensor[cam]/ferret@role");
  f = load_failure(robot("<link name=\"x\"><ferret role=\"object_camera\"/></link>"));
  EXPECT_EQ(f.field, "link[x]/ferret@role");
  EXPECT_NE(f.expected.find("sensor roles go inside the <sensor>"), std::string::npos);
}

TEST(UrdfBadInput, ARoleOnASensorOfTheWrongType) {
  const std::string clip = "<clip><near>0.1</near><far>4</far></clip>";
  // object_camera on a depth camera: a colour camera is needed.
  auto f =
      load_failure(robot("<gazebo reference=\"cam_link\"><sensor type=\"depth\" name=\"d\"><ferret "
                         "role=\"object_camera\"/><camera><horizontal_fov>1</horizontal_fov>" +
                         kGoodImage + clip + "</camera></sensor></gazebo>"));
  EXPECT_EQ(f.source, "bad.urdf:" + std::to_string(kBodyLine));
  EXPECT_EQ(f.field, "sensor[d]/role[object_camera]");
  EXPECT_EQ(f.expected, "a colour camera for the role object_camera");
  // depth_camera on a colour camera, ir on a camera.
  f =
      load_failure(robot(gazebo_camera("<ferret role=\"depth_camera\"/><camera><horizontal_fov>1"
                                       "</horizontal_fov>" +
                                       kGoodImage + clip + "</camera>")));
  EXPECT_EQ(f.expected, "a depth camera for the role depth_camera");
  f =
      load_failure(robot(gazebo_camera("<ferret role=\"ir\"/><camera><horizontal_fov>1"
                                       "</horizontal_fov>" +
                                       kGoodImage + clip + "</camera>")));
  EXPECT_EQ(f.expected, "a range (ray) sensor for the role ir");
}

TEST(UrdfBadInput, TwoSensorsForARoleThatTakesOne) {
  const std::string cam = "<camera><horizontal_fov>1</horizontal_fov>" + kGoodImage +
                          "<clip><near>0.1</near><far>4</far></clip></camera>";
  auto f = load_failure(
      robot("<gazebo reference=\"cam_link\"><sensor type=\"camera\" name=\"a\"><ferret "
            "role=\"object_camera\"/>" +
            cam +
            "</sensor>\n<sensor type=\"camera\" name=\"b\"><ferret "
            "role=\"object_camera\"/>" +
            cam + "</sensor></gazebo>"));
  EXPECT_EQ(f.source, "bad.urdf:" + std::to_string(kBodyLine + 1));
  EXPECT_EQ(f.field, "role[object_camera]");
  EXPECT_NE(f.what.find("also 'b'"), std::string::npos) << f.what;
}

TEST(UrdfBadInput, MissionRolesNamingNoSensorOrLinkOfTheUrdf) {
  const RobotMissionSettings mission =
      test::robot_mission_from_yaml("roles: {bad: {object_camera: nothing_here}}", "mission.yaml");
  try {
    (void)robot_description_from_string(robot(""), "bad.urdf", mission);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "mission.yaml");
    EXPECT_EQ(e.field(), "roles.bad.object_camera");
    EXPECT_NE(e.expected().find("the name of a sensor of bad.urdf"), std::string::npos) << e.what();
  }
  try {
    (void)robot_description_from_string(
        robot(""), "bad.urdf",
        test::robot_mission_from_yaml("roles: {bad: {epm: no_link}}", "mission.yaml"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "roles.bad.epm");
    EXPECT_NE(e.expected().find("one of base_link, cam_link"), std::string::npos) << e.what();
  }
}

TEST(UrdfBadInput, MissionRolesSectionIsChecked) {
  auto fails = [](const std::string& yaml, const std::string& field, const std::string& expect) {
    SCOPED_TRACE(yaml);
    try {
      (void)test::robot_mission_from_yaml(yaml, "mission.yaml");
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), "mission.yaml");
      EXPECT_EQ(e.field(), field);
      EXPECT_NE(e.expected().find(expect), std::string::npos) << e.what();
    }
  };
  fails("roles: {rover: {camera: cam}}", "roles.rover.camera", "a role: one of object_camera");
  fails("roles: {rover: cam}", "roles.rover", "a mapping of roles");
  fails("roles: {rover: {ir: []}}", "roles.rover.ir", "non-empty list");
  fails("roles: {rover: {ir: {a: 1}}}", "roles.rover.ir", "a list");
}

}  // namespace
}  // namespace ferret
