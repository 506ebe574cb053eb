// The detector-independent part of marker detection: options, the factory, and the
// pose fit both detectors share (so AprilTag and ArUco poses differ only by their
// corners).

#include "ferret/uav/marker_detector.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>
#include <tuple>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "marker_detectors.hpp"

namespace ferret {

void MarkerDetectorOptions::check(const std::string& source) const {
  check_marker_dictionary(dictionary, source, "dictionary");
  check_number(marker_size_m, NumberRange::positive(100.0, "m"), source, "marker_size_m");
  if (max_hamming < 0 || max_hamming > 3)
    throw InputError(source, "max_hamming", "an integer in [0, 3]", std::to_string(max_hamming));
  check_number(min_marker_side_px, NumberRange::closed(4.0, 4096.0, "px"), source,
               "min_marker_side_px");
  check_number(min_decision_margin, NumberRange::non_negative(255.0), source,
               "min_decision_margin");
  check_number(quad_decimate, NumberRange::closed(1.0, 8.0), source, "quad_decimate");
  if (apriltag_min_white_black_diff < 0 || apriltag_min_white_black_diff > 255)
    throw InputError(source, "apriltag_min_white_black_diff", "an integer in [0, 255]",
                     std::to_string(apriltag_min_white_black_diff));
  check_number(quad_sigma, NumberRange::non_negative(10.0, "px"), source, "quad_sigma");
  check_number(decode_sharpening, NumberRange::non_negative(10.0), source, "decode_sharpening");
  check_number(aruco_error_correction_rate, NumberRange::non_negative(1.0), source,
               "aruco_error_correction_rate");
  check_number(aruco_min_margin, NumberRange::non_negative(1.0), source, "aruco_min_margin");
  check_number(aruco_candidate_blur_px, NumberRange::non_negative(2.0, "px"), source,
               "aruco_candidate_blur_px");
  check_number(aruco_threshold_constant, NumberRange::non_negative(255.0), source,
               "aruco_threshold_constant");
  check_number(max_reprojection_error_px, NumberRange::positive(1000.0, "px"), source,
               "max_reprojection_error_px");
}

const char* default_marker_dictionary(MarkerFamily family) {
  return family == MarkerFamily::kAprilTag ? "tag36h11" : "DICT_4X4_50";
}

void register_builtin_marker_detectors(MarkerDetectorRegistry& registry) {
  registry.add(to_string(MarkerFamily::kAprilTag), "AprilTag 3 (the paper's tag36h11)",
               internal::make_apriltag_detector, "AprilTag");
  registry.add(to_string(MarkerFamily::kAruco), "OpenCV 4.6 ArUco", internal::make_aruco_detector,
               "ArUco");
}

const MarkerDetectorRegistry& marker_detectors() {
  return filled_registry<MarkerDetectorRegistry, register_builtin_marker_detectors>();
}

std::unique_ptr<MarkerDetector> make_marker_detector(const MarkerDetectorOptions& options) {
  options.check("marker detector options");
  return marker_detectors().make(to_string(options.dictionary.family), options,
                                 "marker detector options", "dictionary.family");
}

namespace internal {

bool fit_marker_pose(const CameraModel& camera, double marker_size_m, MarkerDetection& d) {
  const double h = marker_size_m / 2;
  // OpenCV's IPPE_SQUARE order, which is M's: x right, y up, z out of the face.
  const std::array<Eigen::Vector3d, 4> p_M{Eigen::Vector3d{-h, h, 0}, Eigen::Vector3d{h, h, 0},
                                           Eigen::Vector3d{h, -h, 0}, Eigen::Vector3d{-h, -h, 0}};
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (int i = 0; i < 4; ++i) {
    object.emplace_back(p_M[i].x(), p_M[i].y(), p_M[i].z());
    image.emplace_back(d.corners_px[i].x(), d.corners_px[i].y());
  }
  cv::Mat K, D;
  cv::eigen2cv(camera.K(), K);
  D = cv::Mat(1, 5, CV_64F);
  for (int i = 0; i < 5; ++i) D.at<double>(0, i) = camera.distortion_coefficients[i];
  // Candidates: IPPE_SQUARE's two solutions, generic IPPE's and SQPnP's (OpenCV 4.6's
  // IPPE solvers return a pose facing away, 100 px off, for a square seen exactly
  // face-on; SQPnP, a global solver, does not), each refined by
  // LM, which spreads the corner noise over all eight residuals. The plausible one
  // (in front, face towards the camera) with the least reprojection error wins.
  std::vector<cv::Mat> rvecs, tvecs;
  for (const int method : {cv::SOLVEPNP_IPPE_SQUARE, cv::SOLVEPNP_IPPE, cv::SOLVEPNP_SQPNP}) {
    std::vector<cv::Mat> r, t;
    cv::solvePnPGeneric(object, image, K, D, r, t, false, static_cast<cv::SolvePnPMethod>(method));
    rvecs.insert(rvecs.end(), r.begin(), r.end());
    tvecs.insert(tvecs.end(), t.begin(), t.end());
  }
  bool found = false;
  double best_sq = 0.0;
  for (std::size_t c = 0; c < rvecs.size(); ++c) {
    cv::Mat rvec = rvecs[c], tvec = tvecs[c];
    cv::solvePnPRefineLM(object, image, K, D, rvec, tvec);
    cv::Mat R;
    cv::Rodrigues(rvec, R);
    Eigen::Matrix3d R_CM;
    Eigen::Vector3d t_CM;
    cv::cv2eigen(R, R_CM);
    cv::cv2eigen(tvec, t_CM);
    if (!R_CM.allFinite() || !t_CM.allFinite()) continue;
    // Plausible: the marker in front of the camera and its printed face towards it.
    if (t_CM.z() <= 0.0 || R_CM.col(2).dot(t_CM) >= 0.0) continue;
    Pose3 X_CM = Pose3::Identity();
    X_CM.linear() = R_CM;
    X_CM.translation() = t_CM;
    double sum_sq = 0.0;
    bool projected = true;
    for (int i = 0; i < 4 && projected; ++i) {
      const auto px = camera.project(X_CM * p_M[i]);
      projected = px.has_value();
      if (px) sum_sq += (*px - d.corners_px[i]).squaredNorm();
    }
    if (!projected || (found && sum_sq >= best_sq)) continue;
    found = true;
    best_sq = sum_sq;
    d.X_CM = X_CM;
  }
  if (!found) return false;
  d.reprojection_error_px = std::sqrt(best_sq / 4);
  return true;
}

void check_frame(const GrayImage& image, const CameraModel& camera) {
  if (image.empty() || image.width_px != camera.width_px || image.height_px != camera.height_px)
    throw InputError(
        "image", "size",
        fmt::format("{}x{} px (the camera {})", camera.width_px, camera.height_px, camera.name),
        fmt::format("{}x{} px", image.width_px, image.height_px));
}

void sort_detections(std::vector<MarkerDetection>& detections) {
  std::sort(detections.begin(), detections.end(), [](const auto& a, const auto& b) {
    return std::tuple(a.id, a.corners_px[0].x(), a.corners_px[0].y()) <
           std::tuple(b.id, b.corners_px[0].x(), b.corners_px[0].y());
  });
}

}  // namespace internal
}  // namespace ferret
