// The overlay `ferret detect marker -o` writes.

#include <fmt/format.h>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>

#include "ferret/uav/marker_detector.hpp"

namespace ferret {

RgbImage draw_marker_overlay(const GrayImage& image, const CameraModel& camera,
                             const std::vector<MarkerDetection>& detections, double axis_length_m) {
  internal::check_frame(image, camera);
  const cv::Mat gray(image.height_px, image.width_px, CV_8UC1,
                     const_cast<std::uint8_t*>(image.data.data()));
  cv::Mat rgb;
  cv::cvtColor(gray, rgb, cv::COLOR_GRAY2RGB);
  // Lines scale with the frame so the overlay reads at any resolution.
  const int thick = std::max(1, image.width_px / 640);
  auto pt = [](const Eigen::Vector2d& p) { return cv::Point2d(p.x(), p.y()); };
  for (const auto& d : detections) {
    for (int k = 0; k < 4; ++k)
      cv::line(rgb, pt(d.corners_px[k]), pt(d.corners_px[(k + 1) % 4]), {0, 255, 0}, thick,
               cv::LINE_AA);
    cv::circle(rgb, pt(d.corners_px[0]), 3 * thick, {255, 0, 255}, thick, cv::LINE_AA);
    const auto origin = camera.project(d.X_CM.translation());
    const std::array<cv::Scalar, 3> colour{cv::Scalar{255, 0, 0}, cv::Scalar{0, 255, 0},
                                           cv::Scalar{0, 0, 255}};
    for (int a = 0; a < 3 && origin; ++a) {
      const auto tip = camera.project(d.X_CM * (axis_length_m * Eigen::Vector3d::Unit(a)));
      if (tip) cv::line(rgb, pt(*origin), pt(*tip), colour[a], 2 * thick, cv::LINE_AA);
    }
    cv::putText(rgb, fmt::format("#{}", d.id), pt(d.corners_px[0]) + cv::Point2d(4, -6),
                cv::FONT_HERSHEY_SIMPLEX, 0.6 * thick, {255, 255, 0}, thick, cv::LINE_AA);
  }
  RgbImage out(image.width_px, image.height_px);
  for (int y = 0; y < rgb.rows; ++y)
    for (int x = 0; x < rgb.cols; ++x)
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = rgb.at<cv::Vec3b>(y, x)[c];
  return out;
}

}  // namespace ferret
