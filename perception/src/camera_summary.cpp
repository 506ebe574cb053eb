#include "ferret/perception/camera_summary.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "ferret/perception/camera_model.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

/// Display form: 9 decimals (tan() leaves 320.00000000000006 for an fx of 320), the
/// shortest decimal that reads back. `ferret config --camera-info` gives every digit.
std::string shown(double v) {
  const double r = std::round(v * 1e9) / 1e9;
  return r == 0.0 ? "0" : fmt::format("{}", r);
}

void key_number(YAML::Emitter& e, const char* key, double v) {
  e << YAML::Key << key << YAML::Value << shown(v);
}

std::string provenance_of(const RobotDescription& robot, const std::string& key,
                          const std::string& fallback) {
  const auto it = robot.provenance.find(key);
  return it != robot.provenance.end() ? it->second : fallback;
}

}  // namespace

std::string camera_models_yaml(const RobotDescription& robot) {
  YAML::Emitter e;
  e << YAML::BeginMap << YAML::Key << "camera_models" << YAML::Value << YAML::BeginSeq;
  for (const CameraSensor& sensor : robot.cameras) {
    const CameraModel m = camera_model(sensor, robot.source);
    e << YAML::BeginMap;
    e << YAML::Key << "name" << YAML::Value << m.name;
    std::vector<std::string> roles;
    for (const auto& [role, names] : robot.roles)
      for (const auto& n : names)
        if (n == sensor.name) roles.push_back(role);
    e << YAML::Key << "roles" << YAML::Value << YAML::Flow << roles;
    e << YAML::Key << "image_px" << YAML::Value << YAML::Flow << YAML::BeginSeq << m.width_px
      << m.height_px << YAML::EndSeq;
    key_number(e, "fx_px", m.fx_px);
    key_number(e, "fy_px", m.fy_px);
    key_number(e, "cx_px", m.cx_px);
    key_number(e, "cy_px", m.cy_px);
    key_number(e, "skew", m.skew);
    e << YAML::Key << "distortion_model" << YAML::Value << to_string(m.distortion);
    e << YAML::Key << "distortion_coefficients" << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (const double d : m.distortion_coefficients) e << shown(d);
    e << YAML::EndSeq << YAML::Comment("k1, k2, p1, p2, k3");
    const double hfov = m.horizontal_fov_rad(), vfov = m.vertical_fov_rad();
    key_number(e, "horizontal_fov_deg", hfov * 180.0 / std::numbers::pi);
    key_number(e, "horizontal_fov_rad", hfov);
    key_number(e, "vertical_fov_deg", vfov * 180.0 / std::numbers::pi);
    key_number(e, "vertical_fov_rad", vfov);

    const std::string k = "cameras." + sensor.name + ".";
    const std::string size = provenance_of(robot, k + "image_width_px", "urdf:" + robot.source);
    const std::string pinhole =
        sensor.intrinsics
            ? provenance_of(robot, k + "intrinsics", "urdf:" + robot.source)
            : provenance_of(robot, k + "horizontal_fov", "urdf:" + robot.source) +
                  " (fx = fy = (width / 2) / tan(hfov / 2), principal point at the image "
                  "centre: no <lens><intrinsics>)";
    const std::string distortion =
        sensor.distortion ? provenance_of(robot, k + "distortion", "urdf:" + robot.source) +
                                " (Gazebo <distortion> as plumb_bob)"
                          : "default (no <distortion> block: none)";
    e << YAML::Key << "provenance" << YAML::Value << YAML::BeginMap;
    e << YAML::Key << "image_px" << YAML::Value << size;
    e << YAML::Key << "pinhole" << YAML::Value << pinhole;
    e << YAML::Key << "distortion" << YAML::Value << distortion;
    e << YAML::Key << "fov" << YAML::Value << "computed from the pinhole above";
    e << YAML::EndMap;
    e << YAML::EndMap;
  }
  e << YAML::EndSeq << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

}  // namespace ferret
