// Tether trajectories a careless or hostile user could write (generated here): each is
// an InputError naming the file and the field, before the simulator does any work.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/sim/tether_sim.hpp"
#include "support/cli_runner.hpp"

namespace ferret::sim {
namespace {

using ::testing::HasSubstr;

std::string write(const test::TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir / name;
  std::ofstream(path) << text;
  return path;
}

void expect_error(const std::string& path, const std::string& field, const std::string& expected,
                  const std::string& got = "") {
  try {
    (void)load_tether_scenario(path);
    FAIL() << "accepted " << path;
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), path);
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_THAT(e.expected(), HasSubstr(expected)) << e.what();
    EXPECT_THAT(std::string(e.what()), HasSubstr(got)) << e.what();
  }
}

TEST(TrajectoryBadInput, CsvCellsAreStrictDecimalNumbers) {
  test::TempDir dir;
  int k = 0;
  for (const std::string cell :
       {"", "nan", "-inf", "inf", "1e400", "-1e400", "0x10", "0x1p3", "2m", "+-1", "1 2"}) {
    SCOPED_TRACE(cell);
    std::string name = "c";  // built in steps: GCC 12 warns on "c" + std::to_string(k)
    name += std::to_string(k++);
    name += ".csv";
    const auto p = write(dir, name, "t,x,y,yaw\n0,0,0,0\n1," + cell + ",0,0\n");
    expect_error(p, "line 3, field 'x'", "a finite number");
  }
  // Exponents and a leading plus are numbers.
  const auto ok = write(dir, "ok.csv", "t,x,y,yaw\n0,0,0,0\n+1,2e-1,0,0\n");
  EXPECT_DOUBLE_EQ(load_tether_scenario(ok).samples.back().p_WG.x(), 0.2);
}

TEST(TrajectoryBadInput, CsvColumnsByNameAnyOrder) {
  test::TempDir dir;
  // yaw first, time last: the values land by name.
  const auto s = load_tether_scenario(write(dir, "p.csv", "yaw,y,x,t\n0.5,2,1,0\n0.5,3,1,2\n"));
  ASSERT_EQ(s.samples.size(), 2u);
  EXPECT_EQ(s.samples[1].t_s, 2.0);
  EXPECT_EQ(s.samples[1].p_WG.x(), 1.0);
  EXPECT_EQ(s.samples[1].p_WG.y(), 3.0);
  EXPECT_EQ(s.samples[1].yaw_rad, 0.5);
  EXPECT_DOUBLE_EQ(s.samples[0].v_WG.y(), 0.5);  // differentiated: 1 m in 2 s
  const auto d = load_tether_scenario(
      write(dir, "d.csv", "ay,ax,vy,vx,yaw,y,x,t\n8,7,6,5,0,0,0,0\n0,0,0,0,0,0,1,1\n"));
  EXPECT_EQ(d.samples[0].v_WG, Eigen::Vector2d(5, 6));
  EXPECT_EQ(d.samples[0].a_WG, Eigen::Vector2d(7, 8));
  expect_error(write(dir, "ab.csv", "a,b\n1,2\n"), "line 1 column 1", "a header naming", "'a'");
  expect_error(write(dir, "dup.csv", "t,x,y,yaw,x\n0,0,0,0,0\n"), "line 1 column 5", "each once");
  expect_error(write(dir, "miss.csv", "t,x,yaw\n0,0,0\n"), "line 1", "a header naming",
               "no column 'y'");
  expect_error(write(dir, "half.csv", "t,x,y,yaw,vx\n0,0,0,0,0\n"), "line 1", "a header naming",
               "no column 'vy'");
}

TEST(TrajectoryBadInput, DurationBoundedNotTheGap) {
  test::TempDir dir;
  // Two samples 1e7 s apart: 5e8 sim steps at 0.02 s; refused, naming the limit.
  expect_error(write(dir, "gap.csv", "t,x,y,yaw\n0,0,0,0\n1e7,1,0,0\n"), "line 3, field 't'",
               "at most 3600 s of simulated time", "1e+07 s");
  expect_error(write(dir, "gap.yaml", "samples: [[0, 0, 0, 0], [5, 1, 0, 0], [3601, 1, 1, 0]]\n"),
               "samples[2], field 't'", "at most 3600 s", "3601 s");
  // A large gap inside the limit is a trajectory: 3600 s from start to end exactly.
  const auto s =
      load_tether_scenario(write(dir, "hour.csv", "t,x,y,yaw\n-100,0,0,0\n3500,1,0,0\n"));
  EXPECT_DOUBLE_EQ(s.end_s() - s.start_s(), 3600.0);
  // A script that would take 1e8 s: refused before its samples are made.
  expect_error(write(dir, "slow.yaml",
                     "script: {waypoints_xy_m: [[0, 0], [100000, 0]], cruise_mps: 0.001, "
                     "accel_mps2: 1}\n"),
               "script.waypoints_xy_m", "at most 3600 s", "1e+08 s");
}

TEST(TrajectoryBadInput, PositionsBoundedAndFinite) {
  test::TempDir dir;
  expect_error(write(dir, "far.csv", "t,x,y,yaw\n0,0,0,0\n1,4e9,0,0\n"), "line 3, field 'x'/'y'",
               "within +-100000 m");
  expect_error(write(dir, "far.yaml", "samples: [[0, 0, 0, 0], [1, 0, -2e5, 0]]\n"),
               "samples[1], field 'x'/'y'", "within +-100000 m");
  expect_error(write(dir, "inf.yaml", "samples: [[0, 0, 0, 0], [1, .inf, 0, 0]]\n"),
               "samples[1][1]", "a finite number");
  expect_error(
      write(dir, "entry.yaml", "entry_xy_m: [.nan, 0]\nsamples: [[0, 0, 0, 0], [1, 1, 0, 0]]\n"),
      "entry_xy_m[0]", "a finite number", "'.nan'");  // the element, by the YAML number parser
  expect_error(write(dir, "wrap.yaml",
                     "wrap_points: [{xy_m: [1, 1e9]}]\nsamples: [[0, 0, 0, 0], [1, 1, 0, 0]]\n"),
               "wrap_points[0].xy_m", "within +-100000 m");
}

TEST(TrajectoryBadInput, YamlKeysAndTimes) {
  test::TempDir dir;
  expect_error(write(dir, "key.yaml", "samples: [[0, 0, 0, 0], [1, 1, 0, 0]]\nsampels: []\n"),
               "sampels", "");
  expect_error(write(dir, "back.yaml", "samples: [[0, 0, 0, 0], [1, 1, 0, 0], [1, 2, 0, 0]]\n"),
               "samples[2], field 't'", "a time greater than the previous sample's");
  expect_error(write(dir, "type.yaml", "samples: [[0, 0, 0, 0], [1, one, 0, 0]]\n"),
               "samples[1][1]", "number");
}

TEST(TrajectoryBadInput, CliGapExitsTwoNamingTheLimitWithoutOutput) {
  test::TempDir dir;
  const auto p = write(dir, "gap.csv", "t,x,y,yaw\n0,0,0,0\n1e7,1,0,0\n");
  const auto r = test::run_cli("tether-sim --trajectory '" + p + "' -o '" + (dir / "out") + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("gap.csv: line 3, field 't'"));
  EXPECT_THAT(r.err, HasSubstr("at most 3600 s of simulated time"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

}  // namespace
}  // namespace ferret::sim
