#pragma once
// The two implementations behind make_marker_detector (private to ferret::uav).

#include <memory>

#include "ferret/uav/marker_detector.hpp"

namespace ferret::internal {

[[nodiscard]] std::unique_ptr<MarkerDetector> make_apriltag_detector(
    const MarkerDetectorOptions& options);
[[nodiscard]] std::unique_ptr<MarkerDetector> make_aruco_detector(
    const MarkerDetectorOptions& options);

}  // namespace ferret::internal
