#pragma once
// A robot as the rest of ferret sees it: collision shapes, sensor frames and
// parameters, special frames (EPM, IMU, tether attachments, winch spool) and motion
// limits, all read from a URDF plus the mission YAML. Everything is expressed in the
// base frame B (the URDF's root link) at zero joint positions. Sensors and special
// frames are found by role, never by name: a <ferret role=".."/> marker inside the
// <sensor> or <link>, or the mission YAML's `roles:` section (docs/configuration.md).
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
#include "ferret/urdf/robot_mission_settings.hpp"

namespace ferret {

/// One primitive of a link's collision geometry, placed in the base frame.
/// Boxes are centred on S; cylinders are centred on S with their axis along S's z
/// (as in URDF, FCL and Gazebo); spheres are centred on S. A <mesh> becomes the box
/// that bounds its (scaled) vertices in the collision frame; `mesh` names its file.
struct CollisionShape {
  enum class Type { kBox, kCylinder, kSphere };
  Type type = Type::kBox;
  std::string link;  ///< the URDF link the shape belongs to
  std::string mesh;  ///< the resolved mesh file a box was made from; empty for primitives
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

/// Gazebo's <camera><distortion> block: the Brown-Conrady coefficients (ROS's
/// plumb_bob, in camera_info's order k1, k2, p1, p2, k3 once read) and the distortion
/// centre in normalised image coordinates (0.5, 0.5 = the image centre).
struct CameraDistortion {
  double k1 = 0.0, k2 = 0.0, k3 = 0.0, p1 = 0.0, p2 = 0.0;
  double center_x = 0.5, center_y = 0.5;
};

/// Gazebo's <camera><lens><intrinsics> block (SDF 1.7): a calibrated pinhole that
/// replaces the one the horizontal fov implies. Pixels as in camera_info.
struct CameraIntrinsics {
  double fx_px = 0.0, fy_px = 0.0, cx_px = 0.0, cy_px = 0.0;
  double skew = 0.0;  ///< <s>, 0 when absent
};

/// A camera (colour or depth). The horizontal fov is the URDF value; the vertical fov
/// follows from the image aspect ratio (square pixels). The optional distortion and
/// intrinsics blocks make its camera model (perception/camera_model.hpp) a calibrated
/// one.
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
  std::optional<CameraDistortion> distortion;  ///< Gazebo <camera><distortion>
  std::optional<CameraIntrinsics> intrinsics;  ///< Gazebo <camera><lens><intrinsics>
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

/// The roles a sensor can play (docs/configuration.md). A role names what a consumer
/// needs, whatever the sensor is called: `object_camera` (the miniUGV's colour camera
/// for the object detector), `ir` (the miniUGV's IR array: one or more range sensors),
/// `marker_camera` (the UAV's colour camera for ArUco markers), `depth_camera` (the
/// UAV's landing-zone camera, a depth camera).
inline constexpr std::string_view kRoleObjectCamera = "object_camera";
inline constexpr std::string_view kRoleIr = "ir";
inline constexpr std::string_view kRoleMarkerCamera = "marker_camera";
inline constexpr std::string_view kRoleDepthCamera = "depth_camera";
/// The roles of links: `epm` (x out of the magnet face), `imu`, `winch_spool` (spool
/// axis = z), `tether_attachment` (several allowed).
inline constexpr std::string_view kRoleEpm = "epm";
inline constexpr std::string_view kRoleImu = "imu";
inline constexpr std::string_view kRoleWinchSpool = "winch_spool";
inline constexpr std::string_view kRoleTetherAttachment = "tether_attachment";
/// Every sensor role, then every frame role.
[[nodiscard]] const std::vector<std::string>& sensor_role_names();
[[nodiscard]] const std::vector<std::string>& frame_role_names();

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

  std::optional<Frame> epm;               ///< the link with role `epm` (x out of the magnet face)
  std::optional<Frame> imu;               ///< the link with role `imu`
  std::optional<Frame> winch_spool;       ///< the link with role `winch_spool` (spool axis = z)
  std::vector<Frame> tether_attachments;  ///< links with role `tether_attachment`, in URDF order

  /// Role -> the sensors (or links) that play it, in URDF order; only roles that are
  /// declared appear (a <ferret role> marker or the mission's `roles:` section).
  std::map<std::string, std::vector<std::string>> roles;

