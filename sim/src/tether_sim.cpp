#include "ferret/sim/tether_sim.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "ferret/core/atomic_file.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "ferret/core/random.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/tether_model/winch_controllers.hpp"

namespace ferret::sim {

TrajectorySample TetherScenario::at(double t_s) const {
  if (t_s <= samples.front().t_s) return samples.front();
  if (t_s >= samples.back().t_s) return samples.back();
  const auto it = std::upper_bound(samples.begin(), samples.end(), t_s,
                                   [](double t, const TrajectorySample& s) { return t < s.t_s; });
  const TrajectorySample& b = *it;
  const TrajectorySample& a = *(it - 1);
  const double f = (t_s - a.t_s) / (b.t_s - a.t_s);
  TrajectorySample out;
  out.t_s = t_s;
  out.p_WG = a.p_WG + f * (b.p_WG - a.p_WG);
  out.yaw_rad = a.yaw_rad + f * std::remainder(b.yaw_rad - a.yaw_rad, 2.0 * std::numbers::pi);
  out.v_WG = a.v_WG + f * (b.v_WG - a.v_WG);
  out.a_WG = a.a_WG + f * (b.a_WG - a.a_WG);
  return out;
}

void differentiate_trajectory(std::vector<TrajectorySample>& s) {
  const std::size_t n = s.size();
  if (n < 2) return;
  auto diff = [&](auto get, auto set) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t a = i == 0 ? 0 : i - 1, b = i + 1 == n ? n - 1 : i + 1;
      set(s[i], Eigen::Vector2d((get(s[b]) - get(s[a])) / (s[b].t_s - s[a].t_s)));
    }
  };
  diff([](const TrajectorySample& x) { return x.p_WG; },
       [](TrajectorySample& x, Eigen::Vector2d v) { x.v_WG = v; });
  diff([](const TrajectorySample& x) { return x.v_WG; },
       [](TrajectorySample& x, Eigen::Vector2d a) { x.a_WG = a; });
}

std::vector<TrajectorySample> scripted_trajectory(const std::vector<Eigen::Vector2d>& waypoints,
                                                  double cruise_mps, double accel_mps2,
                                                  double dwell_s, double dt_s) {
  if (waypoints.size() < 2 || !(cruise_mps > 0.0) || !(accel_mps2 > 0.0) || !(dt_s > 0.0) ||
      dwell_s < 0.0)
    throw std::invalid_argument(
        "scripted_trajectory: need >= 2 waypoints, positive speed, acceleration and dt");
  // Each segment: accelerate, cruise, decelerate (a triangle when too short), then dwell.
  struct Segment {
    Eigen::Vector2d from, dir;
    double t0, t_acc, t_cruise, v_peak, length, yaw;
  };
  std::vector<Segment> segments;
  double t = 0.0;
  double yaw = 0.0;
  for (std::size_t i = 0; i + 1 < waypoints.size(); ++i) {
    const Eigen::Vector2d d = waypoints[i + 1] - waypoints[i];
    const double length = d.norm();
    if (length < 1e-9) continue;
    yaw = std::atan2(d.y(), d.x());
    Segment s{waypoints[i], d / length, t, 0, 0, 0, length, yaw};
    if (length >= cruise_mps * cruise_mps / accel_mps2) {
      s.v_peak = cruise_mps;
      s.t_acc = cruise_mps / accel_mps2;
      s.t_cruise = (length - cruise_mps * s.t_acc) / cruise_mps;
    } else {
      s.v_peak = std::sqrt(length * accel_mps2);
      s.t_acc = s.v_peak / accel_mps2;
    }
    segments.push_back(s);
    t += 2.0 * s.t_acc + s.t_cruise + dwell_s;
  }
  if (segments.empty()) throw std::invalid_argument("scripted_trajectory: all waypoints coincide");
  const double total = t;
  std::vector<TrajectorySample> out;
  std::size_t k = 0;
  const auto count = static_cast<std::size_t>(std::floor(total / dt_s + 1e-9)) + 1;
  for (std::size_t i = 0; i < count; ++i) {
    const double ti = std::min(total, static_cast<double>(i) * dt_s);
    while (k + 1 < segments.size() && ti >= segments[k + 1].t0) ++k;
    const Segment& s = segments[k];
    const double tau = ti - s.t0, move = 2.0 * s.t_acc + s.t_cruise;
    double dist, speed, acc;
    if (tau < s.t_acc) {
      dist = 0.5 * accel_mps2 * tau * tau, speed = accel_mps2 * tau, acc = accel_mps2;
    } else if (tau < s.t_acc + s.t_cruise) {
      dist = 0.5 * s.v_peak * s.t_acc + s.v_peak * (tau - s.t_acc), speed = s.v_peak, acc = 0.0;
    } else if (tau < move) {
      const double rem = move - tau;
      dist = s.length - 0.5 * accel_mps2 * rem * rem, speed = accel_mps2 * rem, acc = -accel_mps2;
    } else {
      dist = s.length, speed = 0.0, acc = 0.0;
    }
    TrajectorySample smp;
    smp.t_s = ti;
    smp.p_WG = s.from + s.dir * dist;
    smp.yaw_rad = s.yaw;
    smp.v_WG = s.dir * speed;
    smp.a_WG = s.dir * acc;
    if (!out.empty() && ti <= out.back().t_s) break;
    out.push_back(smp);
  }
  return out;
}

