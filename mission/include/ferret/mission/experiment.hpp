#pragma once
// The paper's exploration experiment: for every map and zone, objects sampled
// uniformly on the zone's free cells (with clearance), one search per object and
// method with the same object and seed for every method; optional sweeps over the
// camera and IR fields of view. Config schema and outputs: docs/object_search.md.
//
// Every run's seed derives from (seed, map name, zone, object index), so runs can be
// spread over threads (--jobs) and machines (--shard I/N) and give the same numbers.
// Shards split by group (map, zone, method, field of view), so each shard's
// summary rows are complete and the CSVs of all shards merge by concatenation.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/mission/exploration_run.hpp"
#include "ferret/sim/hidden_space_generator.hpp"

namespace ferret {

struct ExperimentMap {
  std::string name;
  std::filesystem::path map_path;
  OccupancyMap2D map;
  Pose2 start;
  std::vector<ZoneSpec> zones;  ///< sorted by id, ids 1..N
};

struct ExperimentConfig {
  std::filesystem::path source;
  std::uint64_t seed = 1;
  int objects_per_zone = 20;
  std::vector<std::string> methods;
  ExplorationSettings base;          ///< robot, sensors, mission, time limit (method set per run)
  std::filesystem::path robot_urdf;  ///< robot.urdf when given: the sensors and limits came from it
  double object_clearance_m = 0.25;  ///< sampled objects keep this far from non-free cells
  std::vector<ExperimentMap> maps;
  std::vector<double> sweep_camera_fov_deg;  ///< IR fov held at the base value
  std::vector<double> sweep_ir_fov_deg;      ///< camera fov held at the base value
  std::vector<std::string> sweep_methods;    ///< default: the methods without the oracle
  int sweep_objects_per_zone = 0;            ///< default: objects_per_zone
};

/// Reads an experiment YAML (paths relative to it). Throws InputError naming the file
/// and the field: missing or unknown keys, a map that cannot be loaded, a start off
/// the free space, zones not numbered 1..N, a zone outside the map or without free cells.
[[nodiscard]] ExperimentConfig load_experiment_config(const std::filesystem::path& path);

/// `count` object positions, uniform over the zone's cells that are free with
/// `clearance_m` to every non-free cell. Deterministic in `seed`. Empty if none.
[[nodiscard]] std::vector<Eigen::Vector2d> sample_zone_objects(const OccupancyMap2D& map,
                                                               const ZoneSpec& zone, int count,
                                                               double clearance_m,
                                                               std::uint64_t seed);

/// Which part of the paper's experiment a run belongs to.
enum class ExperimentPart {
  kMain,       ///< every method at the base sensors (summary.csv)
  kCameraFov,  ///< the camera's field-of-view sweep (sweep_camera_fov.csv)
  kIrFov,      ///< the IR sensors' field-of-view sweep, bearings cleared (sweep_ir_fov.csv)
};
/// "main", "camera_fov", "ir_fov": runs.csv's words.
[[nodiscard]] std::string_view to_string(ExperimentPart part);

struct RunSpec {
  ExperimentPart experiment = ExperimentPart::kMain;
  std::size_t map_index = 0;
  int zone = 0;
  int object_index = 0;
  std::string method;
  double camera_fov_deg = 0, ir_fov_deg = 0;
  Eigen::Vector2d object_W = Eigen::Vector2d::Zero();
  std::uint64_t seed = 0;
  std::size_t group = 0;  ///< runs of one (experiment, map, zone, method, fovs) share a group
};

/// Every run of the experiment, in a fixed order.
[[nodiscard]] std::vector<RunSpec> plan_runs(const ExperimentConfig& config);

struct ExperimentOptions {
  int jobs = 1;
  int shard_index = 0;  ///< this process runs the groups g with g % shard_count == shard_index
  int shard_count = 1;
  /// Called after each run with (runs done, runs in this shard); from worker threads, serialised.
  std::function<void(std::size_t, std::size_t)> progress;
  /// Called with the staging directory once the CSVs are written there, before any of
  /// them appears in `out_dir`: what it writes there (the plots) is part of the same
  /// output set. An exception from it leaves nothing in `out_dir`.
  std::function<void(const std::filesystem::path& staging_dir)> before_commit;
};

/// The exact header of summary.csv.
inline constexpr const char* kSummaryHeader =
    "map,zone,method,runs,found,mean_time_s,ci95_lo_time_s,ci95_hi_time_s,mean_path_m";

/// Runs this shard's part of the experiment and writes runs.csv, summary.csv and (with
/// sweeps) sweep_camera_fov.csv / sweep_ir_fov.csv into `out_dir`, all of them or none
/// (one OutputSet). `out_dir` is checked before the first run (InputError).
void run_experiment(const ExperimentConfig& config, const std::filesystem::path& out_dir,
                    const ExperimentOptions& options);

/// The mean of a positive sample (times, path lengths) and its 95% bootstrap percentile
/// interval [lo, hi]: the 2.5% and 97.5% quantiles of the means of 10,000 resamples
/// drawn with a fixed seed, so the interval is a function of the sample alone. It lies
/// inside [min, max] of the sample, so it never goes below zero for non-negative data
/// (a symmetric Student t interval does for skewed times). lo = hi = NaN below 2 values;
/// everything NaN for an empty sample. docs/object_search.md says why this interval.
struct MeanCi {
  double mean = 0.0;
  double lo = 0.0;
  double hi = 0.0;
};
[[nodiscard]] MeanCi mean_ci95(const std::vector<double>& values);

}  // namespace ferret
