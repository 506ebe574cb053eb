#include "ferret/uav/opening_locator.hpp"

#include <cmath>

namespace ferret {

OpeningInMarker opening_in_marker(const HiddenSpace& space) {
  OpeningInMarker out;
  out.marker_id = space.marker.id;
  const Pose3 X_MW = space.marker.X_WM.inverse();
  out.p_ME = X_MW * space.p_WE;
  const Eigen::Vector3d heading_W{std::cos(space.entry_yaw_rad), std::sin(space.entry_yaw_rad), 0};
  out.entry_direction_M = X_MW.linear() * heading_W;
  return out;
}

OpeningEstimate locate_opening(const MarkerDetection& detection, const Pose3& X_WC,
                               const OpeningInMarker& opening) {
  OpeningEstimate out;
  out.X_WM = X_WC * detection.X_CM;
  out.p_WE = out.X_WM * opening.p_ME;
  const Eigen::Vector3d heading_W = out.X_WM.linear() * opening.entry_direction_M;
  out.entry_yaw_rad = std::atan2(heading_W.y(), heading_W.x());
  return out;
}

MarkerDetectorOptions marker_detector_options(const FiducialMarker& marker) {
  MarkerDetectorOptions o;
  o.dictionary = marker.dictionary;
  o.marker_size_m = marker.size_m;
  return o;
}

}  // namespace ferret
