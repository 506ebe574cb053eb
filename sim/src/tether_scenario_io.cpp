// Tether simulation files: a scenario read from a trajectory CSV or a scenario YAML
// (wrap points, snags, samples or a script), every bad value an InputError naming the
// file and the field; and a run's log written as CSV.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "ferret/core/atomic_file.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/sim/tether_sim.hpp"

namespace ferret::sim {

namespace {

// The limits on what a trajectory may ask the simulator to do (docs/tether.md): the
// sim steps at its physics rate over the whole time span, so the span is bounded, not
// the gaps between samples.
constexpr double kMaxDuration_s = 3600.0;
constexpr std::size_t kMaxSamples = 1'000'000;
constexpr double kMaxCoordinate_m = 1e5;

// Messages are one printable line: control and non-ASCII bytes of the file are
// escaped, a long echo cut short.
std::string printable(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (out.size() >= 80) return out + "...";
    const auto u = static_cast<unsigned char>(c);
    out += u >= 0x20 && u < 0x7f ? std::string(1, c) : fmt::format("\\x{:02x}", u);
  }
  return out;
}

// Trajectory numbers through core's one number parser (no hex, nan/inf, trailing text).
double parse_number(const std::string& text, const std::string& source, const std::string& field) {
  if (const auto v = parse_finite(text)) return *v;
  throw InputError(source, field, "a finite number", "'" + printable(text) + "'");
}

void check_duration(double duration_s, const std::string& source, const std::string& field) {
  if (!(duration_s <= kMaxDuration_s))
    throw InputError(
        source, field,
        fmt::format("a trajectory of at most {:g} s of simulated time", kMaxDuration_s),
        fmt::format("{:g} s", duration_s));
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

const std::vector<std::string> kShortHeader = {"t", "x", "y", "yaw"};
const std::vector<std::string> kLongHeader = {"t", "x", "y", "yaw", "vx", "vy", "ax", "ay"};

// Turns rows of 4 or 8 numbers into samples; `where(i)` names row i in errors.
template <class Where>
std::vector<TrajectorySample> samples_from_rows(const std::vector<std::vector<double>>& rows,
                                                bool has_derivatives, const std::string& source,
                                                Where where) {
  std::vector<TrajectorySample> out;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    TrajectorySample s;
    s.t_s = r[0];
    s.p_WG = {r[1], r[2]};
    s.yaw_rad = r[3];
    if (has_derivatives) {
      s.v_WG = {r[4], r[5]};
      s.a_WG = {r[6], r[7]};
    }
    if (!out.empty() && !(s.t_s > out.back().t_s))
      throw InputError(source, where(i) + ", field 't'",
                       "a time greater than the previous sample's", fmt::format("{}", s.t_s));
    if (!(s.p_WG.cwiseAbs().maxCoeff() <= kMaxCoordinate_m))
      throw InputError(source, where(i) + ", field 'x'/'y'", "a position within +-100000 m",
                       fmt::format("({:g}, {:g})", s.p_WG.x(), s.p_WG.y()));
    if (!out.empty()) check_duration(s.t_s - out.front().t_s, source, where(i) + ", field 't'");
    out.push_back(s);
  }
  if (out.size() < 2)
    throw InputError(source, "", "at least two trajectory samples", std::to_string(out.size()));
  if (!has_derivatives) differentiate_trajectory(out);
  return out;
}

std::vector<TrajectorySample> read_csv_samples(const std::filesystem::path& path) {
  const std::string source = path.string();
  std::ifstream in(path);
  if (!in) throw InputError(source, "", "a readable trajectory CSV file", "cannot open");
  std::string line;
  std::vector<std::string> header;
  std::vector<std::size_t> column;  // cell index -> index in kLongHeader
  std::vector<std::vector<double>> rows;
  std::vector<int> line_numbers;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    auto fields = split_csv(line);
    if (header.empty()) {
      // The header: each column named once, in any order; vx,vy,ax,ay all or none.
      const std::string expected = "a header naming t,x,y,yaw (and optionally vx,vy,ax,ay)";
      column.assign(fields.size(), 0);
      std::vector<bool> seen(kLongHeader.size(), false);
      for (std::size_t c = 0; c < fields.size(); ++c) {
        std::string f = fields[c];
        f.erase(0, f.find_first_not_of(" \t"));
        f.erase(f.find_last_not_of(" \t") + 1);
        const auto it = std::find(kLongHeader.begin(), kLongHeader.end(), f);
        const std::string at = fmt::format("line {} column {}", number, c + 1);
        if (it == kLongHeader.end())
          throw InputError(source, at, expected, "'" + printable(f) + "'");
        const auto k = static_cast<std::size_t>(it - kLongHeader.begin());
        if (seen[k]) throw InputError(source, at, expected + ", each once", "'" + f + "' again");
        seen[k] = true;
        column[c] = k;
      }
      const bool derivatives = seen[4] || seen[5] || seen[6] || seen[7];
      for (std::size_t k = 0; k < (derivatives ? kLongHeader.size() : kShortHeader.size()); ++k)
        if (!seen[k])
          throw InputError(source, fmt::format("line {}", number), expected,
                           fmt::format("no column '{}'", kLongHeader[k]));
      header = fields;
      continue;
    }
    if (fields.size() != header.size())
      throw InputError(source, fmt::format("line {}", number),
                       fmt::format("{} comma-separated numbers", header.size()),
                       fmt::format("{} fields", fields.size()));
    if (rows.size() >= kMaxSamples)
      throw InputError(source, fmt::format("line {}", number),
                       fmt::format("at most {} trajectory samples", kMaxSamples), "more samples");
    // Cells land in t,x,y,yaw[,vx,vy,ax,ay] order, whatever the header's.
    std::vector<double> row(fields.size());
    for (std::size_t i = 0; i < fields.size(); ++i)
      row[column[i]] = parse_number(
          fields[i], source, fmt::format("line {}, field '{}'", number, kLongHeader[column[i]]));
    rows.push_back(row);
    line_numbers.push_back(number);
  }
  if (header.empty())
    throw InputError(source, "", "a header line t,x,y,yaw[,vx,vy,ax,ay]", "an empty file");
  return samples_from_rows(rows, header.size() == kLongHeader.size(), source,
                           [&](std::size_t i) { return fmt::format("line {}", line_numbers[i]); });
}

