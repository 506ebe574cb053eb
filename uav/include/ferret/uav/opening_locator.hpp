#pragma once
// From a marker detection to the hidden space's opening. The detection gives the
// marker in the camera (X_CM); the UAV's state gives the camera in the world (X_WC);
// the world's marker placement gives where the opening's entry E lies in the marker's
// frame (p_ME) and which way drives into it. Composing them is the estimate the
// mission flies to: X_WM = X_WC * X_CM, p_WE = X_WM * p_ME.

#include <Eigen/Core>

#include "ferret/core/pose.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "ferret/uav/marker_detector.hpp"

namespace ferret {

/// Where a hidden space's opening lies relative to its marker: the entry point E (the
/// bottom centre of the opening, on its outer face) and the unit direction that drives
/// from E into the interior, both in the marker frame M.
struct OpeningInMarker {
  int marker_id = 0;
  Eigen::Vector3d p_ME = Eigen::Vector3d::Zero();
  Eigen::Vector3d entry_direction_M = -Eigen::Vector3d::UnitZ();
};

/// The relation as the world YAML places the marker (wall, roof, ground or an explicit
/// pose): p_ME = X_WM^-1 p_WE, the entry heading rotated into M.
[[nodiscard]] OpeningInMarker opening_in_marker(const HiddenSpace& space);

struct OpeningEstimate {
  Pose3 X_WM = Pose3::Identity();  ///< the marker in the world
  Eigen::Vector3d p_WE = Eigen::Vector3d::Zero();
  double entry_yaw_rad = 0.0;  ///< heading in the world that drives into the interior
};

/// The opening from one detection, given the camera's pose in the world.
[[nodiscard]] OpeningEstimate locate_opening(const MarkerDetection& detection, const Pose3& X_WC,
                                             const OpeningInMarker& opening);

/// The detector options that read a world's marker: its dictionary and size.
[[nodiscard]] MarkerDetectorOptions marker_detector_options(const FiducialMarker& marker);

}  // namespace ferret
