#pragma once
// A robot as the rest of ferret sees it: collision shapes, sensor frames and
// parameters, special frames (EPM, IMU, tether attachments, winch spool) and motion
// limits, all read from a URDF plus the mission YAML. Everything is expressed in the
// base frame B (the URDF's root link) at zero joint positions. docs/configuration.md
// lists the naming conventions a URDF must follow.
//
// Frames follow monogram notation: X_BS is the pose of a shape or sensor S in the
// base frame B; p_BO a position in B. Sensor frames look along their +x axis, with
// +y left and +z up (Gazebo's sensor convention), for cameras and range sensors alike.

#include <Eigen/Geometry>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/urdf/mission_config.hpp"

namespace ferret {

/// One primitive of a link's collision geometry, placed in the base frame.
/// Boxes are centred on S; cylinders are centred on S with their axis along S's z
/// (as in URDF, FCL and Gazebo); spheres are centred on S.
struct CollisionShape {
  enum class Type { kBox, kCylinder, kSphere };
  Type type = Type::kBox;
  std::string link;  ///< the URDF link the shape belongs to
  Pose3 X_BS = Pose3::Identity();
  Eigen::Vector3d box_size_m = Eigen::Vector3d::Zero();  ///< full extents (boxes)
  double radius_m = 0.0;                                 ///< cylinders and spheres
  double length_m = 0.0;                                 ///< cylinders, along S's z

  /// Tight axis-aligned bounding box of the shape in B.
  [[nodiscard]] Eigen::AlignedBox3d aabb_B() const;
  /// Largest distance, in B's xy plane, from B's origin to a point of the shape.
  [[nodiscard]] double xy_reach_m() const;
};

[[nodiscard]] const char* to_string(CollisionShape::Type type);

/// A camera (colour or depth). The horizontal fov is the URDF value; the vertical fov
/// follows from the image aspect ratio (square pixels).
struct CameraSensor {
  std::string name;
  std::string link;  ///< the link it is attached to
  Pose3 X_BS = Pose3::Identity();
  bool depth = false;  ///< a depth camera (Gazebo type "depth" / "depth_camera")
  double horizontal_fov_rad = 0.0;
  double vertical_fov_rad = 0.0;
  int image_width_px = 0;
  int image_height_px = 0;
  double range_min_m = 0.0;     ///< clip near
  double range_max_m = 0.0;     ///< clip far: for the object camera, D_cam of the paper
  double update_rate_hz = 0.0;  ///< 0 when the URDF does not say
};

/// A planar range sensor (IR or laser): `samples` beams spread evenly over
/// [min_angle_rad, max_angle_rad] about S's z axis, measured from S's x axis.
struct RangeSensor {
  std::string name;
  std::string link;
  Pose3 X_BS = Pose3::Identity();
  int samples = 1;
  double min_angle_rad = 0.0;
  double max_angle_rad = 0.0;
  double range_min_m = 0.0;
  double range_max_m = 0.0;
  double update_rate_hz = 0.0;

  [[nodiscard]] double fov_rad() const { return max_angle_rad - min_angle_rad; }
  /// Beam i's angle about S's z axis; a single beam points at the middle of the span.
  [[nodiscard]] double beam_angle_rad(int i) const;
};

/// One beam of the IR array, flattened to the base frame's xy plane.
struct IrBeam {
  std::string sensor;
  Eigen::Vector2d p_BO = Eigen::Vector2d::Zero();  ///< beam origin in B (x, y)
  double yaw_B_rad = 0.0;                          ///< beam direction in B
};

/// The miniUGV's IR sensors taken together (paper: fov beta, range D_IR).
struct IrArray {
  double fov_rad = 0.0;           ///< beta: from the leftmost beam edge to the rightmost
  double range_min_m = 0.0;       ///< the largest range_min of the IR sensors
  double range_max_m = 0.0;       ///< the smallest range_max of the IR sensors (D_IR)
  double center_yaw_B_rad = 0.0;  ///< the middle of the fov, in B
  std::vector<IrBeam> beams;
};

/// A named frame: a link, a sensor or a role (EPM, tether attachment ...).
struct Frame {
  std::string name;
  Pose3 X_BF = Pose3::Identity();
};

/// What kind of robot a URDF describes: one with wheel joints is a ground vehicle and
/// takes the mission's ugv_limits, any other one an aerial vehicle with uav_limits.
enum class RobotKind { kUgv, kUav };
[[nodiscard]] const char* to_string(RobotKind kind);

struct RobotDescription {
  std::string name;       ///< <robot name=...>
  std::string source;     ///< the URDF file it came from
  std::string base_link;  ///< the root link: frame B
  RobotKind kind = RobotKind::kUgv;