Eigen::Vector2d read_xy(const yaml::MapReader& r, std::string_view key) {
  const auto v = r.get_list<double>(key, 2);
  if (!(std::abs(v[0]) <= kMaxCoordinate_m && std::abs(v[1]) <= kMaxCoordinate_m))
    r.fail(key, "a point [x, y] within +-100000 m", fmt::format("[{}, {}]", v[0], v[1]));
  return {v[0], v[1]};
}

TetherScenario read_yaml_scenario(const std::filesystem::path& path) {
  const std::string source = path.string();
  const yaml::MapReader root(yaml::load_file(path), source);
  root.allow_only(
      {"name", "entry_xy_m", "wrap_points", "snags", "samples", "samples_csv", "script"});
  TetherScenario scn;
  scn.name = root.get_or<std::string>("name", path.stem().string());
  if (root.has("entry_xy_m")) scn.p_WE = read_xy(root, "entry_xy_m");
  if (root.has("wrap_points")) {
    for (const auto& w : root.child_list("wrap_points")) {
      w.allow_only({"xy_m", "side"});
      const auto side = w.get_or<std::string>("side", "always");
      int s = 0;
      if (side == "left")
        s = +1;
      else if (side == "right")
        s = -1;
      else if (side != "always")
        w.fail("side", "left, right or always", side);
      scn.wrap_points.push_back({read_xy(w, "xy_m"), s});
    }
  }
  if (root.has("snags")) {
    for (const auto& s : root.child_list("snags")) {
      s.allow_only({"wrap_point", "start_s", "duration_s"});
      const int index = s.get<int>("wrap_point");
      if (index < 0 || static_cast<std::size_t>(index) >= scn.wrap_points.size())
        s.fail("wrap_point",
               scn.wrap_points.empty()
                   ? std::string("an index into wrap_points (the file has none)")
                   : fmt::format("an index into wrap_points (0..{})", scn.wrap_points.size() - 1),
               std::to_string(index));
      scn.snags.push_back({static_cast<std::size_t>(index), s.get_in_range("start_s", -1e9, 1e9),
                           s.get_in_range("duration_s", 1e-6, 1e9)});
    }
  }
  const int sources =
      int(root.has("samples")) + int(root.has("samples_csv")) + int(root.has("script"));
  if (sources != 1) root.fail("samples", "exactly one of samples, samples_csv or script");
  if (root.has("samples_csv")) {
    scn.samples = read_csv_samples(path.parent_path() / root.get<std::string>("samples_csv"));
  } else if (root.has("script")) {
    const auto script = root.child("script");
    script.allow_only({"waypoints_xy_m", "cruise_mps", "accel_mps2", "dwell_s"});
    std::vector<Eigen::Vector2d> waypoints;
    const YAML::Node list = script.node()["waypoints_xy_m"];
    if (!list || !list.IsSequence() || list.size() < 2)
      script.fail("waypoints_xy_m", "a list of at least two [x, y] points");
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string field = script.field_path("waypoints_xy_m") + fmt::format("[{}]", i);
      if (!list[i].IsSequence() || list[i].size() != 2) throw InputError(source, field, "[x, y]");
      waypoints.emplace_back(script.convert<double>(list[i][0], field + "[0]"),
                             script.convert<double>(list[i][1], field + "[1]"));
    }
    const double cruise = script.get_in_range("cruise_mps", 1e-3, 10.0);
    const double accel = script.get_in_range("accel_mps2", 1e-3, 100.0);
    const double dwell = script.get_in_range_or("dwell_s", 0.0, 1e4, 0.0);
    // The script's duration before its samples are made (the same profile as
    // scripted_trajectory: accelerate, cruise, brake, dwell).
    double duration_s = 0.0;
    for (std::size_t i = 0; i + 1 < waypoints.size(); ++i) {
      const double length = (waypoints[i + 1] - waypoints[i]).norm();
      if (!(length >= 1e-9)) continue;
      duration_s += (length >= cruise * cruise / accel ? length / cruise + cruise / accel
                                                       : 2.0 * std::sqrt(length / accel)) +
                    dwell;
    }
    check_duration(duration_s, source, script.field_path("waypoints_xy_m"));
    try {
      scn.samples = scripted_trajectory(waypoints, cruise, accel, dwell);
    } catch (const std::invalid_argument&) {
      script.fail("waypoints_xy_m", "waypoints that are not all the same point");
    }
  } else {
    const YAML::Node list = root.node()["samples"];
    if (!list.IsSequence())
      root.fail("samples", "a list of [t, x, y, yaw] or [t, x, y, yaw, vx, vy, ax, ay]");
    std::vector<std::vector<double>> rows;
    std::size_t width = 0;
    if (list.size() > kMaxSamples)
      root.fail("samples", fmt::format("at most {} trajectory samples", kMaxSamples),
                std::to_string(list.size()));
    for (std::size_t i = 0; i < list.size(); ++i) {
      const std::string field = fmt::format("samples[{}]", i);
      if (!list[i].IsSequence() || (list[i].size() != 4 && list[i].size() != 8) ||
          (width && list[i].size() != width))
        throw InputError(source, field,
                         width ? fmt::format("a list of {} numbers like the first sample", width)
                               : "a list of 4 or 8 numbers");
      width = list[i].size();
      std::vector<double> row;
      for (std::size_t j = 0; j < width; ++j) {
        const double v = root.convert<double>(list[i][j], fmt::format("{}[{}]", field, j));
        if (!std::isfinite(v))
          throw InputError(source, fmt::format("{}[{}]", field, j), "a finite number");
        row.push_back(v);
      }
      rows.push_back(row);
    }
    scn.samples = samples_from_rows(rows, width == 8, source,
                                    [](std::size_t i) { return fmt::format("samples[{}]", i); });
  }
  return scn;
}

}  // namespace

