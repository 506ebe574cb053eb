#include "ferret/urdf/robot_description.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "ferret/core/data_path.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/yaml_emit.hpp"

namespace ferret {

const char* to_string(CollisionShape::Type type) {
  switch (type) {
    case CollisionShape::Type::kBox:
      return "box";
    case CollisionShape::Type::kCylinder:
      return "cylinder";
    case CollisionShape::Type::kSphere:
      return "sphere";
  }
  return "?";
}

const char* to_string(RobotKind kind) { return kind == RobotKind::kUgv ? "ugv" : "uav"; }

Eigen::AlignedBox3d CollisionShape::aabb_B() const {
  const Eigen::Vector3d c = X_BS.translation();
  const Eigen::Matrix3d R = X_BS.linear();
  Eigen::Vector3d half;
  switch (type) {
    case Type::kBox:
      half = R.cwiseAbs() * (box_size_m / 2.0);
      break;
    case Type::kCylinder: {
      // The axis contributes |a_i| L/2; the end discs contribute r sqrt(1 - a_i^2).
      const Eigen::Vector3d a = R.col(2);
      for (int i = 0; i < 3; ++i)
        half[i] = std::abs(a[i]) * length_m / 2.0 +
                  radius_m * std::sqrt(std::max(0.0, 1.0 - a[i] * a[i]));
      break;
    }
    case Type::kSphere:
    default:
      half = Eigen::Vector3d::Constant(radius_m);
      break;
  }
  return {c - half, c + half};
}

double CollisionShape::xy_reach_m() const {
  // Distance from the z axis is convex, so its maximum over a convex shape is at an
  // extreme point: a box corner, or a point on a cylinder's rim.
  double reach = 0.0;
  auto consider = [&](const Eigen::Vector3d& p_BP) {
    reach = std::max(reach, p_BP.head<2>().norm());
  };
  switch (type) {
    case Type::kBox:
      for (int corner = 0; corner < 8; ++corner) {
        const Eigen::Vector3d sign((corner & 1) ? 1 : -1, (corner & 2) ? 1 : -1,
                                   (corner & 4) ? 1 : -1);
        consider(X_BS * sign.cwiseProduct(box_size_m / 2.0));
      }
      break;
    case Type::kCylinder: {
      // 720 rim points per cap: under-estimates by at most r (1 - cos(0.25 deg)) < 1e-5 r.
      constexpr int kRimPoints = 720;
      for (int i = 0; i < kRimPoints; ++i) {
        const double t = 2.0 * std::numbers::pi * i / kRimPoints;
        for (const double z : {-length_m / 2.0, length_m / 2.0})
          consider(X_BS * Eigen::Vector3d(radius_m * std::cos(t), radius_m * std::sin(t), z));
      }
      break;
    }
    case Type::kSphere:
      reach = X_BS.translation().head<2>().norm() + radius_m;
      break;
  }
  return reach;
}

double RangeSensor::beam_angle_rad(int i) const {
  if (samples <= 1) return (min_angle_rad + max_angle_rad) / 2.0;
  return min_angle_rad + (max_angle_rad - min_angle_rad) * i / (samples - 1);
}

const CameraSensor* RobotDescription::find_camera(std::string_view camera_name) const {
  for (const auto& c : cameras)
    if (c.name == camera_name) return &c;
  return nullptr;
}

const CameraSensor& RobotDescription::camera(std::string_view camera_name) const {
  if (const auto* c = find_camera(camera_name)) return *c;
  throw InputError(
      source, "sensor[" + std::string(camera_name) + "]",
      "a camera sensor named '" + std::string(camera_name) + "' (docs/configuration.md)", "none");
}

const RangeSensor* RobotDescription::find_range_sensor(std::string_view sensor_name) const {
  for (const auto& r : range_sensors)
    if (r.name == sensor_name) return &r;
  return nullptr;
}

const Pose3& RobotDescription::frame(std::string_view frame_name) const {
  const auto it = frames.find(std::string(frame_name));
  if (it == frames.end())
    throw InputError(source, std::string(frame_name),
                     "a link or sensor named '" + std::string(frame_name) + "'", "none");
  return it->second;
}

const std::vector<std::string>& sensor_role_names() {
  static const std::vector<std::string> names{std::string(kRoleObjectCamera), std::string(kRoleIr),
                                              std::string(kRoleMarkerCamera),
                                              std::string(kRoleDepthCamera)};
  return names;
}

const std::vector<std::string>& frame_role_names() {
  static const std::vector<std::string> names{std::string(kRoleEpm), std::string(kRoleImu),
                                              std::string(kRoleWinchSpool),
                                              std::string(kRoleTetherAttachment)};
  return names;
}

Eigen::AlignedBox2d RobotDescription::footprint_B() const {
  return {bounding_box_B.min().head<2>(), bounding_box_B.max().head<2>()};
}

void RobotDescription::missing_role(std::string_view role, std::string_view what) const {
  const bool sensor = std::find(sensor_role_names().begin(), sensor_role_names().end(),
                                std::string(role)) != sensor_role_names().end();
  throw InputError(source, "role[" + std::string(role) + "]",
                   std::string(what) + " with the role " + std::string(role) +
                       ": declare it with <ferret role=\"" + std::string(role) +
                       "\"/> inside its " + (sensor ? "<sensor>" : "<link>") +
                       ", or in the mission YAML as roles: {" + name + ": {" + std::string(role) +
                       ": NAME}} (docs/configuration.md)",
                   "none");
}

namespace {
const CameraSensor* camera_of_role(const RobotDescription& r, std::string_view role) {
  const auto it = r.roles.find(std::string(role));
  if (it == r.roles.end() || it->second.empty()) return nullptr;
  return r.find_camera(it->second.front());
}
}  // namespace

const CameraSensor* RobotDescription::find_object_camera() const {
  return camera_of_role(*this, kRoleObjectCamera);
}

const CameraSensor& RobotDescription::object_camera() const {
  if (const auto* c = find_object_camera()) return *c;
  missing_role(kRoleObjectCamera, "a colour camera");
}

const CameraSensor& RobotDescription::marker_camera() const {
  if (const auto* c = camera_of_role(*this, kRoleMarkerCamera)) return *c;
  missing_role(kRoleMarkerCamera, "a colour camera");
}

const CameraSensor& RobotDescription::depth_camera() const {
  if (const auto* c = camera_of_role(*this, kRoleDepthCamera)) return *c;
  missing_role(kRoleDepthCamera, "a depth camera (Gazebo <sensor type=\"depth\">)");
}

bool RobotDescription::has_ir() const {
  const auto it = roles.find(std::string(kRoleIr));
  return it != roles.end() && !it->second.empty();
}

IrArray RobotDescription::ir_array() const {
  std::vector<const RangeSensor*> ir;
  if (const auto it = roles.find(std::string(kRoleIr)); it != roles.end())
    for (const auto& n : it->second)
      if (const auto* r = find_range_sensor(n)) ir.push_back(r);
  if (ir.empty()) missing_role(kRoleIr, "one or more range (ray) sensors");

  // Beam yaw in B; sensors are taken as level (their scan plane parallel to B's xy).
  auto yaw_B = [](const RangeSensor& r, double angle) {
    const Eigen::Vector3d d_B =
        r.X_BS.linear() * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.0);
    return std::atan2(d_B.y(), d_B.x());
  };
  // Measure every edge relative to the first sensor's middle, so a fov across +-pi works.
  const double ref =
      yaw_B(*ir.front(), (ir.front()->min_angle_rad + ir.front()->max_angle_rad) / 2.0);
  double lo = 0.0, hi = 0.0;
  IrArray out;
  out.range_min_m = 0.0;
  out.range_max_m = std::numeric_limits<double>::infinity();
  for (const auto* r : ir) {
    for (const double edge : {r->min_angle_rad, r->max_angle_rad}) {
      const double rel = wrap_angle_rad(yaw_B(*r, edge) - ref);
      lo = std::min(lo, rel);
      hi = std::max(hi, rel);
    }
    out.range_min_m = std::max(out.range_min_m, r->range_min_m);
    out.range_max_m = std::min(out.range_max_m, r->range_max_m);
    for (int i = 0; i < r->samples; ++i)
      out.beams.push_back(
          IrBeam{r->name, r->X_BS.translation().head<2>(), yaw_B(*r, r->beam_angle_rad(i))});
  }
  out.fov_rad = hi - lo;
  out.center_yaw_B_rad = wrap_angle_rad(ref + (lo + hi) / 2.0);
  return out;
}