  std::vector<CollisionShape> collision_shapes;
  /// Every link and sensor frame by name (X_BF). Sensor names and link names share
  /// this map; the loader rejects a sensor named like a link.
  std::map<std::string, Pose3> frames;
  std::vector<CameraSensor> cameras;
  std::vector<RangeSensor> range_sensors;

  /// Effective motion limits: the mission's ugv_limits or uav_limits, with the
  /// velocity capped by wheel radius x wheel joint velocity limit where the URDF has one.
  MotionLimits limits;
  std::optional<double> wheel_speed_limit_mps;  ///< from the wheel joints, if any

  std::optional<Frame> epm;               ///< link `epm_link` (x out of the magnet face)
  std::optional<Frame> imu;               ///< link `imu_link`
  std::optional<Frame> winch_spool;       ///< link `winch_spool_link` (spool axis = z)
  std::vector<Frame> tether_attachments;  ///< links named `tether_attach*`, in URDF order

  /// Axis-aligned box around all collision shapes, in B.
  Eigen::AlignedBox3d bounding_box_B;
  /// Largest distance in B's xy plane from B's origin to any collision geometry:
  /// a disc of this radius around the base covers the robot at any heading.
  double circumscribed_radius_m = 0.0;

  /// The camera with this name, or nullptr.
  [[nodiscard]] const CameraSensor* find_camera(std::string_view camera_name) const;
  /// The camera with this name; throws InputError naming the URDF when it is missing.
  [[nodiscard]] const CameraSensor& camera(std::string_view camera_name) const;
  /// The first depth camera; throws InputError when there is none.
  [[nodiscard]] const CameraSensor& depth_camera() const;
  /// The range sensor with this name, or nullptr.
  [[nodiscard]] const RangeSensor* find_range_sensor(std::string_view sensor_name) const;
  /// The range sensors whose names start with "ir" taken together; throws InputError
  /// when there is none.
  [[nodiscard]] IrArray ir_array() const;
  /// X_BF of a link or sensor; throws InputError when there is no such frame.
  [[nodiscard]] const Pose3& frame(std::string_view frame_name) const;
};

/// Conventional sensor names (docs/configuration.md).
inline constexpr std::string_view kFrontCameraName = "front_camera";    ///< miniUGV object camera
inline constexpr std::string_view kMarkerCameraName = "marker_camera";  ///< UAV ArUco camera
inline constexpr std::string_view kDepthCameraName = "depth_camera";    ///< UAV landing-zone camera

/// Reads a URDF and completes it with the mission's motion limits. Throws InputError
/// naming the file (with line), the element and what was expected for: a missing file,
/// malformed XML, joints naming missing links, non-positive shape sizes, mesh collision
/// geometry, sensors with missing or non-positive fov or range, conflicting sensor
/// definitions. urdfdom's console messages are captured, never printed.
[[nodiscard]] RobotDescription load_robot_description(const std::filesystem::path& urdf_path,
                                                      const MissionConfig& mission = {});
/// The same from URDF text; `source` names it in errors.
[[nodiscard]] RobotDescription robot_description_from_string(const std::string& urdf_xml,
                                                             const std::string& source,
                                                             const MissionConfig& mission = {});

/// YAML summary of a description (what `ferret config --dump` prints under `robot:`).
/// Angles are given in degrees and radians; lengths in metres.
[[nodiscard]] std::string robot_description_to_yaml(const RobotDescription& robot);

/// Finds a model shipped with ferret (e.g. "miniugv.urdf") beside the running ferret
/// library: <prefix>/share/ferret/models when installed, the source tree's urdf/models
/// for the build tree (ferret/core/data_path.hpp). Throws InputError naming the path.
[[nodiscard]] std::filesystem::path find_model(std::string_view file_name);

}  // namespace ferret
