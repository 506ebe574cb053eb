#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "support/cli_runner.hpp"
#include "support/test_maps.hpp"

namespace ferret::test {
namespace {

using ::testing::HasSubstr;

struct ExperimentDir {
  TempDir dir;
  ExperimentDir() { save_map_server(small_hidden_space(), dir.path() / "room.yaml"); }
  std::string config(const std::string& zones, const std::string& extra = "") const {
    std::ofstream out(dir.path() / "exp.yaml");
    out << "seed: 2\nobjects_per_zone: 2\nmethods: [cdos, rapid, oracle]\n"
        << extra
        << "maps:\n  - name: room\n    map: room.yaml\n    start: [0.5, 1.0, 0.0]\n    zones:\n"
        << zones;
    return (dir.path() / "exp.yaml").string();
  }
};

const char* kZones = "      1: [1.0, 0.5, 1.8, 1.5]\n      2: [2.8, 0.4, 4.6, 1.4]\n";

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ExperimentCli, WritesTheCsvsWithTheExactSummaryHeader) {
  ExperimentDir s;
  const std::string out = s.dir / "out";
  const auto r = run_cli("experiment " +
                         s.config(kZones, "sweeps: {ir_fov_deg: [20, 40], objects_per_zone: 1}\n") +
                         " --out " + out + " --jobs 2 --no-plots");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("runs/s"));  // the progress line
  const std::string summary = slurp(std::filesystem::path(out) / "summary.csv");
  EXPECT_EQ(summary.substr(0, summary.find('\n')),
            "map,zone,method,runs,found,mean_time_s,ci95_lo_time_s,ci95_hi_time_s,mean_path_m");
  EXPECT_THAT(summary, HasSubstr("room,2,oracle,2,2,"));
  const std::string runs = slurp(std::filesystem::path(out) / "runs.csv");
  EXPECT_EQ(std::count(runs.begin(), runs.end(), '\n'), 1 + 2 * 3 * 2 + 2 * 2 * 2 * 1);
  const std::string sweep = slurp(std::filesystem::path(out) / "sweep_ir_fov.csv");
  EXPECT_THAT(sweep, HasSubstr("room,1,cdos,90,20,1,"));
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(out) / "sweep_camera_fov.csv"));
}

TEST(ExperimentCli, BadConfigsExitTwoNamingTheFieldAndWriteNothing) {
  ExperimentDir s;
  struct Case {
    std::string zones, extra, field;
  };
  const Case cases[] = {
      {"      1: [1.0, 0.5, 1.8, 1.5]\n      3: [2.8, 0.4, 4.6, 1.4]\n", "",
       "maps[0].zones.2"},  // missing zone
      {"      1: [1.0, 0.5, 1.8, 1.5]\n      2: [2.8, 0.4, 7.0, 1.4]\n", "",
       "maps[0].zones.2"},  // outside
      {kZones, "time_limit_s: -1\n", "time_limit_s"},
  };
  for (const auto& c : cases) {
    const auto r =
        run_cli("experiment " + s.config(c.zones, c.extra) + " --out " + (s.dir / "out"));
    EXPECT_EQ(r.exit_code, 2) << c.field;
    EXPECT_THAT(r.err, HasSubstr(c.field));
    EXPECT_FALSE(std::filesystem::exists(s.dir / "out"));
  }
  {
    std::ofstream out(s.dir.path() / "exp.yaml");
    out << "methods: [cdos]\nmaps:\n  - {name: a, map: nowhere.yaml, start: [0.5, 1, 0], zones: "
           "{1: [1, 1, 2, 2]}}\n";
  }
  auto r = run_cli("experiment " + (s.dir / "exp.yaml") + " --out " + (s.dir / "out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("maps[0].map"));
  EXPECT_THAT(r.err, HasSubstr("nowhere.yaml"));
  r = run_cli("experiment " + s.config(kZones) + " --out " + (s.dir / "out") + " --shard 2/2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--shard"));
  EXPECT_FALSE(std::filesystem::exists(s.dir / "out"));
}

}  // namespace
}  // namespace ferret::test

namespace ferret::test {
namespace {

TEST(ExperimentCli, DrawsThePlotsFromTheCsvs) {
  if (std::system("/usr/bin/python3 -c 'import matplotlib' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "Debian's python3-matplotlib is not installed (scripts/install-deps)";
  ExperimentDir s;
  const std::string out = s.dir / "out";
  const auto r =
      run_cli("experiment " +
              s.config(kZones, "sweeps: {camera_fov_deg: [60, 120], objects_per_zone: 1}\n") +
              " --out " + out + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"time_room.png", "sweep_camera_fov.png", "ratios.csv"})
    EXPECT_TRUE(std::filesystem::is_regular_file(std::filesystem::path(out) / f)) << f << "\n"
                                                                                  << r.err;
  const std::string ratios = slurp(std::filesystem::path(out) / "ratios.csv");
  EXPECT_THAT(ratios, HasSubstr("map,zone,method,mean_time_s,ratio_to_rapid,ratio_to_oracle"));
  EXPECT_THAT(ratios, HasSubstr("room,1,rapid,"));
}

TEST(ExperimentCli, ARobotUrdfGivesTheSensorsOfEveryRun) {
  ExperimentDir s;
  const std::string rover = std::string(FERRET_SOURCE_DIR) + "/tests/data/robots/rover.urdf";
  std::filesystem::copy_file(rover, s.dir.path() / "rover.urdf");
  const std::string out = s.dir / "out";
  // robot.urdf is relative to the experiment YAML.
  const auto r = run_cli(
      "experiment " + s.config("      1: [1.0, 0.5, 1.8, 1.5]\n", "robot: {urdf: rover.urdf}\n") +
      " --out " + out + " --no-plots --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream runs(slurp(std::filesystem::path(out) / "runs.csv"));
  std::string line;
  std::getline(runs, line);
  EXPECT_EQ(line.substr(0, line.find(",seed")),
            "experiment,map,zone,object,method,camera_fov_deg,ir_fov_deg");
  int rows = 0;
  while (std::getline(runs, line)) {
    ++rows;
    // The rover's 1.2 rad camera and 50 deg IR array, not the miniUGV's 90 and 30.
    EXPECT_THAT(line, HasSubstr(",68.7549,50,")) << line;
  }
  EXPECT_EQ(rows, 3 * 2);

  // A URDF that is not there names the experiment's field.
  std::ofstream(s.dir.path() / "bad.yaml")
      << slurp(s.config(kZones, "robot: {urdf: no_such.urdf}\n"));
  const auto bad = run_cli("experiment " + (s.dir / "bad.yaml") + " --out " + (s.dir / "o2") +
                           " --no-plots --quiet");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("robot.urdf"));
  EXPECT_FALSE(std::filesystem::exists(s.dir.path() / "o2"));
}

}  // namespace
}  // namespace ferret::test
