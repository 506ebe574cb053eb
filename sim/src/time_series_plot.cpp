#include "ferret/sim/time_series_plot.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "plot_panel.hpp"

namespace ferret::sim {

void write_time_series_plot(const TimeSeriesPlot& plot, const std::filesystem::path& path) {
  if (!(plot.y_max > plot.y_min)) throw std::invalid_argument("time series plot: y_max <= y_min");
  double t0 = std::numeric_limits<double>::infinity(), t1 = -t0;
  for (const TimeSeries& s : plot.series) {
    if (s.t_s.size() != s.y.size())
      throw std::invalid_argument("time series plot: t_s and y differ in length");
    for (const double t : s.t_s) t0 = std::min(t0, t), t1 = std::max(t1, t);
  }
  if (!(t1 >= t0)) throw std::invalid_argument("time series plot: no samples");
  if (t1 == t0) t1 = t0 + 1.0;
  cv::Mat img(480, 1100, CV_8UC3, cv::Scalar(255, 255, 255));
  const internal::Panel panel{cv::Rect(80, 90, 990, 330), t0, t1, plot.y_min, plot.y_max};
  internal::draw_axes(img, panel, plot.y_label, internal::nice_step(plot.y_max - plot.y_min));
  std::vector<internal::Key> keys;
  const cv::Scalar kLevel(150, 150, 150);
  for (const auto& [value, label] : plot.levels) {
    cv::line(img, panel.to_px(t0, value), panel.to_px(t1, value), kLevel, 1, cv::LINE_AA);
    keys.push_back({label, kLevel});
  }
  for (const TimeSeries& s : plot.series) {
    const cv::Scalar colour(s.rgb[2], s.rgb[1], s.rgb[0]);  // OpenCV is BGR
    keys.push_back({s.label, colour});
    std::vector<cv::Point> run;
    const auto flush = [&] {
      if (run.size() >= 2) cv::polylines(img, run, false, colour, 2, cv::LINE_AA);
      run.clear();
    };
    for (std::size_t i = 0; i < s.t_s.size(); ++i) {
      if (!std::isfinite(s.y[i])) {
        flush();
        continue;
      }
      run.push_back(panel.to_px(s.t_s[i], std::clamp(s.y[i], plot.y_min, plot.y_max)));
    }
    flush();
  }
  internal::draw_keys(img, panel, keys);
  cv::putText(img, plot.title, cv::Point(20, 26), cv::FONT_HERSHEY_SIMPLEX, 0.62,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  cv::putText(img, plot.subtitle, cv::Point(20, 50), cv::FONT_HERSHEY_SIMPLEX, 0.45,
              cv::Scalar(40, 40, 40), 1, cv::LINE_AA);
  cv::putText(img, "time [s]", cv::Point(540, 465), cv::FONT_HERSHEY_SIMPLEX, 0.45,
              cv::Scalar(40, 40, 40), 1, cv::LINE_AA);
  internal::write_png_atomically(img, path);
}

}  // namespace ferret::sim
