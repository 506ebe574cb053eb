#include "ferret/mission/experiment.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"
#include "ferret/sim/hidden_space_generator.hpp"
#include "support/cli_runner.hpp"
#include "support/test_maps.hpp"

namespace ferret {
namespace {

using ::testing::HasSubstr;

// An experiment on the small test space, in a temporary directory.
struct ExperimentDir {
  test::TempDir dir;
  ExperimentDir() { save_map_server(test::small_hidden_space(), dir.path() / "room.yaml"); }
  std::filesystem::path config(const std::string& zones, const std::string& extra = "") const {
    std::ofstream out(dir.path() / "exp.yaml");
    out << "seed: 3\nobjects_per_zone: 2\nmethods: [cdos, rapid]\n"
        << extra
        << "maps:\n  - name: room\n    map: room.yaml\n    start: [0.5, 1.0, 0.0]\n    zones:\n"
        << zones;
    return dir.path() / "exp.yaml";
  }
};

const char* kZones = "      1: [1.0, 0.5, 1.8, 1.5]\n      2: [2.8, 0.4, 4.6, 1.4]\n";

void expect_input_error(const std::filesystem::path& config, const std::string& field) {
  try {
    (void)load_experiment_config(config);
    FAIL() << "no error for " << field;
  } catch (const InputError& e) {
    EXPECT_THAT(e.field(), HasSubstr(field)) << e.what();
  }
}

TEST(Experiment, LoadsZonesInOrderWithDefaults) {
  ExperimentDir s;
  const auto c = load_experiment_config(s.config(kZones));
  EXPECT_EQ(c.seed, 3u);
  ASSERT_EQ(c.maps.size(), 1u);
  ASSERT_EQ(c.maps[0].zones.size(), 2u);
  EXPECT_EQ(c.maps[0].zones[1].id, 2);
  EXPECT_DOUBLE_EQ(c.maps[0].zones[1].xmax_m, 4.6);
  EXPECT_EQ(c.sweep_methods, (std::vector<std::string>{"cdos", "rapid"}));
  EXPECT_DOUBLE_EQ(rad_to_deg(c.base.sensors.camera_fov_rad), 90.0);
}

TEST(Experiment, BadConfigsNameTheField) {
  ExperimentDir s;
  expect_input_error(s.config("      1: [1.0, 0.5, 1.8, 1.5]\n      3: [2.8, 0.4, 4.6, 1.4]\n"),
                     "maps[0].zones.2");
  expect_input_error(s.config("      1: [1.0, 0.5, 1.8, 1.5]\n      2: [2.8, 0.4, 6.0, 1.4]\n"),
                     "maps[0].zones.2");
  expect_input_error(s.config("      1: [2.0, 0.2, 2.4, 1.5]\n"),
                     "maps[0].zones.1");  // inside the wall: no free cell
  expect_input_error(s.config(kZones, "sensors: {camera_fov_deg: -5}\n"), "sensors.camera_fov_deg");
  expect_input_error(s.config(kZones, "colour: red\n"), "colour");
  expect_input_error(s.config(kZones, "sweeps: {objects_per_zone: 2.5}\n"),
                     "sweeps.objects_per_zone");
  expect_input_error(s.config(kZones, "sweeps: {objects_per_zone: 0}\n"),
                     "sweeps.objects_per_zone");
  {
    std::ofstream out(s.dir.path() / "exp.yaml");
    out << "methods: [cdos, random]\nmaps:\n  - {name: a, map: nowhere.yaml, start: [0.5, 1, 0], "
           "zones: {1: [1, 1, 2, 2]}}\n";
  }
  expect_input_error(s.dir.path() / "exp.yaml", "methods[1]");
  {
    std::ofstream out(s.dir.path() / "exp.yaml");
    out << "methods: [cdos]\nmaps:\n  - {name: a, map: nowhere.yaml, start: [0.5, 1, 0], zones: "
           "{1: [1, 1, 2, 2]}}\n";
  }
  expect_input_error(s.dir.path() / "exp.yaml", "maps[0].map");
  {
    std::ofstream out(s.dir.path() / "exp.yaml");
    out << "methods: [cdos]\nmaps:\n  - {name: a, map: room.yaml, start: [0.5, 1, 0]}\n";
  }
  expect_input_error(s.dir.path() / "exp.yaml", "maps[0].zones");
}

TEST(Experiment, AGeneratedMapBringsItsOwnStartAndZones) {
  ExperimentDir s;
  HiddenSpaceGeneratorOptions o;
  o.seed = 5;
  const GeneratedHiddenSpace h = generate_hidden_space(o);
  save_map_server(h.map, s.dir.path() / "gen.yaml", h.search_yaml());
  {
    std::ofstream out(s.dir.path() / "exp.yaml");
    out << "methods: [cdos]\nmaps:\n  - {name: g, map: gen.yaml}\n"
           "  - {name: h, map: gen.yaml, start: [1.0, 4.0, 0.0], zones: {1: [2, 3.7, 4, 4.3]}}\n";
  }
  const auto c = load_experiment_config(s.dir.path() / "exp.yaml");
  ASSERT_EQ(c.maps.size(), 2u);
  EXPECT_EQ(c.maps[0].map, h.map);
  EXPECT_DOUBLE_EQ(c.maps[0].start.y_m, h.start.y_m);
  ASSERT_EQ(c.maps[0].zones.size(), 5u);
  for (std::size_t z = 0; z < 5; ++z) {
    EXPECT_EQ(c.maps[0].zones[z].id, h.zones[z].id);
    EXPECT_DOUBLE_EQ(c.maps[0].zones[z].xmin_m, h.zones[z].xmin_m);
    EXPECT_DOUBLE_EQ(c.maps[0].zones[z].ymax_m, h.zones[z].ymax_m);
  }
  // The entry's own start and zones win over the map's.
  EXPECT_EQ(c.maps[1].zones.size(), 1u);
  // A map with neither: the start is what is missing.
  {
    std::ofstream out(s.dir.path() / "exp.yaml");
    out << "methods: [cdos]\nmaps:\n  - {name: a, map: room.yaml}\n";
  }
  expect_input_error(s.dir.path() / "exp.yaml", "maps[0].start");
  // A broken search section is named in the map's file.
  {
    std::ofstream out(s.dir.path() / "bad.yaml");
    out << "image: gen.pgm\nresolution: 0.05\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
           "free_thresh: 0.196\nsearch: {start: [1, 4], zones: {1: [2, 3.7, 4, 4.3]}}\n";
    std::ofstream exp(s.dir.path() / "exp.yaml");
    exp << "methods: [cdos]\nmaps:\n  - {name: a, map: bad.yaml}\n";
  }
  try {
    (void)load_experiment_config(s.dir.path() / "exp.yaml");
    FAIL() << "a two-number start";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "search.start") << e.what();
    EXPECT_THAT(e.source(), HasSubstr("bad.yaml"));
  }
  // A key the section does not know is a typo, not ignored.
  {
    std::ofstream out(s.dir.path() / "bad.yaml");
    out << "image: gen.pgm\nresolution: 0.05\norigin: [0, 0, 0]\n"
           "search: {start: [1, 4, 0], zones: {1: [2, 3.7, 4, 4.3]}, zone: {2: [3, 5, 4, 6]}}\n";
  }
  try {
    (void)load_experiment_config(s.dir.path() / "exp.yaml");
    FAIL() << "an unknown key in search";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "search.zone") << e.what();
  }
}