// ---------------------------------------------------------------- YAML dump

namespace {
using internal::emit_key_number;
using internal::emit_key_numbers;

/// Rounds composition noise (0.30000000000000004) away for display.
double clean(double v) {
  const double r = std::round(v * 1e9) / 1e9;
  return r == 0.0 ? 0.0 : r;
}

Eigen::Vector3d rpy_of(const Eigen::Matrix3d& R) {
  // Fixed-axis roll, pitch, yaw (URDF order): R = Rz(yaw) Ry(pitch) Rx(roll).
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  if (std::abs(R(2, 0)) > 1.0 - 1e-12)  // gimbal lock: fold roll into yaw
    return {0.0, pitch, std::atan2(-R(0, 1), R(1, 1))};
  return {std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0))};
}

void emit_pose(YAML::Emitter& e, const char* key, const Pose3& X) {
  const Eigen::Vector3d p = X.translation(), rpy = rpy_of(X.linear());
  e << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap;
  emit_key_numbers(e, "xyz_m", {clean(p.x()), clean(p.y()), clean(p.z())});
  emit_key_numbers(e, "rpy_rad", {clean(rpy.x()), clean(rpy.y()), clean(rpy.z())});
  e << YAML::EndMap;
}

void emit_angle(YAML::Emitter& e, const std::string& key, double rad) {
  emit_key_number(e, (key + "_deg").c_str(), clean(rad_to_deg(rad)));
  emit_key_number(e, (key + "_rad").c_str(), clean(rad));
}