namespace {

// The default scenario: a block x in [1, 3.5], y in [0.5, 2] beside the entry; the
// tether wraps its two right-hand corners when the miniUGV drives up and behind it.
std::vector<tether::WrapPoint> default_wraps() { return {{{3.5, 0.5}, +1}, {{3.5, 2.0}, +1}}; }
std::vector<Eigen::Vector2d> default_waypoints() {
  return {{0.3, 0.0}, {4.2, 0.0}, {4.2, 3.0}, {1.5, 3.0}, {4.2, 3.0}, {4.2, 0.0}, {0.3, 0.0}};
}

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

std::vector<TrajectorySample> actual_ugv_motion(const TetherScenario& scn, const UgvObedience& ugv,
                                                double dt_s, std::uint64_t seed) {
  if (!(dt_s > 0.0) || ugv.velocity_lag_s < 0.0 || ugv.slip_mps < 0.0 || !(ugv.slip_time_s > 0.0) ||
      ugv.tracking_time_s < 0.0)
    throw std::invalid_argument("actual_ugv_motion: need dt > 0, times and slip >= 0");
  Rng rng(seed);
  const auto count =
      static_cast<std::size_t>(std::floor((scn.end_s() - scn.start_s()) / dt_s + 1e-9)) + 1;
  // Exact discretisation of the lag v' = (v_cmd - v) / lag and of the slip process.
  const double follow = ugv.velocity_lag_s > 0.0 ? 1.0 - std::exp(-dt_s / ugv.velocity_lag_s) : 1.0;
  const double keep = std::exp(-dt_s / ugv.slip_time_s);
  const double kick = ugv.slip_mps * std::sqrt(1.0 - keep * keep);
  const double steer = ugv.tracking_time_s > 0.0 ? 1.0 / ugv.tracking_time_s : 0.0;
  std::vector<TrajectorySample> out;
  out.reserve(count);
  // The position is the desired one plus the integrated velocity error, so an
  // obedient robot reproduces its trajectory exactly.
  TrajectorySample desired = scn.at(scn.start_s());
  Eigen::Vector2d v = desired.v_WG, slip = Eigen::Vector2d::Zero(), offset = slip;
  out.push_back(desired);
  for (std::size_t i = 1; i < count; ++i) {
    const Eigen::Vector2d error_before = v + slip - desired.v_WG;
    desired = scn.at(scn.start_s() + static_cast<double>(i) * dt_s);
    v += follow * (desired.v_WG - steer * offset - v);
    if (ugv.slip_mps > 0.0)
      slip = keep * slip + kick * Eigen::Vector2d(rng.normal(0.0, 1.0), rng.normal(0.0, 1.0));
    offset += 0.5 * (error_before + v + slip - desired.v_WG) * dt_s;
    TrajectorySample row = desired;
    row.p_WG += offset;
    row.v_WG = v + slip;
    out.push_back(row);
  }
  return out;
}

TetherScenario default_tether_scenario() {
  TetherScenario scn;
  scn.name = "default";
  scn.wrap_points = default_wraps();
  scn.samples = scripted_trajectory(default_waypoints(), 0.4, 1.0, 1.0);
  return scn;
}

TetherSimOptions TetherSimOptions::for_tether(double total_length_m, double entry_offset_m) {
  TetherSimOptions o;
  o.entry_offset_m = entry_offset_m;
  o.control.limits.total_length_m = total_length_m;
  o.winch.total_length_m = total_length_m;
  o.winch.max_speed_mps = o.control.limits.max_speed_mps;
  o.winch.max_acceleration_mps2 = o.control.limits.max_acceleration_mps2;
  return o;
}

TetherRunConfig TetherRunConfig::for_tether(double total_length_m, double entry_offset_m) {
  TetherRunConfig c;
  c.sim = TetherSimOptions::for_tether(total_length_m, entry_offset_m);
  c.mpc.control = c.sim.control;
  c.baseline.control = c.sim.control;
  return c;
}

void apply_tether_run_config(const std::filesystem::path& path, TetherRunConfig& c) {
  const yaml::MapReader root(yaml::load_file(path), path.string());
  root.allow_only({"control", "mpc", "baseline", "sim"});
  auto& ctl = c.sim.control;
  if (const auto r = root.optional_child("control")) {
    r->allow_only({"slack_reference_m", "max_slack_m", "pose_filter_gain", "guard_n",
                   "max_tension_n", "max_speed_mps", "max_acceleration_mps2", "ugv_velocity_lag_s",
                   "ugv_tracking_time_s", "identify_ugv_response",
                   "tension_fusion", "observer_pose_noise_m", "observer_tension_noise_n",
                   "observer_speed_noise_mps", "observer_model_offset_decay_mps",
                   "servo_time_constant_s"});
    ctl.slack_reference_m =
        r->get_in_range_or("slack_reference_m", -0.1, 1.0, ctl.slack_reference_m);
    ctl.max_slack_m = r->get_in_range_or("max_slack_m", 0.0, 10.0, ctl.max_slack_m);
    ctl.pose_filter_gain = r->get_in_range_or("pose_filter_gain", 1e-3, 1.0, ctl.pose_filter_gain);
    ctl.ugv_velocity_lag_s =
        r->get_in_range_or("ugv_velocity_lag_s", 0.0, 5.0, ctl.ugv_velocity_lag_s);
    ctl.ugv_tracking_time_s =
        r->get_in_range_or("ugv_tracking_time_s", 0.0, 100.0, ctl.ugv_tracking_time_s);
    ctl.ugv_response_identification.enabled =
        r->get_or<bool>("identify_ugv_response", ctl.ugv_response_identification.enabled);
    ctl.limits.velocity_time_constant_s =
        r->get_in_range_or("servo_time_constant_s", 1e-4, 1.0, ctl.limits.velocity_time_constant_s);
    auto& obs = ctl.slack_observer;
    obs.tension_fusion = r->get_or<bool>("tension_fusion", obs.tension_fusion);
    obs.pose_noise_m = r->get_in_range_or("observer_pose_noise_m", 0.0, 1.0, obs.pose_noise_m);
    obs.tension_noise_n =
        r->get_in_range_or("observer_tension_noise_n", 1e-3, 100.0, obs.tension_noise_n);
    obs.ugv_speed_noise_mps =
        r->get_in_range_or("observer_speed_noise_mps", 0.0, 10.0, obs.ugv_speed_noise_mps);
    obs.model_offset_decay_mps =
        r->get_in_range_or("observer_model_offset_decay_mps", 0.0, 10.0, obs.model_offset_decay_mps);
    ctl.slack_estimator.guard_n =
        r->get_in_range_or("guard_n", 0.0, 1e3, ctl.slack_estimator.guard_n);
    ctl.slack_estimator.tension.max_tension_n =
        r->get_in_range_or("max_tension_n", 0.1, 1e4, ctl.slack_estimator.tension.max_tension_n);
    ctl.limits.max_speed_mps =
        r->get_in_range_or("max_speed_mps", 1e-3, 10.0, ctl.limits.max_speed_mps);
    ctl.limits.max_acceleration_mps2 =
        r->get_in_range_or("max_acceleration_mps2", 1e-3, 100.0, ctl.limits.max_acceleration_mps2);
    c.sim.winch.max_speed_mps = ctl.limits.max_speed_mps;
    c.sim.winch.max_acceleration_mps2 = ctl.limits.max_acceleration_mps2;
  }
  // Each controller's own section, read beside its options (winch_controllers.hpp).
  if (const auto r = root.optional_child("mpc")) tether::read_mpc_options(*r, c.mpc);
  if (const auto r = root.optional_child("baseline")) tether::read_baseline_options(*r, c.baseline);
  if (const auto r = root.optional_child("sim")) {
    r->allow_only({"link_latency_s", "pose_noise_m", "tension_noise_n", "ugv_preview_s",
                   "ugv_preview_step_s", "ugv_velocity_lag_s", "ugv_slip_noise_mps",
                   "ugv_slip_time_s", "ugv_tracking_time_s"});
    c.sim.link_latency_s = r->get_in_range_or("link_latency_s", 0.0, 1.0, c.sim.link_latency_s);
    c.sim.pose_noise_m = r->get_in_range_or("pose_noise_m", 0.0, 1.0, c.sim.pose_noise_m);
    c.sim.tension_noise_n =
        r->get_in_range_or("tension_noise_n", 0.0, 100.0, c.sim.tension_noise_n);
    c.sim.ugv_preview_s = r->get_in_range_or("ugv_preview_s", 0.0, 10.0, c.sim.ugv_preview_s);
    c.sim.ugv_preview_step_s =
        r->get_in_range_or("ugv_preview_step_s", 1e-3, 1.0, c.sim.ugv_preview_step_s);
    c.sim.ugv_velocity_lag_s =
        r->get_in_range_or("ugv_velocity_lag_s", 0.0, 5.0, c.sim.ugv_velocity_lag_s);
    c.sim.ugv_slip_noise_mps =
        r->get_in_range_or("ugv_slip_noise_mps", 0.0, 1.0, c.sim.ugv_slip_noise_mps);
    c.sim.ugv_slip_time_s =
        r->get_in_range_or("ugv_slip_time_s", 1e-3, 100.0, c.sim.ugv_slip_time_s);
    c.sim.ugv_tracking_time_s =
        r->get_in_range_or("ugv_tracking_time_s", 0.0, 100.0, c.sim.ugv_tracking_time_s);
  }
  c.mpc.control = ctl;
  c.baseline.control = ctl;
}

namespace {

// The tether between the winch and the miniUGV, sliding freely over its wrap points
// except while a snag pins it at one.
class TetherState {
 public:
  TetherState(const TetherScenario& scn, const TetherSimOptions& opt)
      : scn_(scn), opt_(opt), geometry_(opt.entry_offset_m, scn.p_WE, scn.wrap_points) {}