TEST(Experiment, AGenerateEntryIsThatManyGeneratedMaps) {
  ExperimentDir s;
  {
    std::ofstream out(s.dir.path() / "exp.yaml");
    out << "methods: [cdos, rapid]\nobjects_per_zone: 1\nmaps:\n  - generate: {count: 3, seed: 10, "
           "clutter: dense}\n"
           "  - {name: room, map: room.yaml, start: [0.5, 1.0, 0.0], zones: {1: [1.0, 0.5, 1.8, "
           "1.5]}}\n";
  }
  const auto c = load_experiment_config(s.dir.path() / "exp.yaml");
  ASSERT_EQ(c.maps.size(), 4u);
  for (std::uint64_t k = 0; k < 3; ++k) {
    HiddenSpaceGeneratorOptions o;
    o.seed = 10 + k;
    o.clutter = HiddenSpaceClutter::kDense;
    EXPECT_EQ(c.maps[k].name, "dense-s" + std::to_string(10 + k));
    EXPECT_EQ(c.maps[k].map, generate_hidden_space(o).map) << k;
    EXPECT_EQ(c.maps[k].zones.size(), 5u);
  }
  EXPECT_EQ(c.maps[3].name, "room");
  // 4 maps: 3 x 5 zones + 1 zone, one object each, two methods.
  EXPECT_EQ(plan_runs(c).size(), 2u * (3 * 5 + 1));
  const auto entry = [&](const std::string& generate) {
    std::ofstream out(s.dir.path() / "exp.yaml");
    out << "methods: [cdos]\nmaps:\n  - generate: " << generate << "\n";
    return s.dir.path() / "exp.yaml";
  };
  expect_input_error(entry("{count: 0}"), "maps[0].generate.count");
  expect_input_error(entry("{count: 2.5}"), "maps[0].generate.count");
  expect_input_error(entry("{count: 1, clutter: medium}"), "maps[0].generate.clutter");
  expect_input_error(entry("{count: 1, size_m: [4, 4]}"), "maps[0].generate.size_m");
  expect_input_error(entry("{count: 1, seed: -1}"), "maps[0].generate.seed");
  expect_input_error(entry("{count: 1, colour: red}"), "maps[0].generate.colour");
  expect_input_error(entry("{count: 200, size_m: [64, 64]}"),
                     "maps[0].generate.count");  // 3.3e8 cells
  // Two entries that generate the same map names are one map twice.
  {
    std::ofstream out(s.dir.path() / "exp.yaml");
    out << "methods: [cdos]\nmaps:\n  - generate: {count: 2, seed: 1}\n  - generate: {count: 1, "
           "seed: 2}\n";
  }
  expect_input_error(s.dir.path() / "exp.yaml", "maps[1].generate");
}

