// PNG plot of a tether simulation run, drawn with OpenCV (kept out of the public header).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <system_error>

#include "ferret/core/atomic_file.hpp"
#include "ferret/core/error.hpp"
#include "ferret/sim/tether_sim.hpp"
#include "ferret/tether_model/winch_controllers.hpp"
#include "plot_panel.hpp"

namespace ferret::sim {
using internal::draw_axes;
using internal::draw_keys;
using internal::Key;
using internal::nice_step;
using internal::Panel;
namespace {

template <class Get>
void polyline(cv::Mat& img, const Panel& p, const TetherSimResult& r, Get get,
              const cv::Scalar& color) {
  std::vector<cv::Point> pts;
  pts.reserve(r.log.size());
  for (const auto& s : r.log) pts.push_back(p.to_px(s.t_s, std::clamp(get(s), p.y0, p.y1)));
  cv::polylines(img, pts, false, color, 1, cv::LINE_AA);
}

}  // namespace

void write_tether_sim_plot(const TetherSimResult& r, double max_slack_m, double total_length_m,
                           const std::filesystem::path& path) {
  if (r.log.empty()) throw std::invalid_argument("tether plot: empty log");
  cv::Mat img(750, 1100, CV_8UC3, cv::Scalar(255, 255, 255));
  const double t0 = r.log.front().t_s, t1 = r.log.back().t_s;
  double lo = total_length_m, hi = 0.0;
  for (const auto& s : r.log) {
    lo = std::min({lo, s.released_m, s.required_m});
    hi = std::max({hi, s.released_m, s.required_m});
  }
  const double pad = std::max(0.1, 0.05 * (hi - lo));
  const Panel top{cv::Rect(80, 90, 990, 330), t0, t1, std::max(0.0, lo - pad),
                  std::min(total_length_m + pad, hi + pad)};
  // Slack in millimetres, fitted to the run (a taut line's millimetres would vanish
  // on a scale that always showed the whole [0, s_max] band).
  double smin = -2.0, smax = 2.0;
  for (const auto& s : r.log) {
    smin = std::min(smin, 1e3 * s.slack_m);
    smax = std::max(smax, 1e3 * s.slack_m);
  }
  const double spad = 0.1 * (smax - smin);
  const Panel bottom{cv::Rect(80, 470, 990, 230), t0, t1, smin - spad, smax + spad};

  // Snag intervals shaded in both panels.
  for (std::size_t i = 0; i < r.log.size(); ++i) {
    if (!r.log[i].snagged) continue;
    const double ta = r.log[i].t_s, tb = i + 1 < r.log.size() ? r.log[i + 1].t_s : ta;
    for (const Panel* p : {&top, &bottom})
      cv::rectangle(img, cv::Rect(p->to_px(ta, p->y1), p->to_px(tb, p->y0)),
                    cv::Scalar(210, 230, 255), cv::FILLED);
  }
  // The allowed slack band [0, s_max], as far as it is on the panel.
  cv::rectangle(img,
                cv::Rect(bottom.to_px(t0, std::min(1e3 * max_slack_m, bottom.y1)),
                         bottom.to_px(t1, std::max(0.0, bottom.y0))),
                cv::Scalar(225, 245, 225), cv::FILLED);
  const cv::Scalar kReleased(200, 90, 20), kRequired(40, 40, 220), kLimit(150, 150, 150),
      kBand(225, 245, 225), kSnag(210, 230, 255);
  draw_axes(img, top, "tether length [m]", nice_step(top.y1 - top.y0));
  draw_axes(img, bottom, "slack = l_t - required [mm]", nice_step(bottom.y1 - bottom.y0));
  std::vector<Key> top_keys{{"released l_t", kReleased},
                            {"required (taut, ground truth)", kRequired},
                            {fmt::format("L = {:g} m{}", total_length_m,
                                         total_length_m <= top.y1 ? "" : " (above the panel)"),
                             kLimit}};
  std::vector<Key> bottom_keys{
      {"slack", kReleased},
      {r.band_label.empty() ? fmt::format("allowed [0, s_max = {:g} mm]", 1e3 * max_slack_m)
                            : r.band_label,
       kBand, true}};
  if (std::any_of(r.log.begin(), r.log.end(), [](const auto& s) { return s.snagged; })) {
    top_keys.push_back({"snagged", kSnag, true});
    bottom_keys.push_back({"snagged", kSnag, true});
  }
  draw_keys(img, top, top_keys);
  draw_keys(img, bottom, bottom_keys);
  if (total_length_m <= top.y1)
    cv::line(img, top.to_px(t0, total_length_m), top.to_px(t1, total_length_m),
             cv::Scalar(150, 150, 150), 1);
  polyline(
      img, top, r, [](const TetherSimSample& s) { return s.required_m; }, kRequired);
  polyline(
      img, top, r, [](const TetherSimSample& s) { return s.released_m; }, kReleased);
  polyline(
      img, bottom, r, [](const TetherSimSample& s) { return 1e3 * s.slack_m; }, kReleased);
  cv::line(img, bottom.to_px(t0, 0.0), bottom.to_px(t1, 0.0), cv::Scalar(0, 0, 0), 1);
  const auto& m = r.metrics;
  // Two lines: what ran, then how it went.
  cv::putText(
      img,
      fmt::format(
          "{}, {}: slack RMS {:.2f} mm, peak {:.1f} N",
          r.plot_title.empty() ? fmt::format("tether-sim {} trajectory", r.scenario) : r.plot_title,
          tether::tether_controllers().label(r.controller), 1e3 * m.slack_rms_m, m.max_tension_n),
      cv::Point(20, 26), cv::FONT_HERSHEY_SIMPLEX, 0.62, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  cv::putText(img,
              fmt::format("slack max {:.1f} mm, min {:.1f} mm; {} over-tension events; l_t at L "
                          "for {:.2f} s",
                          1e3 * m.max_slack_m, 1e3 * m.min_slack_m, m.over_tension_events,
                          m.limit_active_s),
              cv::Point(20, 50), cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(40, 40, 40), 1,
              cv::LINE_AA);
  cv::putText(img, "time [s]", cv::Point(540, 735), cv::FONT_HERSHEY_SIMPLEX, 0.45,
              cv::Scalar(40, 40, 40), 1, cv::LINE_AA);
  internal::write_png_atomically(img, path);
}

}  // namespace ferret::sim

namespace ferret::sim::internal {

void write_png_atomically(const cv::Mat& img, const std::filesystem::path& path) {
  write_file_atomically(path, [&](const std::filesystem::path& staged) {
    // imwrite picks the format from the extension: PNG whatever the target is called.
    const auto png = staged.string() + ".png";
    bool ok = false;
    try {
      ok = cv::imwrite(png, img);
    } catch (const cv::Exception& e) {  // OpenCV throws for some I/O failures
      throw InputError(path.string(), "", "a writable PNG file", e.what());
    }
    if (!ok) throw InputError(path.string(), "", "a writable PNG file");
    std::error_code ec;
    std::filesystem::rename(png, staged, ec);
    if (ec) throw InputError(path.string(), "", "a writable directory", ec.message());
  });
}

}  // namespace ferret::sim::internal