TetherScenario load_tether_scenario(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (!std::filesystem::is_regular_file(path))
    throw InputError(path.string(), "", "an existing trajectory file (.csv, .yaml or .yml)",
                     "not found");
  if (ext == ".csv") {
    TetherScenario scn;
    scn.name = path.stem().string();
    scn.samples = read_csv_samples(path);
    return scn;
  }
  if (ext == ".yaml" || ext == ".yml") return read_yaml_scenario(path);
  throw InputError(path.string(), "", "a .csv, .yaml or .yml trajectory file", ext);
}

void write_tether_sim_csv(const TetherSimResult& result, const std::filesystem::path& path) {
  std::string text =
      "t_s,released_m,required_m,slack_m,ugv_tension_n,winch_tension_n,command_mps,speed_mps,"
      "snagged,reachable_slack_m\n";
  for (const auto& r : result.log)
    text +=
        fmt::format("{:.3f},{:.5f},{:.5f},{:.5f},{:.4f},{:.4f},{:.5f},{:.5f},{},{:.5f}\n", r.t_s,
                    r.released_m, r.required_m, r.slack_m, r.ugv_tension_n, r.winch_tension_n,
                    r.command_mps, r.speed_mps, r.snagged ? 1 : 0, r.reachable_slack_m);
  write_text_atomically(path, text);
}

}  // namespace ferret::sim