TEST(Experiment, ObjectsAreUniformInTheZoneWithClearanceAndReproducible) {
  const auto map = test::small_hidden_space();
  const ZoneSpec zone{1, 1.5, 0.2, 2.9, 1.0};  // straddles the partition at x 2.0..2.4
  const auto a = sample_zone_objects(map, zone, 200, 0.25, 42);
  const auto b = sample_zone_objects(map, zone, 200, 0.25, 42);
  ASSERT_EQ(a.size(), 200u);
  EXPECT_EQ(a, b);
  double left = 0;
  for (const auto& p : a) {
    EXPECT_GE(p.x(), 1.5);
    EXPECT_LE(p.x(), 2.9);
    EXPECT_GE(p.y(), 0.35 - 1e-9);  // 0.25 m from the bottom wall (y <= 0.1)
    EXPECT_TRUE(p.x() <= 1.75 + 1e-9 || p.x() >= 2.65 - 1e-9);  // and from the partition
    left += p.x() < 2.0;
  }
  // Free-with-clearance area left of the partition: 0.25 of (0.25 + 0.25) wide... roughly half.
  EXPECT_GT(left, 60);
  EXPECT_LT(left, 140);
}

TEST(Experiment, EveryMethodMeetsTheSameObjectsAndSeeds) {
  ExperimentDir s;
  auto c = load_experiment_config(
      s.config(kZones, "sweeps: {camera_fov_deg: [60, 120], objects_per_zone: 1}\n"));
  const auto runs = plan_runs(c);
  // main: 2 zones x 2 methods x 2 objects; sweep: 2 fovs x 2 zones x 2 methods x 1 object.
  ASSERT_EQ(runs.size(), 8u + 8u);
  std::set<std::tuple<int, int, double, double, std::uint64_t>> per_object;
  for (const auto& r : runs)
    per_object.insert({r.zone, r.object_index, r.object_W.x(), r.object_W.y(), r.seed});
  EXPECT_EQ(per_object.size(),
            4u);  // (zone, object) pairs: the method and sweep do not change them
  std::set<std::size_t> groups;
  for (const auto& r : runs) groups.insert(r.group);
  EXPECT_EQ(groups.size(), 4u + 8u);
}

TEST(Experiment, BootstrapIntervalOfASymmetricSampleMatchesTheNormalOne) {
  // 1..20: mean 10.5, population sd sqrt((n^2 - 1) / 12) = 5.766, so the resampled means
  // have sd 5.766 / sqrt(20) = 1.289 and the percentile interval is about
  // 10.5 -+ 1.96 * 1.289 = [7.97, 13.03] (Monte Carlo error of 10,000 resamples ~0.05).
  std::vector<double> v;
  for (int k = 1; k <= 20; ++k) v.push_back(k);
  const auto m = mean_ci95(v);
  EXPECT_DOUBLE_EQ(m.mean, 10.5);
  EXPECT_NEAR(m.lo, 7.97, 0.12);
  EXPECT_NEAR(m.hi, 13.03, 0.12);
  // {1, 2, 4}: of the 27 equally likely resamples, (1, 1, 1) alone has mean 1 and
  // (4, 4, 4) alone mean 4, each 1/27 = 3.7% > 2.5%: the interval is exactly [1, 4].
  const auto small = mean_ci95({1.0, 2.0, 4.0});
  EXPECT_DOUBLE_EQ(small.mean, 7.0 / 3.0);
  EXPECT_DOUBLE_EQ(small.lo, 1.0);
  EXPECT_DOUBLE_EQ(small.hi, 4.0);
  EXPECT_TRUE(std::isnan(mean_ci95({7.0}).lo));
  EXPECT_DOUBLE_EQ(mean_ci95({7.0}).mean, 7.0);
  EXPECT_TRUE(std::isnan(mean_ci95({}).mean));
  // The same sample always gives the same interval (fixed seed).
  EXPECT_EQ(mean_ci95(v).lo, m.lo);
}

