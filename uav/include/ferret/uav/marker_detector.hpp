#pragma once
// Fiducial marker detection on a grey camera frame: one interface, two
// implementations (AprilTag 3 and OpenCV 4.6 ArUco) on a registry, marker_detectors(),
// looked up by the dictionary's family ("apriltag", "aruco"). Each detection carries the marker's
// four corners, its pose X_CM in the camera's optical frame C (x right, y down, z forward) and the
// pose fit's reprojection error.
//
// The marker frame M is the world YAML's: origin at the centre of the black square,
// z out of the printed face, x right and y up in the marker image. The black square
// has side `marker_size_m` (the tag-size convention of both libraries).

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/core/registry.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/image.hpp"
#include "ferret/perception/marker_family.hpp"

namespace ferret {

struct MarkerDetection {
  int id = -1;
  /// Corners of the black square in pixels (distorted image, as seen), in OpenCV's
  /// order for both detectors: top-left, top-right, bottom-right, bottom-left of the
  /// marker image (M's (-s/2, s/2), (s/2, s/2), (s/2, -s/2), (-s/2, -s/2)).
  std::array<Eigen::Vector2d, 4> corners_px{};
  Pose3 X_CM = Pose3::Identity();  ///< the marker in the camera's optical frame
  /// RMS over the four corners of |project(X_CM * corner_M) - corners_px|.
  double reprojection_error_px = 0.0;
  /// Decode quality. AprilTag: the library's decision margin (mean difference between
  /// the bit intensity and the threshold, 0..255). ArUco: the fraction of the marker's
  /// border cells that read black (0..1); both larger is better.
  double decision_margin = 0.0;
  int hamming = 0;  ///< bits corrected in the decode (AprilTag; 0 for ArUco)
};

struct MarkerDetectorOptions {
  MarkerDictionary dictionary;  ///< ArUco DICT_4X4_50 unless set
  double marker_size_m = 0.15;  ///< side of the black square
  /// Bits the AprilTag decoder may correct. tag36h11's codes are at least 11 bits
  /// apart, so one corrected bit still leaves a random pattern far from a valid code;
  /// with min_decision_margin 15 it recovers small blurred markers whose one cell
  /// reads wrong (docs/results/markers.md).
  int max_hamming = 1;
  /// The smallest marker side (black square, pixels) the detectors look for: shorter
  /// candidates are dropped before decoding, which is most of a textured frame's. The
  /// issue's target is 20 px; 16 leaves a margin for foreshortening and blur.
  double min_marker_side_px = 16.0;
  /// AprilTag: the decoder's minimum decision margin (detections below are noise).
  /// 30 (with max_hamming 0) dropped markers of 20-24 px under blur of 1.1-1.5 px.
  double min_decision_margin = 15.0;
  /// AprilTag quad_decimate: the quad search runs on a frame this much smaller (the
  /// corners are then refined on the full frame). 1 costs about 60 ms a 1280x720
  /// textured frame on one core here, 2 about 3 ms, and finds the same markers of
  /// 20 px and more on the simulator's frames (docs/results/markers.md).
  double quad_decimate = 2.0;
  /// AprilTag qtp.min_white_black_diff: the least grey-level difference between a
  /// candidate's dark and light side. The library's 5 lets every texture edge of an
  /// outdoor frame through (about 15 ms more a frame); 20 is still far below a printed
  /// marker's contrast at exposure 0.6.
  int apriltag_min_white_black_diff = 20;
  /// AprilTag quad_sigma: Gaussian blur (pixels) before the quad search; 0 = none.
  double quad_sigma = 0.0;
  /// AprilTag decode_sharpening (the library's default 0.25).
  double decode_sharpening = 0.25;
  /// ArUco errorCorrectionRate: the share of the dictionary's correctable bits the
  /// decoder may correct (OpenCV's default 0.6).
  double aruco_error_correction_rate = 0.6;
  /// ArUco: the least decode margin kept (MarkerDetection::decision_margin): over every
  /// pair of neighbouring cells the decoded id says differ, the white cell's mean grey
  /// level less the black one's, over the marker's contrast. Blur lowers an isolated
  /// white cell of a small marker towards its black neighbours but never below them; a
  /// wrong id, or a marker half covered, has a pair the wrong way round
  /// (docs/results/markers.md).
  double aruco_min_margin = 0.08;
  /// ArUco: Gaussian blur (pixels) of the frame the candidates are searched in (the
  /// corners and the margin read the frame itself). The camera's pixel noise makes the
  /// adaptive threshold fray into thousands of speckle contours at the low
  /// aruco_threshold_constant; a 3x3 blur of 0.6 px removes them and costs a marker
  /// already blurred by 1.3 px little. 0 = none; at most 2 (the kernel is 3x3).
  double aruco_candidate_blur_px = 0.6;
  /// ArUco adaptiveThreshConstant: how much darker than its 13 or 23 px neighbourhood a
  /// pixel must be to count as black. OpenCV's 7 loses the black border of a marker of
  /// 20-24 px blurred by 1.1-1.5 px at exposure 0.6-0.8.
  double aruco_threshold_constant = 5.0;
  /// Detections whose pose fit is worse than this are dropped (a quad that is not a
  /// flat square seen through this camera).
  double max_reprojection_error_px = 3.0;

