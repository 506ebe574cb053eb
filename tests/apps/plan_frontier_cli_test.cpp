// `--planner ompl` (the OMPL frontier sampler with PRM) is deterministic given the
// run's seed: the same explore log, and the same runs.csv from two experiments that
// run their episodes in parallel threads.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "support/cli_runner.hpp"
#include "support/test_maps.hpp"

namespace ferret::test {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(PlannerOmplCli, ExploreLogsRepeatGivenTheSeed) {
  TempDir dir;
  const std::string args =
      "explore --map examples/maps/sparse.yaml --start 1,4,0 --object 9,6 --method cdos --planner "
      "ompl --seed 5 --out ";
  const auto a = run_cli(args + dir / "a");
  const auto b = run_cli(args + dir / "b");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  const std::string log = slurp(dir.path() / "a" / "log.json");
  EXPECT_NE(log.find("+ompl"), std::string::npos);  // PRM chose goals
  EXPECT_EQ(log, slurp(dir.path() / "b" / "log.json"));
}

TEST(PlannerOmplCli, ExperimentRunsRepeatWithParallelJobs) {
  TempDir dir;
  save_map_server(small_hidden_space(), dir.path() / "room.yaml");
  {
    std::ofstream out(dir.path() / "exp.yaml");
    out << "seed: 3\nobjects_per_zone: 3\nmethods: [cdos, rapid]\n"
        << "maps:\n  - name: room\n    map: room.yaml\n    start: [0.5, 1.0, 0.0]\n    zones:\n"
        << "      1: [1.0, 0.5, 1.8, 1.5]\n      2: [2.8, 0.4, 4.6, 1.4]\n";
  }
  std::string runs[2];
  for (int k = 0; k < 2; ++k) {
    const std::string out = dir / ("out" + std::to_string(k));
    const auto r = run_cli("experiment " + dir / "exp.yaml" + " --out " + out +
                           " --planner ompl --jobs 2 --no-plots");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    runs[k] = slurp(std::filesystem::path(out) / "runs.csv");
  }
  EXPECT_NE(runs[0].find("cdos+ompl"), std::string::npos);
  EXPECT_EQ(std::count(runs[0].begin(), runs[0].end(), '\n'), 1 + 2 * 2 * 3);
  EXPECT_EQ(runs[0], runs[1]);
}

}  // namespace
}  // namespace ferret::test
