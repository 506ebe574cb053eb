// The object detector's overlay: the frame with each detection's box, centroid and
// values, for a person to check what the detector saw.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "ferret/core/pose.hpp"
#include "ferret/ugv/object_detector.hpp"

namespace ferret::ugv {

RgbImage draw_object_overlay(const RgbImage& image,
                             const std::vector<ObjectDetection>& detections) {
  RgbImage out = image;
  if (out.empty()) return out;
  cv::Mat m(out.height_px, out.width_px, CV_8UC3, out.data.data());
  // Small frames (160 x 120) get small text; the scale follows the image width.
  const double scale = std::clamp(out.width_px / 1600.0, 0.3, 1.0);
  const int thick = out.width_px >= 1000 ? 2 : 1;
  const cv::Scalar box_rgb(0, 255, 0), text_rgb(255, 255, 255), shadow_rgb(0, 0, 0);
  for (std::size_t k = 0; k < detections.size(); ++k) {
    const ObjectDetection& d = detections[k];
    const cv::Rect r(d.box.x_px - 1, d.box.y_px - 1, d.box.width_px + 2, d.box.height_px + 2);
    cv::rectangle(m, r, box_rgb, thick);
    const cv::Point c(static_cast<int>(std::lround(d.centroid_px.x())),
                      static_cast<int>(std::lround(d.centroid_px.y())));
    cv::drawMarker(m, c, box_rgb, cv::MARKER_CROSS, 5, 1);
    const std::string text = fmt::format("#{} d={:.2f}m conf={:.2f} b={:+.1f}deg", k, d.distance_m,
                                         d.confidence, rad_to_deg(d.bearing_rad));
    int baseline = 0;
    const cv::Size ts = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, thick, &baseline);
    // Above the box where there is room, else below it; kept inside the frame.
    int x = std::clamp(r.x, 0, std::max(0, out.width_px - ts.width));
    int y = r.y - 3 >= ts.height ? r.y - 3 : r.y + r.height + ts.height + 3;
    y = std::clamp(y, ts.height, std::max(ts.height, out.height_px - baseline));
    cv::putText(m, text, {x + 1, y + 1}, cv::FONT_HERSHEY_SIMPLEX, scale, shadow_rgb, thick,
                cv::LINE_AA);
    cv::putText(m, text, {x, y}, cv::FONT_HERSHEY_SIMPLEX, scale, text_rgb, thick, cv::LINE_AA);
  }
  return out;
}

}  // namespace ferret::ugv
