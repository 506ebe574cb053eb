#pragma once
// A calibrated camera: pinhole intrinsics with ROS's plumb_bob distortion (OpenCV's
// five-coefficient radial-tangential model k1, k2, p1, p2, k3), as in a ROS
// camera_info. Points are in the camera's optical frame C: x right, y down, z forward
// (the ROS and OpenCV convention). URDF/Gazebo sensor frames S look along +x with +y
// left and +z up; X_SC() converts.
//
// Pixel coordinates are continuous with (0, 0) at the centre of the top-left pixel
// (OpenCV's convention, and camera_info's cx, cy).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <optional>
#include <string>

#include "ferret/core/pose.hpp"

namespace ferret {

struct CameraSensor;

enum class DistortionModel { kNone, kPlumbBob };
/// "none" / "plumb_bob" (camera_info's distortion_model spelling).
[[nodiscard]] const char* to_string(DistortionModel model);

struct CameraModel {
  std::string name;    ///< camera_info camera_name, or the URDF sensor name
  std::string source;  ///< where it came from (file, "urdf:FILE sensor NAME")
  int width_px = 0;
  int height_px = 0;
  double fx_px = 0.0, fy_px = 0.0;  ///< focal lengths
  double cx_px = 0.0, cy_px = 0.0;  ///< principal point
  double skew = 0.0;                ///< K(0,1); 0 for every real camera ferret meets
  DistortionModel distortion = DistortionModel::kNone;
  /// k1, k2, p1, p2, k3 (plumb_bob); all zero for kNone.
  std::array<double, 5> distortion_coefficients{0.0, 0.0, 0.0, 0.0, 0.0};
  /// camera_info's R: rotation of the rectified frame (identity for a monocular camera).
  Eigen::Matrix3d rectification = Eigen::Matrix3d::Identity();
  /// camera_info's P: the rectified camera's 3x4 projection ([K | 0] for monocular).
  Eigen::Matrix<double, 3, 4> projection = Eigen::Matrix<double, 3, 4>::Zero();

  /// An ideal camera with square pixels, the principal point at the image centre and
  /// no distortion: the URDF/Gazebo <camera> model (fx = (w/2) / tan(hfov/2)).
  [[nodiscard]] static CameraModel from_fov(std::string name, int width_px, int height_px,
                                            double horizontal_fov_rad);

  [[nodiscard]] Eigen::Matrix3d K() const;
  [[nodiscard]] double horizontal_fov_rad() const;  ///< of the undistorted pinhole
  [[nodiscard]] double vertical_fov_rad() const;
  [[nodiscard]] bool has_distortion() const;

  /// Pixel of a point in C (distortion applied); nullopt when the point is not in
  /// front of the camera (z <= 0). The pixel may lie outside the image.
  [[nodiscard]] std::optional<Eigen::Vector2d> project(const Eigen::Vector3d& p_C) const;
  /// Distortion applied to normalised image coordinates (x/z, y/z).
  [[nodiscard]] Eigen::Vector2d distort(const Eigen::Vector2d& xy_normalised) const;
  /// Inverse of distort(), iteratively (converges for the distortion of real lenses
  /// inside the image; returns the best estimate after a bounded number of steps).
  [[nodiscard]] Eigen::Vector2d undistort(const Eigen::Vector2d& xy_distorted) const;
  /// The ray through a pixel in C, scaled to z = 1 (distortion removed).
  [[nodiscard]] Eigen::Vector3d ray(const Eigen::Vector2d& pixel) const;
  /// True when the pixel lies inside the image (with `margin_px` of border excluded).
  [[nodiscard]] bool in_image(const Eigen::Vector2d& pixel, double margin_px = 0.0) const;

  /// Throws InputError (source = `source`) unless sizes are positive and at most
  /// 16384 px, focal lengths positive, the principal point inside the image, every
  /// value finite and R a rotation.
  void check() const;
};

/// The pose of the optical frame C in a URDF/Gazebo sensor frame S (S: x forward, y
/// left, z up; C: x right, y down, z forward). Pose of the optical frame in the base
/// frame: X_BS * X_SC().
[[nodiscard]] Pose3 X_SC();

/// The camera a URDF describes (its Gazebo <camera> / <depth_camera> block).
[[nodiscard]] CameraModel camera_model(const CameraSensor& sensor, const std::string& urdf_source);

}  // namespace ferret