TEST(Experiment, IntervalOfSkewedTimesStaysAboveZeroWhereStudentsDoesNot) {
  // 19 quick finds and one at 100 s: Student's t gives 5.095 -+ 2.093 * 22.34 / sqrt(20)
  // = [-5.36, 15.55]; a time cannot be negative.
  std::vector<double> v(19, 0.1);
  v.push_back(100.0);
  const auto m = mean_ci95(v);
  EXPECT_NEAR(m.mean, 5.095, 1e-9);
  EXPECT_GE(m.lo, 0.1);  // no resample mean is below the smallest value
  EXPECT_LT(m.lo, m.mean);
  EXPECT_GT(m.hi, m.mean);
  EXPECT_LE(m.hi, 100.0);
}

TEST(Experiment, IntervalNeverLeavesTheSampleRangeOnRandomSamples) {
  Rng rng(20261201);
  for (int trial = 0; trial < 300; ++trial) {
    const auto n = static_cast<std::size_t>(rng.uniform_int(2, 40));
    const double sigma = rng.uniform(0.1, 2.5);  // log-normal, up to very skewed
    std::vector<double> v(n);
    for (double& x : v) x = std::exp(rng.normal(0.0, sigma)) * (trial % 3 == 0 ? 1e-4 : 1.0);
    const auto m = mean_ci95(v);
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    ASSERT_GT(m.lo, 0.0) << trial;
    ASSERT_GE(m.lo, *lo) << trial;
    ASSERT_LE(m.hi, *hi) << trial;
    ASSERT_LE(m.lo, m.mean) << trial;
    ASSERT_GE(m.hi, m.mean) << trial;
  }
}

// The paired ratios of examples/plot_experiment.py (time of a method over rapid's on the
// same object) get their interval on the log scale. Run with Debian's python3.
TEST(Experiment, PlotScriptsRatioIntervalIsGeometricAndPositive) {
  if (std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "Debian's python3-matplotlib is not installed (scripts/install-deps)";
  test::TempDir dir;
  const std::string script = R"(
import math, random, sys
sys.path.insert(0, ")" FERRET_SOURCE_DIR R"(/examples")
from plot_experiment import geometric_mean_ci95 as gm
# {1, 2, 4}: logs 0, ln 2, 2 ln 2, mean ln 2 (g = 2), sd ln 2, t(0.975, 2) = 4.303:
# 2 exp(-+4.303 ln 2 / sqrt 3) = [0.357412, 11.19155].
g, lo, hi = gm([1.0, 2.0, 4.0])
print("%.6f %.6f %.5f" % (g, lo, hi))
# Symmetric in a/b versus b/a.
g2, lo2, hi2 = gm([1.0, 0.5, 0.25])
print("%.6f %.6f" % (lo2 * hi, hi2 * lo))
print(all(math.isnan(x) for x in gm([1.0, 0.0, 2.0])), math.isnan(gm([3.0])[1]))
rng = random.Random(7)
bad = 0
for trial in range(2000):
    v = [math.exp(rng.gauss(0, rng.uniform(0.1, 4))) for _ in range(rng.randint(2, 40))]
    g, lo, hi = gm(v)
    bad += not (0 < lo <= g <= hi)
print("bad", bad)
)";
  std::ofstream(dir / "check.py") << script;
  const std::string out = dir / "out.txt";
  ASSERT_EQ(std::system(("/usr/bin/python3 " + (dir / "check.py") + " > " + out).c_str()), 0);
  std::ifstream in(out);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "2.000000 0.357412 11.19155\n1.000000 1.000000\nTrue True\nbad 0\n");
}

