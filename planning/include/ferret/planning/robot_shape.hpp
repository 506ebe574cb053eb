#pragma once
// The collision geometry the planners check: a robot as a set of primitives placed
// in its base frame B. The URDF loader fills these from <collision> elements
// (robot_shape_from_description); the builders below give the shapes the planners
// need when the robot's configuration changes (the UAV with the miniUGV hanging
// on a released tether of length l_t).

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "ferret/core/pose.hpp"

namespace ferret {

struct RobotDescription;

/// One primitive. Boxes, cylinders and capsules are centred on their frame S;
/// cylinders and capsules have their axis along S's z (as in URDF and FCL).
struct ShapePart {
  enum class Kind { kBox, kCylinder, kCapsule, kSphere };
  Kind kind = Kind::kBox;
  std::string name;
  Pose3 X_BS = Pose3::Identity();
  Eigen::Vector3d box_size_m = Eigen::Vector3d::Zero();  ///< boxes: full edge lengths
  double radius_m = 0.0;                                 ///< cylinders, capsules, spheres
  double length_m = 0.0;  ///< cylinders and capsules: the axis length (a capsule adds its caps)

  /// Radius of a sphere about S's origin that contains the part.
  [[nodiscard]] double bounding_radius_m() const;
};

struct RobotShape {
  std::string name;
  std::vector<ShapePart> parts;
};

/// The UAV's collision geometry (defaults: a DJI Matrice 100 class quadrotor,
/// 650 mm wheelbase with 13" propellers, docs/planning.md).
struct UavGeometry {
  Eigen::Vector3d body_size_m{0.35, 0.35, 0.30};  ///< fuselage, battery and landing gear
  double rotor_envelope_radius_m = 0.50;          ///< disc swept by all propellers about the centre
  double rotor_envelope_height_m = 0.10;
  double rotor_plane_z_m = 0.10;          ///< height of the rotor disc above B
  Eigen::Vector3d p_BW{0.0, 0.0, -0.15};  ///< winch spool exit in B
  double tether_radius_m = 0.01;          ///< thin capsule around the tether
};

/// The miniUGV's collision geometry: a 130 x 120 x 55 mm box. Its base frame G sits
/// on the floor under the box's centre, x forward.
struct UgvGeometry {
  Eigen::Vector3d body_size_m{0.13, 0.12, 0.055};
  double ground_clearance_m = 0.01;  ///< gap between the floor and the box's underside
};

[[nodiscard]] RobotShape uav_shape(const UavGeometry& uav = {});
/// The UAV with the miniUGV hanging straight down on a released tether of
/// `released_length_m` (from the winch exit to the miniUGV's top).
/// @pre released_length_m >= 0
[[nodiscard]] RobotShape uav_with_suspended_ugv_shape(double released_length_m,
                                                      const UavGeometry& uav = {},
                                                      const UgvGeometry& ugv = {});
[[nodiscard]] RobotShape ugv_shape(const UgvGeometry& ugv = {});

/// The collision shapes of a loaded URDF (boxes, cylinders, spheres; meshes as their
/// bounding boxes). A UAV's parts are in its base frame B. A ground robot's parts are
/// in the ground frame G the planners use (robot_shape.hpp's UgvGeometry: on the floor
/// under B, z up): B sits `robot.ground_offset_m` above G, so the lowest collision
/// point is at z = 0 whatever the URDF's base frame (the miniUGV's is on the ground,
/// offset 0; a base frame at the body centre is lifted by its height).
[[nodiscard]] RobotShape robot_shape_from_description(const RobotDescription& robot);

/// A ground robot's box for the planners' bounds and tether checks: the size of its
/// collision geometry's bounding box (base frame G on the floor, as above).
[[nodiscard]] UgvGeometry ugv_geometry_from_description(const RobotDescription& robot);

}  // namespace ferret
