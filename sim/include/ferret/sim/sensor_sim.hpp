#pragma once
// Rendered sensor frames of a WorldSpec: colour camera frames (shaded geometry, the
// fiducial markers' real bitmaps, objects in their paint colour), RealSense-D415-like
// depth frames, the IR beams of a robot at their URDF poses and an IMU's attitude.
// Ground truth for tests (where each marker appears) comes from the same geometry.
//
// Frames: X_WC is the pose of a camera's OPTICAL frame C (x right, y down, z forward)
// in the world; for a robot, X_WC = X_WB * X_BS * X_SC() (optical_pose()). Every
// simulated frame takes a seed: same seed, same bytes on any machine (core/random.hpp).
//
// How: exact ray casting of the world's primitives (ground plane clipped to the world
// bounds, yawed boxes, upright cylinders, marker squares), one ray per pixel through
// the camera model's distortion, with each primitive tested only in the image tiles its
// bounds project to (docs/perception.md, "Simulated sensors").

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/image.hpp"
#include "ferret/sim/hidden_space_sim.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {

namespace internal {
struct Scene;
}

struct CameraFrameOptions {
  double blur_sigma_px = 0.8;  ///< Gaussian blur of the lens and demosaicing (0: none)
  double noise_sigma = 2.0;    ///< Gaussian sensor noise, grey levels (0: none)
  double exposure_gain = 1.0;  ///< multiplies radiance before the 8-bit clamp
  /// Objects painted kObjectColourRgb (perception/object_appearance.hpp); false paints
  /// them the grey of other boxes (the geometry stays: a negative for the detector).
  bool draw_objects = true;
};

/// A RealSense D415: its datasheet's depth RMS error is <= 2 % at 2 m, and stereo error
/// grows with z^2, so sigma_z = c z^2 with c = 0.02 * 2 m / (2 m)^2 = 0.01 / m.
struct DepthFrameOptions {
  double min_range_m = 0.3;   ///< no return nearer (the D415's minimum z at full resolution)
  double max_range_m = 10.0;  ///< no return farther
  double noise_coefficient_per_m = 0.01;  ///< sigma_z = c * z^2
  double max_incidence_deg = 75.0;        ///< no return where the ray grazes the surface more
  double dropout_fraction = 0.01;         ///< random pixels without a return
};

/// Where a world marker appears in a camera (ground truth for tests and evaluations).
struct VisibleMarker {
  int hidden_space = -1;  ///< index into WorldSpec::hidden_spaces
  int id = 0;
  MarkerDictionary dictionary;
  /// The black square's corners in the image (distortion applied), OpenCV's order:
  /// top-left, top-right, bottom-right, bottom-left of the marker image.
  /// NaN for a corner behind the camera (the marker is then partly visible at most).
  std::array<Eigen::Vector2d, 4> corners_px;
  /// Fraction of the black square seen: in the image, facing the camera, not occluded.
  double visible_fraction = 0.0;
  double distance_m = 0.0;         ///< camera centre to marker centre
  double off_axis_rad = 0.0;       ///< angle between the marker's normal and the line to the camera
  Pose3 X_CM = Pose3::Identity();  ///< the marker in the optical frame
};

/// One IR beam's reading.
struct IrReading {
  std::string sensor;                              ///< the URDF range sensor
  Eigen::Vector3d p_WO = Eigen::Vector3d::Zero();  ///< beam origin in the world
  Eigen::Vector3d direction_W = Eigen::Vector3d::UnitX();
  double range_m = 0.0;  ///< measured; range_max_m when nothing returned
  double range_max_m = 0.0;
  bool hit = false;  ///< a surface within [range_min, range_max] returned the beam
};

struct ImuOptions {
  double tilt_noise_rad = deg_to_rad(0.2);  ///< roll and pitch (standard deviation)
  double yaw_noise_rad = deg_to_rad(1.0);   ///< heading (magnetometer-aided)
};

/// Attitude as the URDF/ROS rpy convention: R = Rz(yaw) * Ry(pitch) * Rx(roll).
struct ImuReading {
  double roll_rad = 0.0, pitch_rad = 0.0, yaw_rad = 0.0;
};

/// A pose from x, y, z and roll, pitch, yaw (R = Rz(yaw) * Ry(pitch) * Rx(roll)).
[[nodiscard]] Pose3 pose_from_xyz_rpy(const Eigen::Vector3d& p_m, double roll_rad, double pitch_rad,
                                      double yaw_rad);
