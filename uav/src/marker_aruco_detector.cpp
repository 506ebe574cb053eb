// OpenCV 4.6 ArUco behind MarkerDetector: the project's one use of the cv::aruco
// detection API (4.7 renamed it to ArucoDetector; only this file changes then).

#include <algorithm>
#include <cmath>
#include <opencv2/aruco.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string_view>

#include "ferret/core/error.hpp"
#include "marker_detectors.hpp"

namespace ferret::internal {
namespace {

struct ArucoEntry {
  const char* name;
  cv::aruco::PREDEFINED_DICTIONARY_NAME id;
};
// Every dictionary perception's marker_family knows (a test checks that each name
// makes a detector).
constexpr ArucoEntry kDictionaries[] = {
    {"DICT_4X4_50", cv::aruco::DICT_4X4_50},
    {"DICT_4X4_100", cv::aruco::DICT_4X4_100},
    {"DICT_4X4_250", cv::aruco::DICT_4X4_250},
    {"DICT_4X4_1000", cv::aruco::DICT_4X4_1000},
    {"DICT_5X5_50", cv::aruco::DICT_5X5_50},
    {"DICT_5X5_100", cv::aruco::DICT_5X5_100},
    {"DICT_5X5_250", cv::aruco::DICT_5X5_250},
    {"DICT_5X5_1000", cv::aruco::DICT_5X5_1000},
    {"DICT_6X6_50", cv::aruco::DICT_6X6_50},
    {"DICT_6X6_100", cv::aruco::DICT_6X6_100},
    {"DICT_6X6_250", cv::aruco::DICT_6X6_250},
    {"DICT_6X6_1000", cv::aruco::DICT_6X6_1000},
    {"DICT_7X7_50", cv::aruco::DICT_7X7_50},
    {"DICT_7X7_100", cv::aruco::DICT_7X7_100},
    {"DICT_7X7_250", cv::aruco::DICT_7X7_250},
    {"DICT_7X7_1000", cv::aruco::DICT_7X7_1000},
    {"DICT_ARUCO_ORIGINAL", cv::aruco::DICT_ARUCO_ORIGINAL},
    {"DICT_APRILTAG_16h5", cv::aruco::DICT_APRILTAG_16h5},
    {"DICT_APRILTAG_25h9", cv::aruco::DICT_APRILTAG_25h9},
    {"DICT_APRILTAG_36h10", cv::aruco::DICT_APRILTAG_36h10},
    {"DICT_APRILTAG_36h11", cv::aruco::DICT_APRILTAG_36h11},
};

class ArucoDetector final : public MarkerDetector {
 public:
  explicit ArucoDetector(const MarkerDetectorOptions& options) : options_(options) {
    const ArucoEntry* entry = nullptr;
    for (const auto& e : kDictionaries)
      if (options.dictionary.name == e.name) entry = &e;
    if (entry == nullptr)
      throw InputError("marker detector options", "dictionary", "an OpenCV ArUco dictionary",
                       options.dictionary.name);
    dictionary_ = cv::aruco::getPredefinedDictionary(entry->id);
    params_ = cv::aruco::DetectorParameters::create();
    // Sub-pixel corners, refined here per marker (below) rather than by detectMarkers:
    // OpenCV 4.6 uses one window for every marker, and a 5 px half-window reaches the
    // data cells of a small marker and pulls its corners off by more than a pixel.
    params_->cornerRefinementMethod = cv::aruco::CORNER_REFINE_NONE;
    params_->errorCorrectionRate = options.aruco_error_correction_rate;
  }

  [[nodiscard]] const MarkerDetectorOptions& options() const override { return options_; }

