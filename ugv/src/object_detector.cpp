#include "ferret/ugv/object_detector.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <utility>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"

namespace ferret::ugv {
namespace {

// OpenCV's 8-bit HSV: hue in [0, 180) (2 degrees a step), saturation and value in
// [0, 255].
constexpr double kDegPerHueStep = 2.0;

double hue_deg_of(const std::array<std::uint8_t, 3>& rgb) {
  cv::Mat px(1, 1, CV_8UC3, cv::Scalar(rgb[0], rgb[1], rgb[2]));
  cv::Mat hsv;
  cv::cvtColor(px, hsv, cv::COLOR_RGB2HSV);
  return hsv.at<cv::Vec3b>(0, 0)[0] * kDegPerHueStep;
}

// Circular distance between two hues, in degrees.
double hue_gap_deg(double a_deg, double b_deg) {
  const double d = std::fmod(std::abs(a_deg - b_deg), 360.0);
  return std::min(d, 360.0 - d);
}

// The object's pixels: hue within the tolerance (two ranges where the band wraps
// around 0), saturated and bright enough.
cv::Mat colour_mask(const cv::Mat& hsv, double hue_deg, const ColourObjectDetector::Options& o) {
  const int s_min = static_cast<int>(std::ceil(o.min_saturation * 255.0));
  const int v_min = static_cast<int>(std::ceil(o.min_value * 255.0));
  const int lo = static_cast<int>(std::ceil((hue_deg - o.hue_tolerance_deg) / kDegPerHueStep));
  const int hi = static_cast<int>(std::floor((hue_deg + o.hue_tolerance_deg) / kDegPerHueStep));
  cv::Mat mask;
  const auto in_range = [&](int h0, int h1) {
    cv::Mat m;
    cv::inRange(hsv, cv::Scalar(h0, s_min, v_min), cv::Scalar(h1, 255, 255), m);
    return m;
  };
  if (lo >= 0 && hi <= 179) {
    mask = in_range(lo, hi);
  } else if (lo < 0) {
    cv::bitwise_or(in_range(0, hi), in_range(180 + lo, 179), mask);
  } else {
    cv::bitwise_or(in_range(lo, 179), in_range(0, hi - 180), mask);
  }
  if (o.open_kernel_px > 1) {
    const cv::Mat kernel =
        cv::getStructuringElement(cv::MORPH_RECT, cv::Size(o.open_kernel_px, o.open_kernel_px));
    cv::morphologyEx(mask, mask, cv::MORPH_OPEN, kernel);
  }
  return mask;
}

// Depth z of an object whose extent along one image axis spans the pixel interval
// [a - 0.5, b + 0.5] at the other coordinate `at`: size_m over the extent of the
// undistorted rays at z = 1.
double depth_from_extent(const CameraModel& camera, bool vertical, double a, double b, double at,
                         double size_m) {
  const Eigen::Vector2d p0 = vertical ? Eigen::Vector2d(at, a - 0.5) : Eigen::Vector2d(a - 0.5, at);
  const Eigen::Vector2d p1 = vertical ? Eigen::Vector2d(at, b + 0.5) : Eigen::Vector2d(b + 0.5, at);
  const Eigen::Vector3d r0 = camera.ray(p0), r1 = camera.ray(p1);
  const double extent = vertical ? r1.y() - r0.y() : r1.x() - r0.x();
  return size_m / std::max(extent, 1e-9);
}

void check_in(const std::string& source, const std::string& field, double value,
              const NumberRange& range) {
  (void)check_number(value, range, source, "object_detector." + field);
}

}  // namespace

const char* to_string(SizeAxis axis) { return axis == SizeAxis::kHeight ? "height" : "width"; }

::ferret::ObjectDetection to_map_detection(const ObjectDetection& d) {
  return {d.bearing_rad, d.distance_m, d.confidence};
}

void ColourObjectDetector::Options::check(const std::string& source) const {
  check_in(source, "hue_tolerance_deg", hue_tolerance_deg, NumberRange::positive(90.0, "deg"));
  check_in(source, "min_saturation", min_saturation, NumberRange::closed(0.0, 1.0));
  check_in(source, "min_value", min_value, NumberRange::closed(0.0, 1.0));
  check_in(source, "object_width_m", object_width_m, NumberRange::positive(100.0, "m"));
  check_in(source, "object_height_m", object_height_m, NumberRange::positive(100.0, "m"));
  check_in(source, "object_depth_m", object_depth_m, NumberRange::non_negative(100.0, "m"));
  if (open_kernel_px < 1 || open_kernel_px > 31 || open_kernel_px % 2 == 0)
    throw InputError(source, "object_detector.open_kernel_px", "an odd integer in [1, 31] px",
                     std::to_string(open_kernel_px));
  if (min_area_px < 1 || min_area_px > 1'000'000)
    throw InputError(source, "object_detector.min_area_px", "an integer in [1, 1000000] px",
                     std::to_string(min_area_px));
  check_in(source, "min_fill_ratio", min_fill_ratio, NumberRange::closed(0.0, 1.0));
  check_in(source, "min_purity", min_purity, NumberRange::closed(0.0, 1.0));
  check_in(source, "full_visibility_px", full_visibility_px, NumberRange::positive(1e4, "px"));
  check_in(source, "max_distance_m", max_distance_m, NumberRange::non_negative(1e6, "m"));
  check_in(source, "search.eta_m", search.eta_m, NumberRange::positive(1e6, "m"));
  check_in(source, "search.conf_floor", search.conf_floor, NumberRange::closed(0.5, 1.0));
  check_in(source, "search.conf_cap", search.conf_cap, NumberRange::closed(0.5, 1.0));
  // The object's own colour must pass the mask (a grey has no hue to look for).
  const auto& c = colour_rgb;
  const int hi = std::max({c[0], c[1], c[2]}), lo = std::min({c[0], c[1], c[2]});
  if (hi == 0 || static_cast<double>(hi - lo) / hi < std::max(min_saturation, 0.05) ||
      hi / 255.0 < min_value)
    throw InputError(source, "object_detector.colour_rgb",
                     "a colour saturated and bright enough for min_saturation and min_value",
                     fmt::format("[{}, {}, {}]", c[0], c[1], c[2]));
  if (search.conf_floor > search.conf_cap)
    throw InputError(source, "object_detector.search.conf_floor", "a value <= conf_cap",
                     fmt::format("{:g}", search.conf_floor));
}

ColourObjectDetector::ColourObjectDetector(Options options) : options_(options) {
  options_.check("ColourObjectDetector");
}

std::vector<ObjectDetection> ColourObjectDetector::detect(const RgbImage& image,
                                                          const CameraModel& camera) const {
  if (image.width_px != camera.width_px || image.height_px != camera.height_px)
    throw InputError(
        camera.source.empty() ? camera.name : camera.source, "image size",
        fmt::format("an image of the camera's {} x {} px", camera.width_px, camera.height_px),
        fmt::format("{} x {}", image.width_px, image.height_px));
  const Options& o = options_;
  std::vector<ObjectDetection> out;
  if (image.empty()) return out;
  // cv::Mat over the caller's buffer: read only.
  const cv::Mat rgb(image.height_px, image.width_px, CV_8UC3,
                    const_cast<std::uint8_t*>(image.data.data()));
  cv::Mat hsv;
  cv::cvtColor(rgb, hsv, cv::COLOR_RGB2HSV);
  const double hue_deg = hue_deg_of(o.colour_rgb);
  const cv::Mat mask = colour_mask(hsv, hue_deg, o);

  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  const int W = image.width_px, H = image.height_px;
  for (int i = 1; i < n; ++i) {
    const int area = stats.at<int>(i, cv::CC_STAT_AREA);
    if (area < o.min_area_px) continue;
    PixelBox box{stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                 stats.at<int>(i, cv::CC_STAT_WIDTH), stats.at<int>(i, cv::CC_STAT_HEIGHT)};
    const double fill =
        static_cast<double>(area) / (static_cast<double>(box.width_px) * box.height_px);
    if (fill < o.min_fill_ratio) continue;
    // Purity: how close the blob's hues sit to the object's, on average.
    double gap_sum = 0.0;
    for (int y = box.y_px; y < box.y_px + box.height_px; ++y) {
      const int* lrow = labels.ptr<int>(y);
      const cv::Vec3b* hrow = hsv.ptr<cv::Vec3b>(y);
      for (int x = box.x_px; x < box.x_px + box.width_px; ++x)
        if (lrow[x] == i) gap_sum += hue_gap_deg(hrow[x][0] * kDegPerHueStep, hue_deg);
    }
    const double purity = std::clamp(1.0 - gap_sum / area / o.hue_tolerance_deg, 0.0, 1.0);
    if (purity < o.min_purity) continue;

    ObjectDetection d;
    d.box = box;
    d.area_px = area;
    d.fill_ratio = fill;
    d.purity = purity;
    d.centroid_px = {centroids.at<double>(i, 0), centroids.at<double>(i, 1)};
    const bool cut_x = box.x_px == 0 || box.x_px + box.width_px == W;
    const bool cut_y = box.y_px == 0 || box.y_px + box.height_px == H;
    d.truncated = cut_x || cut_y;
    const double x0 = box.x_px, x1 = box.x_px + box.width_px - 1;
    const double y0 = box.y_px, y1 = box.y_px + box.height_px - 1;
    const double z_h =
        depth_from_extent(camera, true, y0, y1, d.centroid_px.x(), o.object_height_m);
    const double z_w =
        depth_from_extent(camera, false, x0, x1, d.centroid_px.y(), o.object_width_m);
    // The height first: a level camera sees the same vertical extent from every side,
    // while a box's silhouette width grows by up to sqrt(2) with its yaw. An extent cut
    // by the border is only a lower bound (its depth an upper bound): the other axis
    // then, and with both cut, the tighter of the two bounds.
    double z = 0.0;
    if (!cut_y) {
      z = z_h;
      d.size_axis = SizeAxis::kHeight;
    } else if (!cut_x) {
      z = z_w;
      d.size_axis = SizeAxis::kWidth;
    } else {
      d.size_axis = z_h <= z_w ? SizeAxis::kHeight : SizeAxis::kWidth;
      z = std::min(z_h, z_w);
    }
    d.apparent_size_px = d.size_axis == SizeAxis::kHeight ? box.height_px : box.width_px;
    // A whole blob must have the object's shape: its width over its height (in
    // normalised units) between the face-on w/h and the diagonal's sqrt(2) w/h, with a
    // factor of 2 either way for pixel quantisation at a few pixels and for views from
    // above.
    if (!d.truncated) {
      const double aspect = z_h / z_w * o.object_width_m / o.object_height_m;
      const double nominal = o.object_width_m / o.object_height_m;
      if (aspect < nominal / 2.0 || aspect > nominal * std::sqrt(2.0) * 2.0) continue;
    }
    const Eigen::Vector3d ray = camera.ray(d.centroid_px);
    // The extent is the near face's; the centre lies half the footprint's projected
    // depth further along the optical axis: (l / 2) (|cos yaw| + |sin yaw|) for a
    // square of side l, 2 l / pi on average over the yaw.
    d.distance_m = (z + 2.0 * o.object_depth_m / std::numbers::pi) * ray.norm();
    d.bearing_rad = std::atan2(-ray.x(), ray.z());
    if (o.max_distance_m > 0 && d.distance_m > o.max_distance_m) continue;

    // Visibility: a blob of a few pixels is weak evidence; a blob cut by the border
    // shows only part of the object, by the ratio of its cut extent to the extent the
    // object has at the depth the other axis gave (unknown when both are cut: half).
    double v = std::min(1.0, d.apparent_size_px / o.full_visibility_px);
    if (cut_x && !cut_y) {
      const double expected_px = camera.fx_px * o.object_width_m / z;
      v *= std::min(1.0, box.width_px / expected_px);
    } else if (cut_y && !cut_x) {
      const double expected_px = camera.fy_px * o.object_height_m / z;
      v *= std::min(1.0, box.height_px / expected_px);
    } else if (cut_x && cut_y) {
      v *= 0.5;
    }
    d.visibility = v;
    d.confidence = clip_confidence(v * distance_confidence(o.search.eta_m, d.distance_m),
                                   o.search.conf_floor, o.search.conf_cap);
    out.push_back(d);
  }
  std::sort(out.begin(), out.end(), [](const ObjectDetection& a, const ObjectDetection& b) {
    if (a.confidence != b.confidence) return a.confidence > b.confidence;
    if (a.area_px != b.area_px) return a.area_px > b.area_px;
    // A total order: the same frame gives the same list with any standard library.
    return std::pair(a.box.y_px, a.box.x_px) < std::pair(b.box.y_px, b.box.x_px);
  });
  return out;
}

}  // namespace ferret::ugv