  /// Throws InputError(source, field...) for an unknown dictionary, a size that is not
  /// finite and in (0, 100] m, or an option out of its range.
  void check(const std::string& source) const;
};

class MarkerDetector {
 public:
  virtual ~MarkerDetector() = default;
  /// Markers of the configured dictionary in `image`, seen through `camera` (the image
  /// must have the camera's size: InputError otherwise). Sorted by id, then by
  /// top-left corner (x, y), so the output does not depend on the library's order.
  [[nodiscard]] virtual std::vector<MarkerDetection> detect(const GrayImage& image,
                                                            const CameraModel& camera) const = 0;
  [[nodiscard]] virtual const MarkerDetectorOptions& options() const = 0;
};

using MarkerDetectorRegistry = Registry<MarkerDetector, MarkerDetectorOptions>;

/// Adds "apriltag" (AprilTag 3) and "aruco" (OpenCV ArUco), one a family.
void register_builtin_marker_detectors(MarkerDetectorRegistry& registry);
/// The marker detectors by family name (to_string(MarkerFamily)), registered on first use.
[[nodiscard]] const MarkerDetectorRegistry& marker_detectors();

/// The detector of marker_detectors() for the dictionary's family: AprilTag 3 for
/// kAprilTag dictionaries, OpenCV ArUco for kAruco. Checks the options first
/// (InputError with source "marker detector options").
[[nodiscard]] std::unique_ptr<MarkerDetector> make_marker_detector(
    const MarkerDetectorOptions& options);

/// The default dictionary of a family: tag36h11 (AprilTag, the paper's family) and
/// DICT_4X4_50 (ArUco, the world YAML's default).
[[nodiscard]] const char* default_marker_dictionary(MarkerFamily family);

/// A picture of the detections for a person: the frame in colour, each marker's
/// outline (green, its first corner marked), its id, and its axes from the pose (x red,
/// y green, z blue, `axis_length_m` long; z drawn out of the face).
[[nodiscard]] RgbImage draw_marker_overlay(const GrayImage& image, const CameraModel& camera,
                                           const std::vector<MarkerDetection>& detections,
                                           double axis_length_m);

namespace internal {
/// The shared pose step of both detectors: IPPE_SQUARE solvePnP on the undistorted
/// corners (OpenCV order), the reprojection error through the full camera model.
/// Returns false for an implausible pose (marker behind or at the camera, or its face
/// turned away from it).
bool fit_marker_pose(const CameraModel& camera, double marker_size_m, MarkerDetection& detection);
/// InputError unless the image has the camera's size and is not empty.
void check_frame(const GrayImage& image, const CameraModel& camera);
/// Sorts detections into the interface's order.
void sort_detections(std::vector<MarkerDetection>& detections);
}  // namespace internal

}  // namespace ferret