TEST(Experiment, ShardsPartitionTheRunsAndConcatenateToTheWhole) {
  ExperimentDir s;
  const auto c = load_experiment_config(s.config(kZones));
  ExperimentOptions whole;
  whole.jobs = 2;
  run_experiment(c, s.dir.path() / "all", whole);
  std::set<std::string> shard_rows;
  for (int i = 0; i < 2; ++i) {
    ExperimentOptions o;
    o.shard_index = i;
    o.shard_count = 2;
    run_experiment(c, s.dir.path() / ("shard" + std::to_string(i)), o);
    std::ifstream in(s.dir.path() / ("shard" + std::to_string(i)) / "summary.csv");
    std::string line;
    std::getline(in, line);
    EXPECT_EQ(line, kSummaryHeader);
    while (std::getline(in, line)) shard_rows.insert(line);
  }
  std::ifstream in(s.dir.path() / "all" / "summary.csv");
  std::string line;
  std::getline(in, line);
  std::set<std::string> all_rows;
  while (std::getline(in, line)) all_rows.insert(line);
  EXPECT_EQ(all_rows.size(), 4u);
  EXPECT_EQ(shard_rows, all_rows);  // same numbers, whichever process ran them
  for (const auto& row : all_rows) EXPECT_THAT(row, HasSubstr(",2,2,"));  // 2 runs, 2 found
  // Every row's interval is a pair of times around the mean, none below zero.
  for (const auto& row : all_rows) {
    std::vector<std::string> f;
    std::stringstream in_row(row);
    for (std::string x; std::getline(in_row, x, ',');) f.push_back(x);
    ASSERT_EQ(f.size(), 9u) << row;  // kSummaryHeader's columns
    const double mean = std::stod(f[5]), lo = std::stod(f[6]), hi = std::stod(f[7]);
    EXPECT_GE(lo, 0.0) << row;
    EXPECT_LE(lo, mean) << row;
    EXPECT_GE(hi, mean) << row;
  }
}

TEST(Experiment, ARobotUrdfGivesSensorsAndLimitsAndTheConfigsKeysOverrideThem) {
  ExperimentDir s;
  std::filesystem::copy_file(std::string(FERRET_SOURCE_DIR) + "/tests/data/robots/rover.urdf",
                             s.dir.path() / "rover.urdf");
  auto c = load_experiment_config(s.config(kZones, "robot: {urdf: rover.urdf}\n"));
  EXPECT_EQ(c.robot_urdf, s.dir.path() / "rover.urdf");
  EXPECT_DOUBLE_EQ(c.base.sensors.camera_fov_rad, 1.2);
  EXPECT_EQ(c.base.sensors.image_width_px, 320);
  EXPECT_DOUBLE_EQ(c.base.sensors.ir_range_m, 2.5);
  EXPECT_EQ(c.base.sensors.ir_bearings_rad.size(), 10u);
  EXPECT_DOUBLE_EQ(c.base.robot.max_velocity_mps, 0.5);
  // Keys beside the URDF override single values; an IR fov spreads the beams over it.
  c = load_experiment_config(s.config(kZones,
                                      "robot: {urdf: rover.urdf, max_velocity: 0.2}\n"
                                      "sensors: {ir_fov_deg: 40, camera_range: 1.5}\n"));
  EXPECT_DOUBLE_EQ(c.base.robot.max_velocity_mps, 0.2);
  EXPECT_DOUBLE_EQ(c.base.sensors.camera_range_m, 1.5);
  EXPECT_DOUBLE_EQ(c.base.sensors.camera_fov_rad, 1.2);  // still the rover's
  EXPECT_TRUE(c.base.sensors.ir_bearings_rad.empty());
  EXPECT_EQ(c.base.sensors.ir_beams, 10);
  expect_input_error(s.config(kZones, "robot: {urdf: absent.urdf}\n"), "robot.urdf");
}

TEST(Experiment, WithoutARobotTheMissionsUgvLimitsDriveTheSearch) {
  ExperimentDir s;
  std::ofstream(s.dir.path() / "m.yaml")
      << "ugv_limits: {max_velocity_mps: 0.7, max_yaw_rate_radps: 1.1}\n";
  const auto c = load_experiment_config(s.config(kZones, "mission: m.yaml\n"));
  EXPECT_DOUBLE_EQ(c.base.robot.max_velocity_mps, 0.7);
  EXPECT_DOUBLE_EQ(c.base.robot.max_yaw_rate_radps, 1.1);
  // Without a mission: the paper's 2 m/s and 2 rad/s.
  const auto d = load_experiment_config(s.config(kZones));
  EXPECT_DOUBLE_EQ(d.base.robot.max_velocity_mps, 2.0);
  EXPECT_TRUE(d.base.sensors.ir_bearings_rad.empty());  // the dense fan
}

}  // namespace
}  // namespace ferret
