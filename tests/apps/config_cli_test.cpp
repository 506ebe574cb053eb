// `ferret config --dump`: the effective configuration comes from the URDF and the
// mission YAML, and every bad input is one line naming file and field, exit code 2.

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/cli_runner.hpp"

namespace ferret::test {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_text(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

/// The shipped miniUGV model with `from` replaced by `to` (which must occur).
std::string edited_miniugv(const std::string& from, const std::string& to) {
  std::string xml = read_text(fs::path(FERRET_SOURCE_DIR) / "urdf/models/miniugv.urdf");
  const auto at = xml.find(from);
  EXPECT_NE(at, std::string::npos) << "model no longer contains " << from;
  if (at != std::string::npos) xml.replace(at, from.size(), to);
  return xml;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// The section of a dump from `key` to the next line at the same indentation, with its
/// final newline.
std::string section(const std::string& dump, const std::string& key) {
  const auto start = dump.find(key);
  if (start == std::string::npos) return {};
  const auto line_start = dump.rfind('\n', start) + 1;
  const std::string indent(start - line_start, ' ');
  auto end = dump.find("\n" + indent, start + key.size());
  while (end != std::string::npos && dump.size() > end + 1 + indent.size() &&
         dump[end + 1 + indent.size()] == ' ')
    end = dump.find("\n" + indent, end + 1);
  return dump.substr(
      start, end == std::string::npos ? std::string::npos : end - start + 1);  // with its '\n'
}

/// Checks the usual bad-input contract: exit 2, one line on stderr naming `file` and `field`.
void expect_bad_input(const CliResult& r, const std::string& file, const std::string& field) {
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "not one line:\n" << r.err;
  EXPECT_TRUE(contains(r.err, "ferret: error: ")) << r.err;
  EXPECT_TRUE(contains(r.err, file)) << r.err;
  EXPECT_TRUE(contains(r.err, field)) << r.err;
  EXPECT_TRUE(r.out.empty()) << "partial output on stdout:\n" << r.out;
}

TEST(ConfigCli, DumpShowsSensorsFromTheDefaultUrdfAndTheMission) {
  const auto r = run_cli("config --dump");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "source: urdf/models/miniugv.urdf")) << r.out;
  const std::string camera = section(r.out, "- name: front_camera");
  EXPECT_TRUE(contains(camera, "horizontal_fov_deg: 90\n")) << camera;
  EXPECT_TRUE(contains(camera, "horizontal_fov_rad: 1.570796327\n")) << camera;
  EXPECT_TRUE(contains(camera, "range_max_m: 4\n")) << camera;
  const std::string ir = section(r.out, "ir_array:");
  EXPECT_TRUE(contains(ir, "fov_deg: 30\n")) << ir;
  EXPECT_TRUE(contains(ir, "fov_rad: 0.523598776\n")) << ir;
  EXPECT_TRUE(contains(ir, "beams: 9\n")) << ir;
  EXPECT_TRUE(contains(ir, "range_max_m: 4\n")) << ir;
  EXPECT_TRUE(contains(r.out, "size: [0.13, 0.12, 0.055]")) << r.out;
  EXPECT_TRUE(contains(r.out, "source: \"config/mission.yaml\"")) << r.out;
  const std::string curiosity = section(r.out, "curiosity:");
  EXPECT_TRUE(contains(curiosity, "a: -0.5\n") && contains(curiosity, "b: 0.1\n") &&
              contains(curiosity, "K: 0.62"))
      << curiosity;
}

TEST(ConfigCli, ShippedModelByName) {
  const auto r = run_cli("config --dump --robot m100");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string depth = section(r.out, "- name: depth_camera");
  EXPECT_TRUE(contains(depth, "depth: true")) << depth;
  EXPECT_TRUE(contains(depth, "horizontal_fov_deg: 65\n")) << depth;
  EXPECT_TRUE(contains(depth, "image_px: [1280, 720]")) << depth;
  EXPECT_TRUE(contains(depth, "range_min_m: 0.3\n")) << depth;
  EXPECT_TRUE(contains(r.out, "kind: uav")) << r.out;
}

TEST(ConfigCli, ChangingTheUrdfChangesTheDump) {
  TempDir dir;
  const auto original = run_cli("config --dump --robot urdf/models/miniugv.urdf");
  ASSERT_EQ(original.exit_code, 0) << original.err;
  // Camera fov 90 -> 60 deg; one IR sensor's range 4 -> 2.5 m (the array takes the smallest).
  std::string xml = edited_miniugv("hfov=\"1.5707963267948966\"", "hfov=\"1.0471975511965976\"");
  const auto at = xml.find("<max>4.0</max>");
  ASSERT_NE(at, std::string::npos);
  xml.replace(at, 14, "<max>2.5</max>");
  write_text(dir / "robot.urdf", xml);
  const auto edited = run_cli("config --dump --robot '" + dir / "robot.urdf" + "'");
  ASSERT_EQ(edited.exit_code, 0) << edited.err;

  const std::string cam_before = section(original.out, "- name: front_camera");
  const std::string cam_after = section(edited.out, "- name: front_camera");
  EXPECT_TRUE(contains(cam_before, "horizontal_fov_deg: 90\n"));
  EXPECT_TRUE(contains(cam_after, "horizontal_fov_deg: 60\n")) << cam_after;
  EXPECT_TRUE(contains(cam_after, "horizontal_fov_rad: 1.047197551\n")) << cam_after;
  EXPECT_TRUE(contains(section(original.out, "ir_array:"), "range_max_m: 4\n"));
  EXPECT_TRUE(contains(section(edited.out, "ir_array:"), "range_max_m: 2.5\n")) << edited.out;
  // Nothing else moved: the collision geometry is the same.
  EXPECT_EQ(section(original.out, "collision_shapes:"), section(edited.out, "collision_shapes:"));
}

TEST(ConfigCli, MissionFileFeedsTheLimits) {
  TempDir dir;
  write_text(dir / "mission.yaml", "ugv_limits:\n  max_velocity_mps: 0.5\n");
  const auto r = run_cli("config --dump --config '" + dir / "mission.yaml" + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(section(r.out, "motion_limits:"), "max_velocity_mps: 0.5\n")) << r.out;
}

TEST(ConfigCli, TheUavMissionSectionShowsTheFilesValuesAndTheDefaults) {
  TempDir dir;
  write_text(dir / "mission.yaml", "uav:\n  search_altitude_m: 6.5\n  release: hover\n");
  const auto r = run_cli("config --dump --config '" + dir / "mission.yaml" + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string uav = section(r.out, "uav_mission:");
  EXPECT_TRUE(contains(uav, "search_altitude_m: 6.5\n")) << r.out;
  EXPECT_TRUE(contains(uav, "release: hover\n")) << r.out;
  EXPECT_TRUE(contains(uav, "passes: 2\n")) << r.out;     // a default
  EXPECT_FALSE(contains(uav, "search_area_m")) << r.out;  // the world's, not given
  write_text(dir / "bad.yaml", "uav:\n  passes: 0\n");
  const auto bad = run_cli("config --dump --config '" + dir / "bad.yaml" + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(contains(bad.err, "uav.passes")) << bad.err;
}

TEST(ConfigCli, TheUgvMissionSectionShowsTheFilesValuesWhereTheyCameFromAndReadsBack) {
  TempDir dir;
  write_text(dir / "mission.yaml",
             "ugv:\n  base: {backend: sim}\n  explore_timeout_s: 250\n  explore: {max_revisits: "
             "1}\n");
  const auto r = run_cli("config --dump --config '" + dir / "mission.yaml" + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string ugv = section(r.out, "ugv_mission:");
  EXPECT_TRUE(contains(ugv, "explore_timeout_s: 250\n")) << r.out;
  EXPECT_TRUE(contains(ugv, "max_revisits: 1\n")) << r.out;
  EXPECT_TRUE(contains(ugv, "grasp_attempts: 3\n")) << r.out;  // a default
  EXPECT_TRUE(contains(r.out, "explore.max_revisits, explore_timeout_s; the rest the defaults"))
      << r.out;
  // The section is a mission YAML's `ugv` section: it reads back, and dumps the same.
  write_text(dir / "again.yaml", "ugv:\n" + ugv.substr(ugv.find('\n') + 1));
  const auto again = run_cli("config --dump --config '" + dir / "again.yaml" + "'");
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(section(again.out, "ugv_mission:"), ugv);
  write_text(dir / "bad.yaml", "ugv:\n  grasp_attempts: 0\n");
  const auto bad = run_cli("config --dump --config '" + dir / "bad.yaml" + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(contains(bad.err, "ugv.grasp_attempts")) << bad.err;
}

TEST(ConfigCli, OutputFileIsWrittenWholeOrNotAtAll) {
  TempDir dir;
  const auto ok = run_cli("config --dump -o '" + dir / "effective.yaml" + "'");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(contains(read_text(dir / "effective.yaml"), "ir_array:"));
  write_text(dir / "bad.urdf", "<robot name=\"x\"><link name=\"a\">");
  const auto bad =
      run_cli("config --dump --robot '" + dir / "bad.urdf" + "' -o '" + dir / "second.yaml" + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "second.yaml"));
  EXPECT_EQ(dir.count(), 2u);  // effective.yaml and bad.urdf: no temporary left behind
}

TEST(ConfigCli, BadUrdfFiles) {
  TempDir dir;
  struct Case {
    std::string name, from, to, field;
  };
  const Case cases[] = {
      {"malformed.urdf", "</robot>", "</robt>", ": expected an end tag matching the open element"},
      {"missing_link.urdf", "<child link=\"imu_link\"/>", "<child link=\"imu_lnk\"/>",
       "joint[imu_joint]/child@link"},
      {"negative_size.urdf", "<box size=\"0.130 0.090 0.040\"/></geometry></collision>",
       "<box size=\"0.130 0.090 -0.040\"/></geometry></collision>",
       "link[chassis_link]/collision[0]/geometry/box@size"},
      {"zero_radius.urdf",
       "<collision><origin rpy=\"1.5707963267948966 0 0\"/><geometry><cylinder radius=\"0.020\"",
       "<collision><origin rpy=\"1.5707963267948966 0 0\"/><geometry><cylinder radius=\"0\"",
       "link[front_left_wheel_link]/collision[0]/geometry/cylinder@radius"},
      {"negative_range.urdf", "near=\"0.05\" far=\"4.0\"", "near=\"0.05\" far=\"-4.0\"",
       "sensor[front_camera]/camera/image@far"},
      {"missing_range.urdf",
       "<range><min>0.02</min><max>4.0</max><resolution>0.01</resolution></range>", "",
       "gazebo[ir_left_link]/sensor[ir_left]/range_min"},
      {"negative_fov.urdf", "hfov=\"1.5707963267948966\"", "hfov=\"-1.5707963267948966\"",
       "sensor[front_camera]/camera/image@hfov"},
      {"missing_fov.urdf", "hfov=\"1.5707963267948966\"", "",
       "sensor[front_camera]/horizontal_fov"},
      // A second root, named with its line (urdfdom told only its console).
      {"two_roots.urdf", "<link name=\"imu_link\"><ferret role=\"imu\"/></link>",
       "<link name=\"imu_link\"><ferret role=\"imu\"/></link><link name=\"orphan\"/>",
       "link[orphan]: expected one root link"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    write_text(dir / c.name, edited_miniugv(c.from, c.to));
    expect_bad_input(run_cli("config --dump --robot '" + dir / c.name + "'"), c.name, c.field);
  }
  expect_bad_input(run_cli("config --dump --robot '" + dir / "absent.urdf" + "'"), "absent.urdf",
                   "--robot: expected a URDF file, or a shipped model");
}

TEST(ConfigCli, BadMissionFiles) {
  TempDir dir;
  struct Case {
    std::string name, yaml, field;
  };
  const Case cases[] = {
      {"wrong_type.yaml", "object_search:\n  lambda1: high\n",
       "object_search.lambda1: expected a number in [0, 0.5] (got 'high')"},
      {"nan.yaml", "object_search:\n  lambda1: .nan\n",
       "object_search.lambda1: expected a number in [0, 0.5] (got '.nan')"},
      {"empty.yaml", "object_search:\n  lambda1:\n", "object_search.lambda1: expected a number in"},
      {"inf_entry.yaml", "tether:\n  entry_offset_m: .inf\n", "tether.entry_offset_m: expected"},
      {"unknown_key.yaml", "curiosty:\n  a: -0.5\n", "curiosty: expected a known key"},
      {"unknown_nested.yaml", "tether:\n  length_m: 3\n", "tether.length_m: expected a known key"},
      {"out_of_range.yaml", "object_search:\n  lambda2: 1.5\n",
       "object_search.lambda2: expected a number in [0.5, 1]"},
      {"negative_speed.yaml", "ugv_limits:\n  max_velocity_mps: -2\n",
       "ugv_limits.max_velocity_mps"},
      {"inconsistent.yaml", "tether:\n  total_length_m: 1\n  entry_offset_m: 2\n",
       "tether.entry_offset_m"},
      {"catch_not_bool.yaml", "tether:\n  catch_speed_limit: sometimes\n",
       "tether.catch_speed_limit: expected true or false"},
      {"stall_zero.yaml", "ugv:\n  base:\n    stall_time_s: 0\n",
       "ugv.base.stall_time_s: expected a number in [0.05, 10]"},
      {"syntax.yaml", "tether: [1, 2\n", "valid YAML"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    write_text(dir / c.name, c.yaml);
    expect_bad_input(run_cli("config --dump --config '" + dir / c.name + "'"), c.name, c.field);
  }
  expect_bad_input(run_cli("config --dump --config '" + dir / "absent.yaml" + "'"), "absent.yaml",
                   "a readable YAML file");
}

TEST(ConfigCli, WithoutDumpIsBadInput) {
  const auto r = run_cli("config");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(contains(r.err, "--dump")) << r.err;
}

TEST(ConfigCli, TheRoversValuesAndWhereTheyCameFrom) {
  const std::string rover = "tests/data/robots/rover.urdf";  // run_cli runs in the source tree
  TempDir dir;
  const std::string mission = dir / "mission.yaml";
  write_text(mission, "ugv_limits: {max_yaw_rate_radps: 1.5}\n");
  const std::string out = dir / "dump.yaml";
  const auto r = run_cli("config --dump --robot " + rover + " --mission " + mission + " -o " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const YAML::Node y = YAML::LoadFile(out);
  const YAML::Node robot = y["robot"];
  const YAML::Node cam = robot["cameras"][0];
  EXPECT_EQ(cam["name"].as<std::string>(), "cam_main");
  EXPECT_NEAR(cam["horizontal_fov_deg"].as<double>(), 68.754935, 1e-6);
  EXPECT_EQ(cam["image_px"][0].as<int>(), 320);
  EXPECT_DOUBLE_EQ(robot["ir_array"]["range_max_m"].as<double>(), 2.5);
  EXPECT_DOUBLE_EQ(robot["ir_array"]["fov_deg"].as<double>(), 50.0);
  EXPECT_DOUBLE_EQ(robot["motion_limits"]["max_velocity_mps"].as<double>(), 0.5);
  EXPECT_DOUBLE_EQ(robot["motion_limits"]["max_yaw_rate_radps"].as<double>(), 1.5);
  EXPECT_DOUBLE_EQ(robot["ground_offset_m"].as<double>(), 0.07);
  EXPECT_EQ(robot["roles"]["ir"].size(), 2u);

  const YAML::Node from = robot["provenance"];
  EXPECT_EQ(from["roles.object_camera"].as<std::string>(), "urdf:" + rover + ":38");
  EXPECT_EQ(from["cameras.cam_main.horizontal_fov"].as<std::string>(), "urdf:" + rover + ":41");
  EXPECT_EQ(from["cameras.cam_main.image_width_px"].as<std::string>(), "urdf:" + rover + ":42");
  EXPECT_EQ(from["range_sensors.range_l.range_max_m"].as<std::string>(), "urdf:" + rover + ":58");
  EXPECT_THAT(from["motion_limits.max_velocity_mps"].as<std::string>(),
              ::testing::StartsWith("urdf:" + rover + ":"));
  EXPECT_THAT(from["motion_limits.max_velocity_mps"].as<std::string>(),
              ::testing::HasSubstr("12.5 rad/s x wheel radius 0.04 m"));
  EXPECT_EQ(from["motion_limits.max_yaw_rate_radps"].as<std::string>(), "mission:" + mission);
  EXPECT_EQ(from["motion_limits.max_acceleration_mps2"].as<std::string>(), "default");
  const YAML::Node mission_from = y["mission"]["provenance"];
  EXPECT_EQ(mission_from["ugv_limits.max_yaw_rate_radps"].as<std::string>(), "mission:" + mission);
  EXPECT_EQ(mission_from["curiosity.K"].as<std::string>(), "default");

  // The old spellings --config and --output are hidden aliases of --mission and --out.
  const std::string old_out = dir / "old.yaml";
  const auto old =
      run_cli("config --dump --robot " + rover + " --config " + mission + " --output " + old_out);
  ASSERT_EQ(old.exit_code, 0) << old.err;
  EXPECT_EQ(read_text(old_out), read_text(out));
}

TEST(ConfigCli, MissionRolesNamingAMissingSensorAreBadInput) {
  TempDir dir;
  const std::string mission = dir / "mission.yaml";
  write_text(mission, "roles: {rover: {object_camera: no_such_camera}}\n");
  expect_bad_input(
      run_cli("config --dump --robot tests/data/robots/rover.urdf --mission " + mission), mission,
      "roles.rover.object_camera");
}

TEST(ConfigCli, BadMeshesAndRolesExitTwoNamingTheLine) {
  TempDir dir;
  // A mesh that is not there: the URDF line of the <mesh> and the path tried.
  const std::string missing = dir / "missing_mesh.urdf";
  write_text(missing, edited_miniugv("<collision><geometry><box size=\"0.130 0.090 0.040\"/>",
                                     "<collision><geometry><mesh filename=\"meshes/body.stl\"/>"));
  auto r = run_cli("config --dump --robot " + missing);
  expect_bad_input(r, missing + ":", "link[chassis_link]/collision[0]/geometry/mesh@filename");
  EXPECT_TRUE(contains(r.err, dir / "meshes/body.stl")) << r.err;
  // A corrupt one: assimp's refusal, one line.
  std::filesystem::create_directories(dir.path() / "meshes");
  write_text(dir / "meshes/body.stl",
             "solid nothing\nfacet normal 0 0 1\nouter loop\nvertex 1 2\n");
  r = run_cli("config --dump --robot " + missing);
  expect_bad_input(r, missing + ":", "a mesh file assimp can read");
  // A role on a sensor of the wrong type: depth_camera on an IR sensor.
  const std::string wrong = dir / "wrong_role.urdf";
  write_text(wrong,
             edited_miniugv(
                 "<sensor type=\"ray\" name=\"ir_left\">\n      <ferret role=\"ir\"/>",
                 "<sensor type=\"ray\" name=\"ir_left\">\n      <ferret role=\"depth_camera\"/>"));
  expect_bad_input(run_cli("config --dump --robot " + wrong), wrong + ":",
                   "sensor[ir_left]/role[depth_camera]: expected a depth camera");
}

TEST(ConfigCli, MissionKeyThatIsAListIsBadInput) {
  // YAML allows a list or a mapping as a key (`? [a]`); yaml-cpp's conversion error
  // escaped as exit 3 before (found by fuzz/mission_fuzz.cpp).
  TempDir dir;
  struct Case {
    std::string name, text, field;
  };
  const Case cases[] = {
      {"top.yaml", "? [curiosity]\n: {a: 1}\n", "(document)"},
      {"section.yaml", "curiosity:\n  ? [a]\n  : 1\n", "curiosity"},
      {"robot.yaml", "roles:\n  ? {miniugv: 1}\n  : {ir: ir0}\n", "roles"},
      {"role.yaml", "roles:\n  miniugv:\n    ? [ir]\n    : ir0\n", "roles.miniugv"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string mission = dir / c.name;
    write_text(mission, c.text);
    const std::string out = dir / ("dump_" + c.name);
    const auto r = run_cli("config --dump --mission '" + mission + "' -o '" + out + "'");
    expect_bad_input(r, mission, c.field + ": expected ");
    EXPECT_FALSE(fs::exists(out));
  }
  EXPECT_EQ(dir.count(), 4u);  // the inputs alone
}

TEST(ConfigCli, EveryInterfaceSaysItsBackendSimByDefault) {
  TempDir dir;
  write_text(dir / "mission.yaml", "tether: {total_length_m: 12}\n");
  const auto r = run_cli("config --dump --mission '" + dir / "mission.yaml" + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(contains(r.out,
                       "backends:\n  ugv:\n    base:\n      backend: sim\n      stall_time_s: 0.3\n"
                       "  uav:\n    winch:\n"
                       "      backend: sim\n    flight_controller:\n      backend: sim\n"))
      << r.out;
}

TEST(ConfigCli, AHwFileDumpsEachDeviceWithItsDefaultsFilledIn) {
  TempDir dir;
  write_text(dir / "robot.yaml",
             "ugv:\n  base: {backend: hw, serial: {port: /dev/ttyAMA0}, camera: {device: '0'}}\n"
             "uav:\n  flight_controller: {backend: hw, address: '127.0.0.1:47820'}\n");
  const auto r = run_cli("config --dump --mission '" + dir / "robot.yaml" + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string base = section(r.out, "base:");
  EXPECT_TRUE(contains(base, "backend: hw\n")) << base;
  EXPECT_TRUE(contains(base, "port: /dev/ttyAMA0\n")) << base;
  EXPECT_TRUE(contains(base, "baud: 115200\n")) << base;  // the default, printed
  EXPECT_TRUE(contains(base, "track_width_m: 0.105\n")) << base;
  EXPECT_TRUE(contains(section(r.out, "winch:"), "backend: sim\n")) << r.out;
  EXPECT_TRUE(contains(section(r.out, "flight_controller:"), "address: 127.0.0.1:47820\n"))
      << r.out;
}

TEST(ConfigCli, BadBackendsExitTwoNamingFileAndField) {
  TempDir dir;
  struct Case {
    std::string name, text, field;
  };
  const Case cases[] = {
      {"unknown.yaml", "ugv: {base: {backend: real}}\n",
       "ugv.base.backend: expected one of sim, hw"},
      {"no_port.yaml", "uav: {winch: {backend: hw}}\n", "uav.winch.serial: expected a mapping"},
      {"nan.yaml",
       "ugv: {base: {backend: hw, serial: {port: /dev/ttyAMA0}, camera: {device: '0'}, "
       "odometry: {wheel_radius_m: .nan}}}\n",
       "ugv.base.odometry.wheel_radius_m: expected a number"},
      {"type.yaml", "uav: {winch: {backend: hw, serial: {port: /dev/ttyUSB0, baud: [1]}}}\n",
       "uav.winch.serial.baud: expected an integer"},
      {"address.yaml", "uav: {flight_controller: {backend: hw}}\n",
       "uav.flight_controller.address: expected"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string mission = dir / c.name;
    write_text(mission, c.text);
    expect_bad_input(run_cli("config --dump --mission '" + mission + "'"), mission, c.field);
  }
  // A command that builds no robot checks the sections too, and writes nothing.
  const std::string unknown = dir / "unknown.yaml";
  const std::string out = dir / "tether";
  expect_bad_input(run_cli("tether-sim --mission '" + unknown + "' -o '" + out + "'"), unknown,
                   "ugv.base.backend: expected one of sim, hw (got 'real')");
  EXPECT_FALSE(fs::exists(out));
}

TEST(ConfigCli, TheSimulatedMissionRefusesARealRobotAndSaysWhatItRuns) {
  TempDir dir;
  write_text(dir / "robot.yaml", "uav: {winch: {backend: hw, serial: {port: /dev/ttyUSB0}}}\n");
  const std::string mission = dir / "robot.yaml";
  expect_bad_input(run_cli("mission --mission '" + mission + "'"), mission,
                   "uav.winch.backend: expected sim (ferret mission runs both robots in its own "
                   "simulator)");
}

}  // namespace
}  // namespace ferret::test
