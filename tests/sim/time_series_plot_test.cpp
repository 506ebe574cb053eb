#include "ferret/sim/time_series_plot.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>

#include "ferret/perception/image.hpp"

namespace ferret::sim {
namespace {

namespace fs = std::filesystem;

TimeSeriesPlot ramp() {
  TimeSeriesPlot p;
  p.title = std::string("ramp");
  p.y_label = std::string("y");
  p.y_min = 0.0;
  p.y_max = 100.0;
  TimeSeries s;
  s.label = std::string("ramp");
  s.rgb = {255, 0, 0};
  for (int k = 0; k <= 100; ++k) {
    s.t_s.push_back(k);
    s.y.push_back(k == 50 ? std::numeric_limits<double>::quiet_NaN() : 100.0 - k);
  }
  p.series = {s};
  p.levels.emplace_back(10.0, std::string("reserve"));
  return p;
}

TEST(TimeSeriesPlot, DrawsTheSeriesInItsColourAndBreaksItAtNaN) {
  const fs::path path = fs::temp_directory_path() / "ferret_time_series_plot_test.png";
  write_time_series_plot(ramp(), path);
  const RgbImage img = read_rgb_image(path);
  EXPECT_EQ(img.width_px, 1100);
  EXPECT_EQ(img.height_px, 480);
  // Pure red pixels (the series) inside the panel, none in the column of the NaN.
  int red = 0, red_at_gap = 0;
  const int gap_u = 80 + static_cast<int>(std::lround(0.5 * 990));
  for (int v = 90; v < 420; ++v)
    for (int u = 80; u < 1070; ++u) {
      const bool is_red = img.at(u, v, 0) > 200 && img.at(u, v, 1) < 60 && img.at(u, v, 2) < 60;
      red += is_red;
      if (is_red && std::abs(u - gap_u) <= 2) ++red_at_gap;
    }
  EXPECT_GT(red, 900);  // a 2 px line across the panel
  EXPECT_EQ(red_at_gap, 0);
  fs::remove(path);
}

TEST(TimeSeriesPlot, BadPlotsAreRefusedAndWriteNothing) {
  const fs::path path = fs::temp_directory_path() / "ferret_time_series_plot_bad.png";
  fs::remove(path);
  TimeSeriesPlot p = ramp();
  p.series[0].y.pop_back();
  EXPECT_THROW(write_time_series_plot(p, path), std::invalid_argument);
  p = ramp();
  p.y_max = p.y_min;
  EXPECT_THROW(write_time_series_plot(p, path), std::invalid_argument);
  p = ramp();
  p.series.clear();
  EXPECT_THROW(write_time_series_plot(p, path), std::invalid_argument);
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace ferret::sim
