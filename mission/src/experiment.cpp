#include "ferret/mission/experiment.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <map>
#include <mutex>
#include <sstream>
#include <system_error>
#include <thread>
#include <tuple>

#include "ferret/core/error.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/core/random.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/mission/search_robot.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/sim/hidden_space_generator.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> read_methods(const yaml::MapReader& r, std::string_view key) {
  const auto methods = r.get_list<std::string>(key);
  if (methods.empty()) r.fail(key, "a non-empty list of methods");
  std::string names;
  for (const auto& n : exploration_policy_names()) names += (names.empty() ? "" : ", ") + n;
  for (std::size_t k = 0; k < methods.size(); ++k)
    if (!has_exploration_policy(methods[k]))
      throw InputError(r.source(), r.field_path(key) + "[" + std::to_string(k) + "]",
                       "one of " + names, methods[k]);
  return methods;
}

int read_count(const yaml::MapReader& r, std::string_view key, int fallback) {
  const int n = r.get_or<int>(key, fallback);
  if (n < 1 || n > 100000) r.fail(key, "an integer in [1, 100000]", std::to_string(n));
  return n;
}

std::vector<double> read_fovs(const yaml::MapReader& r, std::string_view key) {
  const auto values = r.get_list<double>(key);
  for (std::size_t k = 0; k < values.size(); ++k)
    if (!(values[k] > 0 && values[k] < 360))
      throw InputError(r.source(), r.field_path(key) + "[" + std::to_string(k) + "]",
                       "a field of view in (0, 360) degrees", std::to_string(values[k]));
  return values;
}

// Cells that are free with clearance_m to every non-free cell (and the map border).
bool clear_cell(const OccupancyMap2D& map, Cell c, double clearance_m) {
  const GridGeometry& g = map.geometry;
  const int r = static_cast<int>(std::ceil(clearance_m / g.resolution_m));
  for (int dj = -r; dj <= r; ++dj)
    for (int di = -r; di <= r; ++di) {
      if ((di * di + dj * dj) * g.resolution_m * g.resolution_m > clearance_m * clearance_m)
        continue;
      if (!map.is_free({c.i + di, c.j + dj})) return false;
    }
  return true;
}

std::vector<Cell> zone_cells(const OccupancyMap2D& map, const ZoneSpec& zone, double clearance_m) {
  const GridGeometry& g = map.geometry;
  std::vector<Cell> cells;
  const Cell lo = g.cell_at(zone.xmin_m, zone.ymin_m), hi = g.cell_at(zone.xmax_m, zone.ymax_m);
  for (int j = std::max(0, lo.j); j <= std::min(g.height - 1, hi.j); ++j)
    for (int i = std::max(0, lo.i); i <= std::min(g.width - 1, hi.i); ++i) {
      const Eigen::Vector2d p = g.center({i, j});
      if (p.x() < zone.xmin_m || p.x() > zone.xmax_m || p.y() < zone.ymin_m || p.y() > zone.ymax_m)
        continue;
      if (clear_cell(map, {i, j}, clearance_m)) cells.push_back({i, j});
    }
  return cells;
}

