// OpenCV 4.6 ArUco behind MarkerDetector: the project's one use of the cv::aruco
// detection API (4.7 renamed it to ArucoDetector; only this file changes then).

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/aruco.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string_view>
#include <utility>

#include "ferret/core/error.hpp"
#include "ferret/perception/marker_library.hpp"
#include "marker_detectors.hpp"

namespace ferret::internal {
namespace {

class ArucoDetector final : public MarkerDetector {
 public:
  explicit ArucoDetector(const MarkerDetectorOptions& options) : options_(options) {
    if (options.dictionary.family != MarkerFamily::kAruco)
      throw InputError("marker detector options", "dictionary", "an OpenCV ArUco dictionary",
                       options.dictionary.name);
    dictionary_ = aruco_dictionary(options.dictionary);
    params_ = cv::aruco::DetectorParameters::create();
    // Sub-pixel corners from an edge fit (refine_corners below) rather than
    // detectMarkers' own: SUBPIX is biased at blurred marker corners, APRILTAG is
    // accurate but costs hundreds of ms a frame.
    params_->cornerRefinementMethod = cv::aruco::CORNER_REFINE_NONE;
    params_->errorCorrectionRate = options.aruco_error_correction_rate;
    // Small blurred markers (docs/results/markers.md): thresholds over 13 and
    // 23 px only (OpenCV's 3 px window sees pixel noise, never a marker's cell), a
    // lower threshold constant, and each cell read at its centre (30 % of the cell on
    // each side ignored, not 13 %: at 3 px a cell, blur carries the neighbours in).
    params_->adaptiveThreshWinSizeMin = 13;
    params_->adaptiveThreshWinSizeMax = 23;
    params_->adaptiveThreshWinSizeStep = 10;
    params_->adaptiveThreshConstant = options.aruco_threshold_constant;
    params_->perspectiveRemoveIgnoredMarginPerCell = 0.3;
    // A marker whose black square reaches the frame's last pixels is still whole.
    params_->minDistanceToBorder = 0;
    // OpenCV merges candidates whose corners are closer than this share of the
    // perimeter and keeps the outer one. A printed marker's one-cell white margin in
    // front of something darker outlines a square a cell outside the black one, its
    // corners sqrt(2) cells off: 0.35 / cells of the perimeter, below OpenCV's 0.05 for
    // a marker of 8 or more cells across (6x6, 7x7, AprilTag 36h11), which was then
    // lost to its own margin. 0.3 / cells keeps the two apart and still merges the
    // contours the threshold windows find along one edge (a pixel or two apart).
    params_->minMarkerDistanceRate =
        std::min(params_->minMarkerDistanceRate, 0.3 / (dictionary_->markerSize + 2));
  }

  [[nodiscard]] const MarkerDetectorOptions& options() const override { return options_; }