  struct Forces {
    double required_m = 0.0, ugv_n = 0.0, winch_n = 0.0;
    /// Slack on the winch's side of a pinned corner (the whole slack when nothing pins).
    double reachable_slack_m = 0.0;
    bool snagged = false;
  };

  Forces update(double t_s, double released_m, const Eigen::Vector2d& p_WG) {
    Forces f;
    f.required_m = geometry_.required_length_m(p_WG);
    const auto& tension = opt_.control.slack_estimator.tension;
    const TetherSnag* snag = nullptr;
    for (const auto& s : scn_.snags)
      if (t_s >= s.start_s && t_s < s.start_s + s.duration_s) snag = &s;
    if (snag != current_snag_) {
      current_snag_ = snag;
      pinned_ = false;
      // A snag only holds a corner the tether is actually bent round.
      if (snag && geometry_.engaged_count(p_WG) > snag->wrap_point) {
        pinned_ = true;
        const double to_pin = geometry_.length_to_wrap_point_m(snag->wrap_point);
        const double beyond = f.required_m - to_pin;
        // The slack at the moment of the snag is shared in proportion to length.
        beyond_material_m_ = beyond + (released_m - f.required_m) * beyond / f.required_m;
        beyond_geometry_ = std::make_unique<tether::FixedWrapTether>(
            0.0, scn_.wrap_points[snag->wrap_point].p_W,
            std::vector<tether::WrapPoint>(
                scn_.wrap_points.begin() + static_cast<long>(snag->wrap_point) + 1,
                scn_.wrap_points.end()));
        winch_side_m_ = to_pin;
      }
    }
    if (pinned_) {
      f.snagged = true;
      const double beyond_geom = beyond_geometry_->required_length_m(p_WG);
      f.ugv_n = tension.tension_n(beyond_material_m_, beyond_material_m_ - beyond_geom);
      f.reachable_slack_m = (released_m - beyond_material_m_) - winch_side_m_;
      f.winch_n = tension.tension_n(released_m - beyond_material_m_, f.reachable_slack_m);
    } else {
      f.reachable_slack_m = released_m - f.required_m;
      f.ugv_n = f.winch_n = tension.tension_n(released_m, f.reachable_slack_m);
    }
    return f;
  }