// The start and zones of a map, from `r` (the experiment's entry, or the map YAML's
// `search` section that ferret world generate-hidden writes).
void read_search(const yaml::MapReader& r, ExperimentMap& m, double clearance_m) {
  const auto start = r.get_list<double>("start", 3);
  m.start = {start[0], start[1], start[2]};
  if (!m.map.is_free(m.map.geometry.cell_at(m.start.x_m, m.start.y_m)))
    r.fail("start", "a pose on a free cell of the map");
  if (!r.has("zones"))
    r.fail("zones",
           "a mapping of zone ids 1..N to [xmin, ymin, xmax, ymax] (required field missing)");
  const YAML::Node zones = r.node()["zones"];
  if (!zones.IsMap() || zones.size() == 0)
    r.fail("zones", "a mapping of zone ids 1..N to [xmin, ymin, xmax, ymax]");
  const yaml::MapReader zr(zones, r.source(), r.field_path("zones"));
  std::map<int, ZoneSpec> by_id;
  for (const auto& entry : zones) {
    // A list or mapping as a key (`? [1]`) is not a zone id (yaml-cpp would throw its own).
    if (!entry.first.IsScalar())
      throw InputError(r.source(), r.field_path("zones"), "zone ids (integers >= 1) as keys",
                       "a key that is " + yaml::internal::describe(entry.first));
    const auto key = entry.first.as<std::string>();
    int id = 0;
    try {
      std::size_t used = 0;
      id = std::stoi(key, &used);
      if (used != key.size()) throw std::invalid_argument(key);
    } catch (const std::exception&) {
      zr.fail(key, "a zone id (an integer >= 1)", key);
    }
    const auto rect = zr.get_list<double>(key, 4);
    ZoneSpec z{id, rect[0], rect[1], rect[2], rect[3]};
    if (!(z.xmin_m < z.xmax_m && z.ymin_m < z.ymax_m))
      zr.fail(key, "[xmin, ymin, xmax, ymax] with xmin < xmax, ymin < ymax");
    const GridGeometry& g = m.map.geometry;
    if (z.xmin_m < g.origin_x_m || z.ymin_m < g.origin_y_m ||
        z.xmax_m > g.origin_x_m + g.width_m() || z.ymax_m > g.origin_y_m + g.height_m()) {
      std::ostringstream bounds;
      bounds << "a rectangle inside the map [" << g.origin_x_m << ", " << g.origin_y_m << ", "
             << g.origin_x_m + g.width_m() << ", " << g.origin_y_m + g.height_m() << "]";
      zr.fail(key, bounds.str());
    }
    if (zone_cells(m.map, z, clearance_m).empty())
      zr.fail(key, "a zone with free cells at least " + std::to_string(clearance_m) +
                       " m from obstacles");
    by_id[id] = z;
  }
  for (int id = 1; id <= static_cast<int>(by_id.size()); ++id)
    if (!by_id.count(id))
      zr.fail(std::to_string(id), "zones numbered 1.." + std::to_string(by_id.size()) +
                                      " without gaps (zone " + std::to_string(id) + " missing)");
  for (const auto& [id, z] : by_id) m.zones.push_back(z);
}

ExperimentMap read_map(const yaml::MapReader& r, const fs::path& base, double clearance_m) {
  r.allow_only({"name", "map", "start", "zones"});
  ExperimentMap m;
  m.name = r.get<std::string>("name");
  if (m.name.empty() || m.name.find_first_of(",\"\n") != std::string::npos)
    r.fail("name", "a non-empty name without commas or quotes", m.name);
  m.map_path = base / r.get<std::string>("map");
  try {
    m.map = load_map_server(m.map_path);
  } catch (const InputError& e) {
    r.fail("map", "a readable map_server YAML (" + std::string(e.what()) + ")",
           m.map_path.string());
  }
  // Without start and zones: the map's own (a generated map carries them).
  if (!r.has("start") && !r.has("zones")) {
    const YAML::Node search = YAML::LoadFile(m.map_path.string())["search"];
    if (!search || !search.IsMap())
      r.fail("start",
             "start and zones, here or in the map YAML's search section (required field missing)");
    const yaml::MapReader sr(search, m.map_path.string(), "search");
    sr.allow_only({"start", "zones", "generator"});  // generator: what made it, for people
    read_search(sr, m, clearance_m);
  } else {
    read_search(r, m, clearance_m);
  }
  return m;
}

