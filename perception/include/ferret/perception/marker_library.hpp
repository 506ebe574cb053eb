#pragma once
// The marker libraries' own handles for a MarkerDictionary: one table of names for the
// marker bitmaps (perception) and the detectors (uav), so the two cannot drift apart.
// An extension point of OpenCV's ArUco module and AprilTag 3: include it only from
// sources that call those libraries (it brings their headers).

#include <apriltag.h>

#include <memory>
#include <opencv2/aruco.hpp>

#include "ferret/perception/marker_family.hpp"

namespace ferret {

/// OpenCV's predefined dictionary of an ArUco MarkerDictionary; InputError for a name
/// OpenCV 4.6 does not define (or an AprilTag family).
[[nodiscard]] cv::Ptr<cv::aruco::Dictionary> aruco_dictionary(const MarkerDictionary& dictionary);

using AprilTagFamilyPtr = std::unique_ptr<apriltag_family_t, void (*)(apriltag_family_t*)>;
/// A new AprilTag 3 family object (freed by the library's own destroy function);
/// InputError for a name the library does not define (or an ArUco dictionary).
[[nodiscard]] AprilTagFamilyPtr apriltag_family(const MarkerDictionary& dictionary);

}  // namespace ferret
