// The motion limits of a robot: a robot with wheel joints is a UGV, the mission's limits
// for its kind, and the speed its wheels allow (joint velocity x wheel radius) when lower.

#include "loader_passes.hpp"

namespace ferret::internal {

namespace {

bool is_wheel_joint(const urdf::Joint& j) {
  return (j.type == urdf::Joint::CONTINUOUS || j.type == urdf::Joint::REVOLUTE) &&
         j.child_link_name.find("wheel") != std::string::npos;
}

}  // namespace

void read_limits(const urdf::ModelInterface& model, const RobotMissionSettings& mission,
                 const Structure& structure, RobotDescription& out) {
  bool has_wheels = false;
  std::string wheel_note;
  for (const auto& [name, joint] : model.joints_) {
    if (!joint || !is_wheel_joint(*joint)) continue;
    has_wheels = true;
    if (!joint->limits || joint->limits->velocity <= 0.0) continue;
    const auto link = model.getLink(joint->child_link_name);
    for (const auto& col : link->collision_array) {
      if (!col || !col->geometry || col->geometry->type != urdf::Geometry::CYLINDER) continue;
      const double r = static_cast<const urdf::Cylinder&>(*col->geometry).radius;
      const double v = joint->limits->velocity * r;
      if (!out.wheel_speed_limit_mps || v < *out.wheel_speed_limit_mps) {
        out.wheel_speed_limit_mps = v;
        wheel_note = "urdf:" + structure.joint_at.at(name) + " (joint " + name + ": " +
                     num(joint->limits->velocity) + " rad/s x wheel radius " + num(r) + " m)";
      }
      break;
    }
  }
  out.kind = has_wheels ? RobotKind::kUgv : RobotKind::kUav;
  out.limits = has_wheels ? mission.ugv_limits : mission.uav_limits;
  const std::string section = has_wheels ? "ugv_limits." : "uav_limits.";
  for (const char* key : {"max_velocity_mps", "max_acceleration_mps2", "max_yaw_rate_radps"})
    out.provenance[std::string("motion_limits.") + key] = mission.provenance(section + key);
  if (out.wheel_speed_limit_mps) {
    out.provenance["motion_limits.wheel_speed_limit_mps"] = wheel_note;
    if (*out.wheel_speed_limit_mps < out.limits.max_velocity_mps) {
      out.limits.max_velocity_mps = *out.wheel_speed_limit_mps;
      out.provenance["motion_limits.max_velocity_mps"] = wheel_note;
    }
  }
}

}  // namespace ferret::internal