// `generate: {count, seed, clutter, size_m}`: maps k = 0..count-1 are
// `ferret world generate-hidden --seed SEED+k`, named CLUTTER-sSEED+k.
std::vector<ExperimentMap> generate_maps(const yaml::MapReader& entry, double clearance_m) {
  entry.allow_only({"generate"});
  const yaml::MapReader g = entry.child("generate");
  g.allow_only({"count", "seed", "clutter", "size_m", "resolution_m"});
  const int count = static_cast<int>(g.get_in_range("count", 1, 10000));
  if (g.get<double>("count") != count) g.fail("count", "a whole number of maps in [1, 10000]");
  const double seed = g.get_in_range_or("seed", 0, 9.0e15, 1.0);
  if (seed != std::floor(seed)) g.fail("seed", "a whole number in [0, 9e15]");
  HiddenSpaceGeneratorOptions o;
  const auto clutter = parse_hidden_space_clutter(g.get_or<std::string>("clutter", "sparse"));
  if (!clutter) g.fail("clutter", "sparse or dense", g.get_or<std::string>("clutter", ""));
  o.clutter = *clutter;
  if (g.has("size_m")) {
    const auto size = g.get_list<double>("size_m", 2);
    o.width_m = size[0];
    o.height_m = size[1];
    if (!(o.width_m >= 8 && o.width_m <= 64 && o.height_m >= 5 && o.height_m <= 64))
      g.fail("size_m", "[width, height] in [8, 64] x [5, 64] metres");
  }
  o.resolution_m = g.get_in_range_or("resolution_m", 0.02, 0.2, o.resolution_m);
  // Every map is held for the whole experiment: 10^8 cells (100 MB) in all at most.
  const double cells =
      std::round(o.width_m / o.resolution_m) * std::round(o.height_m / o.resolution_m);
  if (count * cells > 1e8)
    g.fail("count",
           fmt::format("at most {:.0f} maps of this size and resolution (10^8 cells in all)",
                       std::floor(1e8 / cells)),
           std::to_string(count));
  std::vector<ExperimentMap> maps;
  for (int k = 0; k < count; ++k) {
    o.seed = static_cast<std::uint64_t>(seed) + static_cast<std::uint64_t>(k);
    GeneratedHiddenSpace h = generate_hidden_space(o);
    ExperimentMap m;
    m.name = fmt::format("{}-s{}", to_string(o.clutter), o.seed);
    m.map_path = fmt::format("generated: {} --seed {}", to_string(o.clutter), o.seed);
    m.map = std::move(h.map);
    m.start = h.start;
    m.zones = h.zones;
    for (const ZoneSpec& z : m.zones)
      if (zone_cells(m.map, z, clearance_m).empty())
        g.fail(
            "clutter",
            fmt::format(
                "maps whose zones have free cells {} m from obstacles (seed {} zone {} has none)",
                clearance_m, o.seed, z.id));
    maps.push_back(std::move(m));
  }
  return maps;
}

std::string format_double(double v) {
  if (!std::isfinite(v)) return "nan";
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

struct Outcome {
  bool done = false;
  EpisodeResult result;
};

}  // namespace

MeanCi mean_ci95(const std::vector<double>& values) {
  const double nan = std::nan("");
  if (values.empty()) return {nan, nan, nan};
  const std::size_t n = values.size();
  double sum = 0.0;
  for (const double v : values) sum += v;
  MeanCi out{sum / static_cast<double>(n), nan, nan};
  if (n < 2) return out;
  // Percentile bootstrap: resampled means of non-negative values are non-negative,
  // and the interval follows the sample's skew (times to find have a long right tail).
  constexpr int kResamples = 10000;
  constexpr std::uint64_t kSeed = 0x95c1;  // fixed: the same sample gives the same interval
  Rng rng(kSeed);
  std::vector<double> means(kResamples);
  for (double& m : means) {
    double s = 0.0;
    for (std::size_t k = 0; k < n; ++k)
      s += values[static_cast<std::size_t>(rng.uniform_int(0, static_cast<std::int64_t>(n) - 1))];
    m = s / static_cast<double>(n);
  }
  std::sort(means.begin(), means.end());
  // Linear interpolation between order statistics at p (B - 1).
  const auto quantile = [&](double p) {
    const double at = p * (kResamples - 1);
    const auto k = static_cast<std::size_t>(std::floor(at));
    const double f = at - static_cast<double>(k);
    return k + 1 < means.size() ? means[k] + f * (means[k + 1] - means[k]) : means[k];
  };
  // A resample of the smallest value alone sums and divides to within an ulp of it:
  // clamp to the sample's range, where the interval lies exactly.
  const auto [min_it, max_it] = std::minmax_element(values.begin(), values.end());
  out.lo = std::clamp(quantile(0.025), *min_it, *max_it);
  out.hi = std::clamp(quantile(0.975), *min_it, *max_it);
  return out;
}

