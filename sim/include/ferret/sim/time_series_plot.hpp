#pragma once
// A PNG of quantities over time (the mission's battery.png), drawn like the tether
// figures: one panel, a legend, a dozen time ticks.

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace ferret::sim {

struct TimeSeries {
  std::string label;
  std::array<std::uint8_t, 3> rgb{40, 90, 200};
  std::vector<double> t_s, y;  ///< the same length; a NaN y breaks the line there
};

struct TimeSeriesPlot {
  std::string title, subtitle, y_label;
  double y_min = 0.0, y_max = 1.0;
  std::vector<TimeSeries> series;
  /// Horizontal reference lines (a battery reserve): value and label.
  std::vector<std::pair<double, std::string>> levels;
};

/// Writes the plot as a PNG, all or nothing. Throws std::invalid_argument for a plot
/// without a sample, a series whose t_s and y differ in length or y_max <= y_min, and
/// InputError when the file cannot be written.
void write_time_series_plot(const TimeSeriesPlot& plot, const std::filesystem::path& path);

}  // namespace ferret::sim