 private:
  const TetherScenario& scn_;
  const TetherSimOptions& opt_;
  tether::FixedWrapTether geometry_;
  const TetherSnag* current_snag_ = nullptr;
  bool pinned_ = false;
  double beyond_material_m_ = 0.0, winch_side_m_ = 0.0;
  std::unique_ptr<tether::FixedWrapTether> beyond_geometry_;
};

}  // namespace

TetherSimResult run_tether_sim(const TetherScenario& scn, const TetherSimOptions& opt,
                               tether::TetherController& controller) {
  if (scn.samples.size() < 2)
    throw std::invalid_argument("tether sim: the trajectory needs two samples or more");
  for (const auto& s : scn.snags)
    if (s.wrap_point >= scn.wrap_points.size())
      throw std::invalid_argument("tether sim: snag on a missing wrap point");
  if (!(opt.physics_dt_s > 0.0) || !(opt.control.control_period_s >= opt.physics_dt_s))
    throw std::invalid_argument("tether sim: need 0 < physics dt <= control period");
  if (opt.ugv_preview_s > 0.0 && !(opt.ugv_preview_step_s > 0.0))
    throw std::invalid_argument("tether sim: a preview needs a step > 0");

  const tether::FixedWrapTether geometry(opt.entry_offset_m, scn.p_WE, scn.wrap_points);
  const auto& tension_model = opt.control.slack_estimator.tension;
  const double L = opt.control.limits.total_length_m;
  Rng rng(opt.seed);
  controller.reset();
  tether::SimulatedWinch::Options winch_options = opt.winch;
  winch_options.total_length_m = L;
  winch_options.initial_released_m = std::clamp(
      geometry.required_length_m(scn.samples.front().p_WG) + opt.control.slack_reference_m, 0.0, L);
  tether::SimulatedWinch winch(winch_options);
  TetherState tether_state(scn, opt);
  // Where the miniUGV really is: its desired motion, unless it lags or slips.
  TetherScenario actual_storage;
  const bool obedient = opt.ugv_velocity_lag_s == 0.0 && opt.ugv_slip_noise_mps == 0.0;
  if (!obedient) {
    actual_storage.samples = actual_ugv_motion(scn,
                                               {opt.ugv_velocity_lag_s, opt.ugv_slip_noise_mps,
                                                opt.ugv_slip_time_s, opt.ugv_tracking_time_s},
                                               opt.physics_dt_s, derive_seed(opt.seed, {1}));
  }
  const TetherScenario& actual = obedient ? scn : actual_storage;

  TetherSimResult result;
  result.scenario = scn.name;
  result.controller = std::string(controller.name());
  auto& m = result.metrics;
  const int substeps =
      std::max(1, static_cast<int>(std::lround(opt.control.control_period_s / opt.physics_dt_s)));
  const double dt = opt.control.control_period_s / substeps;
  double t = scn.start_s();
  bool over = false;
  double sum_sq = 0.0, reachable_sum_sq = 0.0;
  std::vector<double> step_times_us;
  m.min_slack_m = std::numeric_limits<double>::infinity();
  m.max_slack_m = -std::numeric_limits<double>::infinity();
  auto forces = tether_state.update(t, winch.released_m(), actual.at(t).p_WG);
  while (t <= scn.end_s() + 1e-9) {
    // The miniUGV's message left latency seconds ago, with its localisation error.
    const double t_msg = std::max(scn.start_s(), t - opt.link_latency_s);
    const TrajectorySample msg = scn.at(t_msg);  // the desired motion it reports
    tether::TetherObservation obs;
    obs.t_s = t;
    obs.released_m = winch.released_m();
    obs.spool_speed_mps = winch.speed_mps();
    obs.winch_tension_n =
        tension_model.hanging_weight_n + forces.winch_n + rng.normal(0.0, opt.tension_noise_n);
    obs.ugv.p_WG = actual.at(t_msg).p_WG + Eigen::Vector2d(rng.normal(0.0, opt.pose_noise_m),
                                                           rng.normal(0.0, opt.pose_noise_m));
    obs.ugv.v_WG = msg.v_WG;
    obs.ugv.a_WG = msg.a_WG;
    obs.ugv_age_s = t - t_msg;
    // Its plan ahead, relative to where the plan has it at the message.
    const int preview_knots =
        static_cast<int>(std::ceil(opt.ugv_preview_s / opt.ugv_preview_step_s - 1e-9));
    if (preview_knots > 0) {
      auto& preview = obs.ugv_preview;
      preview.step_s = opt.ugv_preview_step_s;
      for (int i = 0; i <= preview_knots; ++i) {
        const TrajectorySample planned = scn.at(t_msg + i * opt.ugv_preview_step_s);
        preview.displacement_m.push_back(planned.p_WG - msg.p_WG);
        // The plan stands still once it has ended.
        preview.velocity_mps.push_back(t_msg + i * opt.ugv_preview_step_s >= scn.end_s()
                                           ? Eigen::Vector2d::Zero()
                                           : planned.v_WG);
      }
    }
    const auto tick = std::chrono::steady_clock::now();
    const double command = controller.step(obs);
    step_times_us.push_back(
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - tick).count());
    winch.command_velocity_mps(command);

    TetherSimSample row;
    row.t_s = t;
    row.released_m = winch.released_m();
    row.required_m = forces.required_m;
    row.slack_m = row.released_m - row.required_m;
    row.reachable_slack_m = forces.reachable_slack_m;  // = slack_m unless a corner pins the line
    row.ugv_tension_n = forces.ugv_n;
    row.winch_tension_n = forces.winch_n;
    row.command_mps = command;
    row.speed_mps = winch.speed_mps();
    row.snagged = forces.snagged;
    result.log.push_back(row);
    sum_sq += row.slack_m * row.slack_m;
    reachable_sum_sq += row.reachable_slack_m * row.reachable_slack_m;
    m.min_slack_m = std::min(m.min_slack_m, row.slack_m);
    m.max_slack_m = std::max(m.max_slack_m, row.slack_m);
    if (row.released_m > L + 1e-3) ++m.released_over_limit;

    for (int i = 0; i < substeps; ++i) {
      winch.advance(dt, tension_model.hanging_weight_n + forces.winch_n);
      t += dt;
      forces = tether_state.update(t, winch.released_m(), actual.at(t).p_WG);
      const double peak = std::max(forces.ugv_n, forces.winch_n);
      m.max_tension_n = std::max(m.max_tension_n, peak);
      const bool now_over = peak > tension_model.max_tension_n;
      if (now_over && !over) ++m.over_tension_events;
      if (now_over) m.over_tension_time_s += dt;
      over = now_over;
      if (winch.released_m() >= L - 1e-3) m.limit_active_s += dt;
      m.max_released_m = std::max(m.max_released_m, winch.released_m());
    }
  }
  m.slack_rms_m = std::sqrt(sum_sq / static_cast<double>(result.log.size()));
  m.reachable_slack_rms_m = std::sqrt(reachable_sum_sq / static_cast<double>(result.log.size()));
  m.duration_s = scn.end_s() - scn.start_s();
  m.control_cycles = static_cast<int>(result.log.size());
  std::sort(step_times_us.begin(), step_times_us.end());
  m.step_time_median_us = step_times_us[step_times_us.size() / 2];
  m.step_time_max_us = step_times_us.back();
  return result;
}

void write_tether_sim_csv(const TetherSimResult& result, const std::filesystem::path& path) {
  std::string text =
      "t_s,released_m,required_m,slack_m,ugv_tension_n,winch_tension_n,command_mps,speed_mps,"
      "snagged,reachable_slack_m\n";
  for (const auto& r : result.log)
    text += fmt::format("{:.3f},{:.5f},{:.5f},{:.5f},{:.4f},{:.4f},{:.5f},{:.5f},{},{:.5f}\n",
                        r.t_s, r.released_m, r.required_m, r.slack_m, r.ugv_tension_n,
                        r.winch_tension_n, r.command_mps, r.speed_mps, r.snagged ? 1 : 0,
                        r.reachable_slack_m);
  write_text_atomically(path, text);
}

}  // namespace ferret::sim