ExperimentConfig load_experiment_config(const fs::path& path) {
  const yaml::MapReader r(yaml::load_file(path), path.string());
  r.allow_only({"seed", "objects_per_zone", "methods", "robot", "sensors", "maps", "sweeps",
                "mission", "time_limit_s", "object_clearance_m"});
  ExperimentConfig c;
  c.source = path;
  const fs::path base = path.parent_path();
  c.seed = r.get_or<std::uint64_t>("seed", 1);
  c.objects_per_zone = read_count(r, "objects_per_zone", 20);
  c.methods = read_methods(r, "methods");
  if (r.has("mission")) c.base.mission = load_mission_config(base / r.get<std::string>("mission"));
  c.base.time_limit_s = r.get_in_range_or("time_limit_s", 1, 1e6, 300);
  c.object_clearance_m = r.get_in_range_or("object_clearance_m", 0, 10, 0.25);
  // The mission's ugv_limits unless the robot's URDF or the robot: keys say otherwise.
  c.base.robot.set_limits(c.base.mission.ugv_limits);
  if (const auto robot = r.optional_child("robot")) {
    robot->allow_only({"urdf", "max_velocity", "max_yaw_rate", "clearance"});
    // A URDF gives the sensors and limits; the keys beside it and `sensors:` override.
    if (robot->has("urdf")) {
      const auto urdf = robot->get<std::string>("urdf");
      fs::path file = base / urdf;
      std::error_code ec;
      if (!fs::is_regular_file(file, ec)) {
        try {
          file = find_model(fs::path(urdf).has_extension() ? urdf : urdf + ".urdf");
        } catch (const InputError&) {
          robot->fail("urdf", "a URDF file (relative to this YAML) or a shipped model (miniugv)",
                      file.string());
        }
      }
      c.robot_urdf = file;
      const RobotDescription d = load_robot_description(file, c.base.mission);
      c.base.sensors = sensor_options_for(d, c.base.sensors);
      c.base.robot = robot_options_for(d, c.base.robot);
    }
    c.base.robot.max_velocity_mps =
        robot->get_in_range_or("max_velocity", 1e-3, 100, c.base.robot.max_velocity_mps);
    c.base.robot.max_yaw_rate_radps =
        robot->get_in_range_or("max_yaw_rate", 1e-3, 100, c.base.robot.max_yaw_rate_radps);
    c.base.robot.clearance_m = robot->get_in_range_or("clearance", 0, 5, c.base.robot.clearance_m);
  }
  if (const auto s = r.optional_child("sensors")) {
    // Only the keys given change a value: the defaults are the robot's (the paper's
    // miniUGV without a URDF: SensorOptions' 90 deg, 4 m, 30 deg, 4 m).
    s->allow_only({"camera_fov_deg", "camera_range", "ir_fov_deg", "ir_range"});
    if (s->has("camera_fov_deg"))
      c.base.sensors.camera_fov_rad = deg_to_rad(s->get_in_range("camera_fov_deg", 1, 359));
    if (s->has("camera_range"))
      c.base.sensors.camera_range_m = s->get_in_range("camera_range", 0.1, 100);
    if (s->has("ir_fov_deg")) {
      c.base.sensors.ir_fov_rad = deg_to_rad(s->get_in_range("ir_fov_deg", 1, 359));
      c.base.sensors.ir_bearings_rad.clear();  // the robot's beams, spread evenly over it
    }
    if (s->has("ir_range")) c.base.sensors.ir_range_m = s->get_in_range("ir_range", 0.1, 100);
  }
  const auto maps = r.child_list("maps");
  if (maps.empty()) r.fail("maps", "at least one map");
  std::vector<std::size_t> entry_of;  // the `maps` entry each map came from
  for (std::size_t e = 0; e < maps.size(); ++e) {
    if (maps[e].has("generate")) {
      for (ExperimentMap& m : generate_maps(maps[e], c.object_clearance_m)) {
        c.maps.push_back(std::move(m));
        entry_of.push_back(e);
      }
    } else {
      c.maps.push_back(read_map(maps[e], base, c.object_clearance_m));
      entry_of.push_back(e);
    }
  }
  for (std::size_t a = 0; a < c.maps.size(); ++a)
    for (std::size_t b = 0; b < a; ++b)
      if (c.maps[a].name == c.maps[b].name)
        maps[entry_of[a]].fail(maps[entry_of[a]].has("generate") ? "generate" : "name",
                               "a name no other map has", c.maps[a].name);
  // The sweeps' default: the methods without the reference that knows the object.
  for (const auto& m : c.methods)
    if (!make_exploration_policy(m, PolicyOptions{})->needs_oracle()) c.sweep_methods.push_back(m);
  c.sweep_objects_per_zone = c.objects_per_zone;
  if (const auto sw = r.optional_child("sweeps")) {
    sw->allow_only({"camera_fov_deg", "ir_fov_deg", "methods", "objects_per_zone"});
    if (sw->has("camera_fov_deg")) c.sweep_camera_fov_deg = read_fovs(*sw, "camera_fov_deg");
    if (sw->has("ir_fov_deg")) c.sweep_ir_fov_deg = read_fovs(*sw, "ir_fov_deg");
    if (sw->has("methods")) c.sweep_methods = read_methods(*sw, "methods");
    c.sweep_objects_per_zone = read_count(*sw, "objects_per_zone", c.objects_per_zone);
  }
  return c;
}