/// Roll, pitch, yaw of a rotation (pitch in [-pi/2, pi/2]).
[[nodiscard]] ImuReading rpy_of(const Eigen::Matrix3d& R);
/// The optical frame of a robot's camera in the world: X_WB * X_BS * X_SC().
[[nodiscard]] Pose3 optical_pose(const Pose3& X_WB, const CameraSensor& camera);

/// The camera a robot takes frames with: for colour frames (`depth` false) the
/// marker_camera of a UAV or the object_camera of a UGV, for depth frames the
/// depth_camera; a non-empty `role` (object_camera, marker_camera, depth_camera) picks
/// instead. Throws InputError(option, ...) for an unknown role or, for depth frames, a
/// role whose camera is not a depth camera; the robot's missing-role error otherwise.
[[nodiscard]] const CameraSensor& camera_for(const RobotDescription& robot, bool depth,
                                             const std::string& role = {},
                                             const std::string& option = "--camera-role");

class SensorSimulator {
 public:
  /// Keeps a copy of the world's geometry (the world may go away afterwards).
  explicit SensorSimulator(const WorldSpec& world);
  ~SensorSimulator();
  SensorSimulator(SensorSimulator&&) noexcept;
  SensorSimulator& operator=(SensorSimulator&&) noexcept;

  /// An RGB frame. Sky (outside the world's bounds) is a light grey-blue.
  [[nodiscard]] RgbImage render_camera(const CameraModel& camera, const Pose3& X_WC,
                                       const CameraFrameOptions& options, std::uint64_t seed) const;
  /// The same scene as a grey camera sees it (what the marker detectors read): the
  /// BT.601 luminance of render_camera's colours, blurred alike, with the noise the
  /// luminance of its per-channel noise has (sigma * 0.668). A third of the colour
  /// frame's work; not byte-equal to to_gray(render_camera(...)) (rounded once, not
  /// per channel, and its own noise draws), the same frame statistically.
  [[nodiscard]] GrayImage render_gray(const CameraModel& camera, const Pose3& X_WC,
                                      const CameraFrameOptions& options, std::uint64_t seed) const;
  /// A depth frame: millimetres along the optical axis, 0 = no return.
  [[nodiscard]] DepthImageMm render_depth(const CameraModel& camera, const Pose3& X_WC,
                                          const DepthFrameOptions& options,
                                          std::uint64_t seed) const;
  /// Whether any marker's quad (bitmap and quiet zone) projects into the camera's image
  /// from X_WC, occluded or not. When not, render_camera and render_gray give the frame
  /// the scene gives without markers: a detector has nothing to find in it.
  [[nodiscard]] bool markers_in_frame(const CameraModel& camera, const Pose3& X_WC) const;
  /// The world's markers the camera sees (visible_fraction > 0), in hidden-space order.
  [[nodiscard]] std::vector<VisibleMarker> visible_markers(const CameraModel& camera,
                                                           const Pose3& X_WC) const;

  /// The distance along the ray (unit `direction_W`) to the first surface, if one lies
  /// within max_range_m; the surface normal (facing the ray) in `normal_W` if given.
  [[nodiscard]] std::optional<double> cast_ray(const Eigen::Vector3d& p_W,
                                               const Eigen::Vector3d& direction_W,
                                               double max_range_m,
                                               Eigen::Vector3d* normal_W = nullptr) const;

  /// The robot's IR beams (range sensors with role ir, every sample of each at its URDF
  /// pose) from the base pose X_WB, with the noise and dropout of `noise` (its
  /// ir_noise_m, ir_dropout: the existing IR model's home). Throws InputError naming the
  /// URDF when the robot has no IR.
  [[nodiscard]] std::vector<IrReading> ir_ranges(const RobotDescription& robot, const Pose3& X_WB,
                                                 const SensorOptions& noise,
                                                 std::uint64_t seed) const;

  /// The base pose of a ground robot resting at (x, y) with heading yaw on the surface
  /// under `from_z_m` (ground, a floor slab, a box top): B's z along the surface
  /// normal, B `ground_offset_m` above it. nullopt when there is no surface below.
  [[nodiscard]] std::optional<Pose3> resting_pose(const Eigen::Vector2d& p_W, double yaw_rad,
                                                  double from_z_m,
                                                  double ground_offset_m = 0.0) const;
  /// An IMU's attitude reading of the base pose X_WB, with seeded noise.
  [[nodiscard]] ImuReading imu(const Pose3& X_WB, const ImuOptions& options,
                               std::uint64_t seed) const;

 private:
  std::unique_ptr<internal::Scene> scene_;
};

}  // namespace ferret