  /// Where each value came from, for `ferret config --dump`: key (a dotted path such as
  /// "roles.object_camera", "cameras.cam_main.horizontal_fov",
  /// "motion_limits.max_velocity_mps") -> "urdf:FILE:LINE", "mission:FILE" or "default",
  /// with a note in parentheses where a value is computed.
  std::map<std::string, std::string> provenance;

  /// Axis-aligned box around all collision shapes, in B.
  Eigen::AlignedBox3d bounding_box_B;
  /// Largest distance in B's xy plane from B's origin to any collision geometry:
  /// a disc of this radius around the base covers the robot at any heading.
  double circumscribed_radius_m = 0.0;
  /// Height of B above the lowest point of the collision geometry: for a ground robot
  /// resting on its lowest point, where B sits above the floor (0 when B is on the
  /// ground, as in the miniUGV; 0.07 m for a base frame at a body centre 7 cm up).
  double ground_offset_m = 0.0;

  /// The footprint at the ground: the bounding box's xy extent, in B's xy.
  [[nodiscard]] Eigen::AlignedBox2d footprint_B() const;

  /// The camera with this name, or nullptr.
  [[nodiscard]] const CameraSensor* find_camera(std::string_view camera_name) const;
  /// The camera with this name; throws InputError naming the URDF when it is missing.
  [[nodiscard]] const CameraSensor& camera(std::string_view camera_name) const;
  /// The range sensor with this name, or nullptr.
  [[nodiscard]] const RangeSensor* find_range_sensor(std::string_view sensor_name) const;

  /// The camera with role `object_camera` (a colour camera), or nullptr.
  [[nodiscard]] const CameraSensor* find_object_camera() const;
  /// The cameras of the roles; each throws InputError naming the URDF, the role and
  /// how to declare it when the role is missing.
  [[nodiscard]] const CameraSensor& object_camera() const;
  [[nodiscard]] const CameraSensor& marker_camera() const;
  [[nodiscard]] const CameraSensor& depth_camera() const;
  /// True when some range sensor has the role `ir`.
  [[nodiscard]] bool has_ir() const;
  /// The range sensors with role `ir` taken together; throws InputError when none.
  [[nodiscard]] IrArray ir_array() const;
  /// X_BF of a link or sensor; throws InputError when there is no such frame.
  [[nodiscard]] const Pose3& frame(std::string_view frame_name) const;
  /// The InputError for a role a consumer needs and the robot does not declare.
  [[noreturn]] void missing_role(std::string_view role, std::string_view what) const;
};

/// Reads a URDF and completes it with the mission's motion limits and role
/// assignments. Throws InputError naming the file (with line), the element and what
/// was expected for: a missing file, malformed XML, joints naming missing links,
/// non-positive shape sizes, a missing or unreadable mesh, sensors with missing or
/// non-positive fov or range, conflicting sensor definitions, an unknown role or a role
/// on a sensor of the wrong type (the mission's `roles:` entries likewise, naming the
/// mission file). urdfdom's console messages are captured, never printed.
///
/// Mesh files: `package://PKG/PATH` is looked up as DIR/PKG/PATH for every DIR of
/// ROS_PACKAGE_PATH, then beside the URDF (each ancestor A of its folder: A/PATH
/// when A is named PKG, else A/PKG/PATH); `file://PATH` and plain names are paths,
/// relative ones to the URDF's folder.
[[nodiscard]] RobotDescription load_robot_description(const std::filesystem::path& urdf_path,
                                                      const RobotMissionSettings& mission = {});
/// The same from URDF text; `source` names it in errors.
[[nodiscard]] RobotDescription robot_description_from_string(
    const std::string& urdf_xml, const std::string& source,
    const RobotMissionSettings& mission = {});

/// A URDF path, or the name of a shipped model ("miniugv", "m100", with or without
/// ".urdf"), loaded with the mission: the one call that gives a robot and where each
/// of its values came from (RobotDescription::provenance).
[[nodiscard]] RobotDescription load_robot(const std::string& urdf_or_name,
                                          const RobotMissionSettings& mission = {});

/// YAML summary of a description (what `ferret config --dump` prints under `robot:`).
/// Angles are given in degrees and radians; lengths in metres.
[[nodiscard]] std::string robot_description_to_yaml(const RobotDescription& robot);

/// Finds a model shipped with ferret (e.g. "miniugv.urdf") beside the running ferret
/// library: <prefix>/share/ferret/models when installed, the source tree's urdf/models
/// for the build tree (ferret/core/data_path.hpp). Throws InputError naming the path.
[[nodiscard]] std::filesystem::path find_model(std::string_view file_name);

}  // namespace ferret