std::vector<Eigen::Vector2d> sample_zone_objects(const OccupancyMap2D& map, const ZoneSpec& zone,
                                                 int count, double clearance_m,
                                                 std::uint64_t seed) {
  const auto cells = zone_cells(map, zone, clearance_m);
  std::vector<Eigen::Vector2d> out;
  if (cells.empty()) return out;
  Rng rng(seed);
  for (int k = 0; k < count; ++k) {
    const auto idx =
        static_cast<std::size_t>(rng.uniform_int(0, static_cast<std::int64_t>(cells.size()) - 1));
    out.push_back(map.geometry.center(cells[idx]));
  }
  return out;
}

std::string_view to_string(ExperimentPart part) {
  switch (part) {
    case ExperimentPart::kMain:
      return "main";
    case ExperimentPart::kCameraFov:
      return "camera_fov";
    case ExperimentPart::kIrFov:
      return "ir_fov";
  }
  return "?";
}

std::vector<RunSpec> plan_runs(const ExperimentConfig& c) {
  std::vector<RunSpec> runs;
  std::size_t group = 0;
  const double cam_deg = rad_to_deg(c.base.sensors.camera_fov_rad),
               ir_deg = rad_to_deg(c.base.sensors.ir_fov_rad);
  const int most = std::max(c.objects_per_zone, c.sweep_objects_per_zone);
  auto add = [&](ExperimentPart experiment, const std::vector<std::string>& methods, int objects,
                 double cam, double ir) {
    for (std::size_t m = 0; m < c.maps.size(); ++m) {
      const auto& map = c.maps[m];
      const std::uint64_t map_hash = stable_hash(map.name.c_str());
      for (const auto& zone : map.zones) {
        // The same objects for every method and sweep: seeded by (seed, map, zone).
        const auto objects_W = sample_zone_objects(
            map.map, zone, most, c.object_clearance_m,
            derive_seed(c.seed, {map_hash, static_cast<std::uint64_t>(zone.id)}));
        for (const auto& method : methods) {
          for (int k = 0; k < objects; ++k) {
            RunSpec s;
            s.experiment = experiment;
            s.map_index = m;
            s.zone = zone.id;
            s.object_index = k;
            s.method = method;
            s.camera_fov_deg = cam;
            s.ir_fov_deg = ir;
            s.object_W = objects_W[static_cast<std::size_t>(k)];
            s.seed = derive_seed(c.seed, {map_hash, static_cast<std::uint64_t>(zone.id),
                                          static_cast<std::uint64_t>(k)});
            s.group = group;
            runs.push_back(s);
          }
          ++group;
        }
      }
    }
  };
  add(ExperimentPart::kMain, c.methods, c.objects_per_zone, cam_deg, ir_deg);
  for (const double a : c.sweep_camera_fov_deg)
    add(ExperimentPart::kCameraFov, c.sweep_methods, c.sweep_objects_per_zone, a, ir_deg);
  for (const double b : c.sweep_ir_fov_deg)
    add(ExperimentPart::kIrFov, c.sweep_methods, c.sweep_objects_per_zone, cam_deg, b);
  return runs;
}

