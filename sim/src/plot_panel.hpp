#pragma once
// The axes, legends and PNG output the sim's time-series plots share (OpenCV stays in
// the sources).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

namespace ferret::sim::internal {

struct Panel {
  cv::Rect area;
  double t0, t1, y0, y1;
  [[nodiscard]] cv::Point to_px(double t, double y) const {
    const double fx = (t - t0) / std::max(t1 - t0, 1e-9), fy = (y - y0) / std::max(y1 - y0, 1e-9);
    return {area.x + static_cast<int>(std::lround(fx * area.width)),
            area.y + area.height - static_cast<int>(std::lround(fy * area.height))};
  }
};

inline double nice_step(double range) {
  const double raw = range / 6.0, mag = std::pow(10.0, std::floor(std::log10(std::max(raw, 1e-9))));
  for (const double f : {1.0, 2.0, 5.0, 10.0})
    if (raw <= f * mag) return f * mag;
  return 10.0 * mag;
}

inline void draw_axes(cv::Mat& img, const Panel& p, const std::string& y_label, double y_step) {
  const cv::Scalar grid(225, 225, 225), text(40, 40, 40);
  const double t_step = nice_step(0.5 * (p.t1 - p.t0));  // about a dozen ticks
  for (double t = std::ceil(p.t0 / t_step) * t_step; t <= p.t1; t += t_step) {
    cv::line(img, p.to_px(t, p.y0), p.to_px(t, p.y1), grid, 1);
    cv::putText(img, fmt::format("{:.0f}", t), p.to_px(t, p.y0) + cv::Point(-8, 18),
                cv::FONT_HERSHEY_SIMPLEX, 0.4, text, 1, cv::LINE_AA);
  }
  for (double y = std::ceil(p.y0 / y_step) * y_step; y <= p.y1 + 1e-9; y += y_step) {
    cv::line(img, p.to_px(p.t0, y), p.to_px(p.t1, y), grid, 1);
    const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(y_step) + 1e-9)));
    const double shown = std::abs(y) < 1e-6 * y_step ? 0.0 : y;  // no "-0"
    cv::putText(img, fmt::format("{:.{}f}", shown, decimals), p.to_px(p.t0, y) + cv::Point(-52, 4),
                cv::FONT_HERSHEY_SIMPLEX, 0.4, text, 1, cv::LINE_AA);
  }
  cv::rectangle(img, p.area, cv::Scalar(90, 90, 90), 1);
  cv::putText(img, y_label, cv::Point(p.area.x, p.area.y - 8), cv::FONT_HERSHEY_SIMPLEX, 0.5, text,
              1, cv::LINE_AA);
}

// A row of legend entries (a line, a filled box, or a shaded box) right-aligned above a panel.
struct Key {
  std::string label;
  cv::Scalar colour;
  bool box = false;
};
inline void draw_keys(cv::Mat& img, const Panel& p, const std::vector<Key>& keys) {
  int x = p.area.x + p.area.width;
  const int y = p.area.y - 12;
  for (auto it = keys.rbegin(); it != keys.rend(); ++it) {
    int base = 0;
    const cv::Size ts = cv::getTextSize(it->label, cv::FONT_HERSHEY_SIMPLEX, 0.42, 1, &base);
    x -= ts.width;
    cv::putText(img, it->label, {x, y}, cv::FONT_HERSHEY_SIMPLEX, 0.42, cv::Scalar(40, 40, 40), 1,
                cv::LINE_AA);
    x -= 28;
    if (it->box) {
      cv::rectangle(img, cv::Rect(x, y - 10, 22, 11), it->colour, cv::FILLED);
      cv::rectangle(img, cv::Rect(x, y - 10, 22, 11), cv::Scalar(120, 120, 120), 1);
    } else {
      cv::line(img, {x, y - 4}, {x + 22, y - 4}, it->colour, 2, cv::LINE_AA);
    }
    x -= 18;
  }
}

/// Writes `img` as a PNG at `path`, all or nothing (InputError on failure).
void write_png_atomically(const cv::Mat& img, const std::filesystem::path& path);

}  // namespace ferret::sim::internal