  [[nodiscard]] std::vector<MarkerDetection> detect(const GrayImage& image,
                                                    const CameraModel& camera) const override {
    check_frame(image, camera);
    const cv::Mat frame(image.height_px, image.width_px, CV_8UC1,
                        const_cast<std::uint8_t*>(image.data.data()));
    std::vector<std::vector<cv::Point2f>> corners;
    std::vector<int> ids;
    cv::aruco::detectMarkers(frame, dictionary_, corners, ids, params_);
    std::vector<MarkerDetection> out;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (ids[i] < 0 || ids[i] >= dictionary_->bytesList.rows) continue;
      refine_corners(frame, corners[i]);
      MarkerDetection d;
      d.id = ids[i];
      // detectMarkers gives the black square's corners in the marker image's order:
      // top-left, top-right, bottom-right, bottom-left.
      for (int k = 0; k < 4; ++k) d.corners_px[k] = {corners[i][k].x, corners[i][k].y};
      d.decision_margin = margin(frame, corners[i], d.id);
      if (options_.aruco_min_margin > 0 && d.decision_margin < options_.aruco_min_margin) continue;
      if (!fit_marker_pose(camera, options_.marker_size_m, d)) continue;
      if (d.reprojection_error_px > options_.max_reprojection_error_px) continue;
      out.push_back(d);
    }
    sort_detections(out);
    return out;
  }

  // cornerSubPix with a half-window inside the marker's black border cell (at most
  // OpenCV's 5 px), so only the corner's two edges are in it.
  void refine_corners(const cv::Mat& frame, std::vector<cv::Point2f>& corners) const {
    double shortest = 1e9;
    for (int k = 0; k < 4; ++k)
      shortest = std::min(shortest, cv::norm(corners[k] - corners[(k + 1) % 4]));
    const double cell_px = shortest / (dictionary_->markerSize + 2);
    const int half = std::clamp(static_cast<int>(cell_px * 0.6), 1, 5);
    cv::cornerSubPix(
        frame, corners, cv::Size(half, half), cv::Size(-1, -1),
        cv::TermCriteria(cv::TermCriteria::MAX_ITER | cv::TermCriteria::EPS, 30, 0.01));
  }

 private:
  // The decode's margin: the marker rectified to 8 px a cell, each cell's central mean
  // compared with the threshold halfway between the darkest and brightest cell, signed
  // by what the decoded id's bit says; the least cell margin over the contrast. A
  // true marker reads clearly on every cell; a pattern decoded by error correction or
  // by luck has a cell on the wrong side or near the threshold.
  [[nodiscard]] double margin(const cv::Mat& frame, const std::vector<cv::Point2f>& corners,
                              int id) const {
    constexpr int kCellPx = 8;
    const int cells = dictionary_->markerSize + 2;
    const float side = static_cast<float>(cells * kCellPx);
    const std::vector<cv::Point2f> square{{0, 0}, {side, 0}, {side, side}, {0, side}};
    // Corners are at pixel centres; the square's edges are half a pixel further out.
    const cv::Mat H = cv::getPerspectiveTransform(corners, square);
    cv::Mat patch;
    cv::warpPerspective(frame, patch, H, cv::Size(cells * kCellPx, cells * kCellPx),
                        cv::INTER_LINEAR);
    cv::Mat expected;
    cv::aruco::drawMarker(dictionary_, id, cells, expected, 1);
    std::vector<double> mean(static_cast<std::size_t>(cells * cells));
    double lo = 255.0, hi = 0.0;
    for (int y = 0; y < cells; ++y)
      for (int x = 0; x < cells; ++x) {
        const cv::Rect inner(x * kCellPx + kCellPx / 4, y * kCellPx + kCellPx / 4, kCellPx / 2,
                             kCellPx / 2);
        const double m = cv::mean(patch(inner))[0];
        mean[static_cast<std::size_t>(y * cells + x)] = m;
        lo = std::min(lo, m);
        hi = std::max(hi, m);
      }
    const double contrast = hi - lo;
    if (contrast <= 0.0) return -1.0;
    const double threshold = (hi + lo) / 2;
    double least = 1.0;
    for (int y = 0; y < cells; ++y)
      for (int x = 0; x < cells; ++x) {
        const double sign = expected.at<std::uint8_t>(y, x) > 127 ? 1.0 : -1.0;
        least = std::min(
            least, sign * (mean[static_cast<std::size_t>(y * cells + x)] - threshold) / contrast);
      }
    return least;
  }

  MarkerDetectorOptions options_;
  cv::Ptr<cv::aruco::Dictionary> dictionary_;
  cv::Ptr<cv::aruco::DetectorParameters> params_;
};

}  // namespace

std::unique_ptr<MarkerDetector> make_aruco_detector(const MarkerDetectorOptions& options) {
  return std::make_unique<ArucoDetector>(options);
}

}  // namespace ferret::internal