void run_experiment(const ExperimentConfig& c, const fs::path& out_dir,
                    const ExperimentOptions& options) {
  if (options.shard_count < 1 || options.shard_index < 0 ||
      options.shard_index >= options.shard_count)
    throw InputError("--shard", "", "I/N with 0 <= I < N");
  check_output_target(out_dir, OutputKind::kDirectory);  // before hours of runs, not after
  std::vector<RunSpec> runs;
  for (const auto& s : plan_runs(c))
    if (static_cast<int>(s.group % static_cast<std::size_t>(options.shard_count)) ==
        options.shard_index)
      runs.push_back(s);

  std::vector<Outcome> outcomes(runs.size());
  std::atomic<std::size_t> next{0};
  std::size_t done = 0;
  std::mutex progress_mutex;
  std::exception_ptr failure;
  auto worker = [&] {
    for (std::size_t k = next++; k < runs.size(); k = next++) {
      const RunSpec& s = runs[k];
      ExplorationSettings settings = c.base;
      settings.method = s.method;
      settings.sensors.camera_fov_rad = deg_to_rad(s.camera_fov_deg);
      settings.sensors.ir_fov_rad = deg_to_rad(s.ir_fov_deg);
      // A swept IR fov spreads the robot's beams evenly over it.
      if (s.experiment == ExperimentPart::kIrFov) settings.sensors.ir_bearings_rad.clear();
      try {
        outcomes[k].result = run_exploration(c.maps[s.map_index].map, c.maps[s.map_index].start,
                                             s.object_W, settings, s.seed);
        outcomes[k].done = true;
      } catch (...) {
        std::lock_guard lock(progress_mutex);
        if (!failure) failure = std::current_exception();
        next = runs.size();
      }
      std::lock_guard lock(progress_mutex);
      ++done;
      if (options.progress) options.progress(done, runs.size());
    }
  };
  // More workers than runs would idle; a thread the system refuses is not an error:
  // the runs already started share the rest (a joinable std::thread left behind by an
  // exception would call std::terminate).
  const int jobs =
      static_cast<int>(std::clamp<std::size_t>(static_cast<std::size_t>(std::max(1, options.jobs)),
                                               1, std::max<std::size_t>(1, runs.size())));
  std::vector<std::thread> threads;
  threads.reserve(static_cast<std::size_t>(jobs));
  for (int j = 1; j < jobs; ++j) {
    try {
      threads.emplace_back(worker);
    } catch (const std::system_error& e) {
      spdlog::warn("experiment: started {} of {} worker threads ({})", j, jobs, e.what());
      break;
    }
  }
  worker();
  for (auto& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);

  std::ostringstream runs_csv;
  runs_csv << "experiment,map,zone,object,method,camera_fov_deg,ir_fov_deg,seed,object_x,object_y,"
              "found,time_s,"
              "path_m,decisions,end\n";
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const RunSpec& s = runs[k];
    const EpisodeResult& r = outcomes[k].result;
    runs_csv << to_string(s.experiment) << ',' << c.maps[s.map_index].name << ',' << s.zone << ','
             << s.object_index << ',' << s.method << ',' << format_double(s.camera_fov_deg) << ','
             << format_double(s.ir_fov_deg) << ',' << s.seed << ',' << format_double(s.object_W.x())
             << ',' << format_double(s.object_W.y()) << ',' << (r.found ? 1 : 0) << ','
             << format_double(r.time_s) << ',' << format_double(r.path_m) << ',' << r.decisions
             << ',' << r.end_reason << '\n';
  }

  // One summary row a group, in plan order.
  std::ostringstream summary, sweep_cam, sweep_ir;
  summary << kSummaryHeader << '\n';
  const char* sweep_header =
      "map,zone,method,camera_fov_deg,ir_fov_deg,runs,found,mean_time_s,ci95_lo_time_s,ci95_hi_"
      "time_s,"
      "mean_path_m\n";
  sweep_cam << sweep_header;
  sweep_ir << sweep_header;
  for (std::size_t k = 0; k < runs.size();) {
    std::size_t end = k;
    std::vector<double> times, paths;
    while (end < runs.size() && runs[end].group == runs[k].group) {
      const EpisodeResult& r = outcomes[end].result;
      if (r.found) {
        times.push_back(r.time_s);
        paths.push_back(r.path_m);
      }
      ++end;
    }
    const RunSpec& s = runs[k];
    const MeanCi t = mean_ci95(times), p = mean_ci95(paths);
    std::ostringstream stats;
    stats << (end - k) << ',' << times.size() << ',' << format_double(t.mean) << ','
          << format_double(t.lo) << ',' << format_double(t.hi) << ',' << format_double(p.mean)
          << '\n';
    const std::string key =
        c.maps[s.map_index].name + "," + std::to_string(s.zone) + "," + s.method + ",";
    const std::string fovs =
        format_double(s.camera_fov_deg) + "," + format_double(s.ir_fov_deg) + ",";
    switch (s.experiment) {
      case ExperimentPart::kMain:
        summary << key << stats.str();
        break;
      case ExperimentPart::kCameraFov:
        sweep_cam << key << fovs << stats.str();
        break;
      case ExperimentPart::kIrFov:
        sweep_ir << key << fovs << stats.str();
        break;
    }
    k = end;
  }
  OutputSet out(out_dir, OutputKind::kDirectory);
  out.write_text("runs.csv", runs_csv.str());
  out.write_text("summary.csv", summary.str());
  if (!c.sweep_camera_fov_deg.empty()) out.write_text("sweep_camera_fov.csv", sweep_cam.str());
  if (!c.sweep_ir_fov_deg.empty()) out.write_text("sweep_ir_fov.csv", sweep_ir.str());
  if (options.before_commit) options.before_commit(out.staging_dir());
  out.commit();
}

}  // namespace ferret