template <class Sensor>
void emit_sensor_head(YAML::Emitter& e, const Sensor& s) {
  e << YAML::Key << "name" << YAML::Value << s.name;
  e << YAML::Key << "link" << YAML::Value << s.link;
}

/// Range, rate and pose, then closes the sensor's map.
template <class Sensor>
void emit_sensor_tail(YAML::Emitter& e, const Sensor& s) {
  emit_key_number(e, "range_min_m", s.range_min_m);
  emit_key_number(e, "range_max_m", s.range_max_m);
  if (s.update_rate_hz > 0) emit_key_number(e, "update_rate_hz", s.update_rate_hz);
  emit_pose(e, "X_BS", s.X_BS);
  e << YAML::EndMap;
}

void emit_frame(YAML::Emitter& e, const char* key, const std::optional<Frame>& f) {
  if (!f) return;
  e << YAML::Key << key << YAML::Value << YAML::BeginMap << YAML::Key << "link" << YAML::Value
    << f->name;
  emit_pose(e, "X_BF", f->X_BF);
  e << YAML::EndMap;
}
}  // namespace

std::string robot_description_to_yaml(const RobotDescription& r) {
  YAML::Emitter e;
  e << YAML::BeginMap;
  e << YAML::Key << "source" << YAML::Value << r.source;
  e << YAML::Key << "name" << YAML::Value << r.name;
  e << YAML::Key << "kind" << YAML::Value << to_string(r.kind);
  e << YAML::Key << "base_link" << YAML::Value << r.base_link;

  e << YAML::Key << "bounding_box_m" << YAML::Value << YAML::BeginMap;
  const auto& bb = r.bounding_box_B;
  emit_key_numbers(e, "min", {clean(bb.min().x()), clean(bb.min().y()), clean(bb.min().z())});
  emit_key_numbers(e, "max", {clean(bb.max().x()), clean(bb.max().y()), clean(bb.max().z())});
  const Eigen::Vector3d size = bb.sizes();
  emit_key_numbers(e, "size", {clean(size.x()), clean(size.y()), clean(size.z())});
  e << YAML::EndMap;
  emit_key_number(e, "circumscribed_radius_m", clean(r.circumscribed_radius_m));
  emit_key_number(e, "ground_offset_m", clean(r.ground_offset_m));

  e << YAML::Key << "motion_limits" << YAML::Value << YAML::BeginMap;
  emit_key_number(e, "max_velocity_mps", r.limits.max_velocity_mps);
  emit_key_number(e, "max_acceleration_mps2", r.limits.max_acceleration_mps2);
  emit_key_number(e, "max_yaw_rate_radps", r.limits.max_yaw_rate_radps);
  if (r.wheel_speed_limit_mps)
    emit_key_number(e, "wheel_speed_limit_mps", clean(*r.wheel_speed_limit_mps));
  e << YAML::EndMap;

  e << YAML::Key << "cameras" << YAML::Value << YAML::BeginSeq;
  for (const auto& c : r.cameras) {
    e << YAML::BeginMap;
    emit_sensor_head(e, c);
    e << YAML::Key << "depth" << YAML::Value << c.depth;
    emit_angle(e, "horizontal_fov", c.horizontal_fov_rad);
    emit_angle(e, "vertical_fov", c.vertical_fov_rad);
    e << YAML::Key << "image_px" << YAML::Value << YAML::Flow << YAML::BeginSeq << c.image_width_px
      << c.image_height_px << YAML::EndSeq;
    emit_sensor_tail(e, c);
  }
  e << YAML::EndSeq;

  e << YAML::Key << "range_sensors" << YAML::Value << YAML::BeginSeq;
  for (const auto& s : r.range_sensors) {
    e << YAML::BeginMap;
    emit_sensor_head(e, s);
    emit_angle(e, "fov", s.fov_rad());
    e << YAML::Key << "samples" << YAML::Value << s.samples;
    emit_sensor_tail(e, s);
  }
  e << YAML::EndSeq;

  if (r.has_ir()) {
    const IrArray ir = r.ir_array();
    e << YAML::Key << "ir_array" << YAML::Value << YAML::BeginMap;
    emit_angle(e, "fov", ir.fov_rad);
    emit_angle(e, "center_yaw", ir.center_yaw_B_rad);
    e << YAML::Key << "beams" << YAML::Value << static_cast<int>(ir.beams.size());
    emit_key_number(e, "range_min_m", ir.range_min_m);
    emit_key_number(e, "range_max_m", ir.range_max_m);
    e << YAML::EndMap;
  }

  emit_frame(e, "epm", r.epm);
  emit_frame(e, "imu", r.imu);
  emit_frame(e, "winch_spool", r.winch_spool);
  e << YAML::Key << "tether_attachments" << YAML::Value << YAML::BeginSeq;
  for (const auto& f : r.tether_attachments) {
    e << YAML::BeginMap << YAML::Key << "link" << YAML::Value << f.name;
    emit_pose(e, "X_BF", f.X_BF);
    e << YAML::EndMap;
  }
  e << YAML::EndSeq;

  e << YAML::Key << "collision_shapes" << YAML::Value << YAML::BeginSeq;
  for (const auto& s : r.collision_shapes) {
    e << YAML::Flow << YAML::BeginMap;
    e << YAML::Key << "link" << YAML::Value << s.link;
    e << YAML::Key << "type" << YAML::Value << to_string(s.type);
    if (s.type == CollisionShape::Type::kBox)
      emit_key_numbers(e, "size_m",
                       {clean(s.box_size_m.x()), clean(s.box_size_m.y()), clean(s.box_size_m.z())});
    else
      emit_key_number(e, "radius_m", s.radius_m);
    if (s.type == CollisionShape::Type::kCylinder) emit_key_number(e, "length_m", s.length_m);
    if (!s.mesh.empty()) e << YAML::Key << "mesh_bounding_box_of" << YAML::Value << s.mesh;
    emit_pose(e, "X_BS", s.X_BS);
    e << YAML::EndMap;
  }
  e << YAML::EndSeq;

  e << YAML::Key << "frames" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, X] : r.frames) emit_pose(e, name.c_str(), X);
  e << YAML::EndMap;

  e << YAML::Key << "roles" << YAML::Value << YAML::BeginMap;
  for (const auto& [role, names] : r.roles)
    e << YAML::Key << role << YAML::Value << YAML::Flow << names;
  e << YAML::EndMap;

  // Where each value came from: urdf:FILE:LINE, mission:FILE or default.
  e << YAML::Key << "provenance" << YAML::Value << YAML::BeginMap;
  for (const auto& [key, from] : r.provenance) e << YAML::Key << key << YAML::Value << from;
  e << YAML::EndMap;

  e << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

// ---------------------------------------------------------------- shipped models

std::filesystem::path find_model(std::string_view file_name) {
  // The models beside the running ferret library: <prefix>/share/ferret/models when
  // installed, urdf/models of the source tree for the build tree (data_path.hpp). Never
  // the working directory or the running program's directory: a downstream program
  // must read the models of the ferret it is linked against.
  return data_path("models/" + std::string(file_name));
}

}  // namespace ferret
