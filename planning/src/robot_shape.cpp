#include "ferret/planning/robot_shape.hpp"

#include <cmath>

#include "ferret/urdf/robot_description.hpp"

namespace ferret {

double ShapePart::bounding_radius_m() const {
  switch (kind) {
    case Kind::kBox:
      return 0.5 * box_size_m.norm();
    case Kind::kCylinder:
      return std::hypot(radius_m, 0.5 * length_m);
    case Kind::kCapsule:
      return 0.5 * length_m + radius_m;
    case Kind::kSphere:
      return radius_m;
  }
  return 0.0;
}

namespace {
ShapePart box(std::string name, const Eigen::Vector3d& size, const Eigen::Vector3d& center) {
  ShapePart p;
  p.kind = ShapePart::Kind::kBox;
  p.name = std::move(name);
  p.box_size_m = size;
  p.X_BS.translation() = center;
  return p;
}
}  // namespace

RobotShape uav_shape(const UavGeometry& uav) {
  RobotShape s{"uav", {box("uav_body", uav.body_size_m, Eigen::Vector3d::Zero())}};
  ShapePart rotors;
  rotors.kind = ShapePart::Kind::kCylinder;
  rotors.name = "uav_rotor_envelope";
  rotors.radius_m = uav.rotor_envelope_radius_m;
  rotors.length_m = uav.rotor_envelope_height_m;
  rotors.X_BS.translation() = Eigen::Vector3d(0, 0, uav.rotor_plane_z_m);
  s.parts.push_back(rotors);
  return s;
}

RobotShape uav_with_suspended_ugv_shape(double released_length_m, const UavGeometry& uav,
                                        const UgvGeometry& ugv) {
  RobotShape s = uav_shape(uav);
  s.name = "uav_with_ugv";
  if (released_length_m > 0.0) {
    ShapePart tether;
    tether.kind = ShapePart::Kind::kCapsule;
    tether.name = "tether";
    tether.radius_m = uav.tether_radius_m;
    tether.length_m = released_length_m;
    tether.X_BS.translation() = uav.p_BW - Eigen::Vector3d(0, 0, 0.5 * released_length_m);
    s.parts.push_back(tether);
  }
  const double top_z = uav.p_BW.z() - released_length_m;
  s.parts.push_back(box("ugv_body", ugv.body_size_m,
                        {uav.p_BW.x(), uav.p_BW.y(), top_z - 0.5 * ugv.body_size_m.z()}));
  return s;
}

RobotShape ugv_shape(const UgvGeometry& ugv) {
  return {"ugv",
          {box("ugv_body", ugv.body_size_m,
               {0, 0, ugv.ground_clearance_m + 0.5 * ugv.body_size_m.z()})}};
}

RobotShape robot_shape_from_description(const RobotDescription& robot) {
  RobotShape s{robot.name, {}};
  // X_GB: a ground robot's planning frame G is on the floor below B.
  const Eigen::Vector3d p_GB(0, 0, robot.kind == RobotKind::kUgv ? robot.ground_offset_m : 0.0);
  for (const CollisionShape& c : robot.collision_shapes) {
    ShapePart p;
    p.name = c.link;
    p.X_BS = c.X_BS;
    p.X_BS.translation() += p_GB;
    switch (c.type) {
      case CollisionShape::Type::kBox:
        p.kind = ShapePart::Kind::kBox;
        p.box_size_m = c.box_size_m;
        break;
      case CollisionShape::Type::kCylinder:
        p.kind = ShapePart::Kind::kCylinder;
        p.radius_m = c.radius_m;
        p.length_m = c.length_m;
        break;
      case CollisionShape::Type::kSphere:
        p.kind = ShapePart::Kind::kSphere;
        p.radius_m = c.radius_m;
        break;
    }
    s.parts.push_back(p);
  }
  return s;
}

UgvGeometry ugv_geometry_from_description(const RobotDescription& robot) {
  UgvGeometry g;
  g.body_size_m = robot.bounding_box_B.sizes();
  return g;
}

}  // namespace ferret