  [[nodiscard]] std::vector<MarkerDetection> detect(const GrayImage& image,
                                                    const CameraModel& camera) const override {
    check_frame(image, camera);
    const cv::Mat frame(image.height_px, image.width_px, CV_8UC1,
                        const_cast<std::uint8_t*>(image.data.data()));
    std::vector<std::vector<cv::Point2f>> corners;
    std::vector<int> ids;
    // Contours shorter than the smallest marker's perimeter are not looked at.
    auto params = cv::makePtr<cv::aruco::DetectorParameters>(*params_);
    params->minMarkerPerimeterRate =
        4 * options_.min_marker_side_px / std::max(image.width_px, image.height_px);
    if (options_.aruco_candidate_blur_px > 0) {
      cv::Mat smoothed;
      cv::GaussianBlur(frame, smoothed, cv::Size(3, 3), options_.aruco_candidate_blur_px);
      cv::aruco::detectMarkers(smoothed, dictionary_, corners, ids, params);
    } else {
      cv::aruco::detectMarkers(frame, dictionary_, corners, ids, params);
    }
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

  // Corners as the intersections of lines fitted to the four edges, each edge found to
  // sub-pixel precision as the gradient maximum across it. cornerSubPix (OpenCV's
  // CORNER_REFINE_SUBPIX) is made for saddle points: at a blurred L-shaped marker
  // corner it converges inside the black square, and the marker looks about 1 %
  // smaller (2.6 cm of range at 3 m on the simulator's frames). The edge fit is
  // AprilTag's refine_edges idea, and unbiased for any symmetric blur.
  void refine_corners(const cv::Mat& frame, std::vector<cv::Point2f>& corners) const {
    // Search across each edge at most 40 % of a cell: the black border is one cell wide,
    // and a white data cell behind it makes an inner edge as strong as the outer one.
    double shortest = 1e9;
    for (int k = 0; k < 4; ++k)
      shortest =
          std::min(shortest, static_cast<double>(cv::norm(corners[k] - corners[(k + 1) % 4])));
    const double reach_px = std::clamp(0.4 * shortest / (dictionary_->markerSize + 2), 0.75, 2.5);
    const int steps = static_cast<int>(reach_px / 0.25);
    auto grey = [&](double x, double y) {
      const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
      if (x0 < 0 || y0 < 0 || x0 + 1 >= frame.cols || y0 + 1 >= frame.rows) return -1.0;
      const double fx = x - x0, fy = y - y0;
      const auto at = [&](int xx, int yy) {
        return static_cast<double>(frame.at<std::uint8_t>(yy, xx));
      };
      return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
             fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
    };
    std::array<cv::Vec3d, 4> lines;  // a x + b y = c, (a, b) unit
    for (int e = 0; e < 4; ++e) {
      const cv::Point2d p0 = corners[e], p1 = corners[(e + 1) % 4];
      const cv::Point2d along = p1 - p0;
      const double length = cv::norm(along);
      if (length < 4.0) return;
      const cv::Point2d t = along / length, n{-t.y, t.x};
      std::vector<cv::Point2d> points;
      const int samples = std::clamp(static_cast<int>(length / 2), 4, 40);
      for (int i = 0; i < samples; ++i) {
        // The middle of the edge only: near the corners the other edge bends the profile.
        const cv::Point2d c = p0 + along * (0.15 + 0.7 * (i + 0.5) / samples);
        // Profile across the edge at 0.25 px steps, +-2.5 px; its steepest point.
        constexpr int kHalf = 10;
        std::array<double, 2 * kHalf + 1> g{};
        g.fill(-1.0);
        bool ok = true;
        for (int k = -steps; k <= steps && ok; ++k) {
          const double v = grey(c.x + n.x * k * 0.25, c.y + n.y * k * 0.25);
          ok = v >= 0;
          g[static_cast<std::size_t>(k + kHalf)] = v;
        }
        if (!ok) continue;
        int best = -1;
        double best_d = 0.0;
        for (int k = kHalf - steps + 1; k < kHalf + steps; ++k) {
          const double d =
              std::abs(g[static_cast<std::size_t>(k + 1)] - g[static_cast<std::size_t>(k - 1)]);
          if (d > best_d) best_d = d, best = k;
        }
        if (best <= kHalf - steps + 1 || best >= kHalf + steps - 1 || best_d < 4.0) continue;
        auto grad = [&](int k) {
          return std::abs(g[static_cast<std::size_t>(k + 1)] - g[static_cast<std::size_t>(k - 1)]);
        };
        const double gm = grad(best - 1), g0 = grad(best), gp = grad(best + 1);
        const double den = gm - 2 * g0 + gp;
        const double sub = den < 0 ? 0.5 * (gm - gp) / den : 0.0;
        points.push_back(c + n * ((best - kHalf + sub) * 0.25));
      }
      if (points.size() < 3) return;  // keep the detector's corners
      cv::Vec4d fit;
      cv::fitLine(points, fit, cv::DIST_L2, 0, 0.01, 0.01);
      const double a = -fit[1], b = fit[0];
      lines[static_cast<std::size_t>(e)] = {a, b, a * fit[2] + b * fit[3]};
    }
    std::vector<cv::Point2f> refined(4);
    for (int k = 0; k < 4; ++k) {
      // Corner k joins edge k-1 (from corner k-1) and edge k (to corner k+1).
      const cv::Vec3d& l1 = lines[static_cast<std::size_t>((k + 3) % 4)];
      const cv::Vec3d& l2 = lines[static_cast<std::size_t>(k)];
      const double det = l1[0] * l2[1] - l1[1] * l2[0];
      if (std::abs(det) < 1e-9) return;
      const cv::Point2f p(static_cast<float>((l1[2] * l2[1] - l1[1] * l2[2]) / det),
                          static_cast<float>((l1[0] * l2[2] - l1[2] * l2[0]) / det));
      if (cv::norm(p - corners[k]) > 3.0) return;  // a fit gone astray: keep the detector's
      refined[static_cast<std::size_t>(k)] = p;
    }
    corners = refined;
  }

 private:
  // The decode's margin: the marker rectified to 8 px a cell, each cell's central mean;
  // over every pair of neighbouring cells the decoded id says differ, the white one's
  // mean less the black one's, over the contrast (brightest less darkest cell), and the
  // least of these. Blur of a small marker pulls an isolated white cell far towards
  // black, so a threshold between the darkest and brightest cell misreads it, but it
  // stays brighter than its black neighbours. A pattern decoded by luck, or a marker
  // half covered, has a pair the wrong way round or level.
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
    const auto white = [&](int x, int y) { return expected.at<std::uint8_t>(y, x) > 127; };
    const auto at = [&](int x, int y) { return mean[static_cast<std::size_t>(y * cells + x)]; };
    double least = 1.0;
    int pairs = 0;
    for (int y = 0; y < cells; ++y)
      for (int x = 0; x < cells; ++x)
        for (const auto& [x2, y2] : {std::pair{x + 1, y}, std::pair{x, y + 1}}) {
          if (x2 >= cells || y2 >= cells || white(x, y) == white(x2, y2)) continue;
          const double brighter = white(x, y) ? at(x, y) - at(x2, y2) : at(x2, y2) - at(x, y);
          least = std::min(least, brighter / contrast);
          ++pairs;
        }
    return pairs > 0 ? least : -1.0;  // an all-black code is any dark square
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
