#include "ferret/sim/experiment.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <sstream>

#include "ferret/core/error.hpp"
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

TEST(Experiment, MeanAndStudentInterval) {
  const auto m = mean_ci95({1.0, 2.0, 3.0, 4.0});
  EXPECT_DOUBLE_EQ(m.mean, 2.5);
  EXPECT_NEAR(m.ci95, 3.182 * std::sqrt(5.0 / 3.0) / 2.0, 1e-9);  // t(0.975, 3) s / sqrt(n)
  EXPECT_DOUBLE_EQ(mean_ci95({7.0}).ci95, 0.0);
  EXPECT_TRUE(std::isnan(mean_ci95({}).mean));
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
