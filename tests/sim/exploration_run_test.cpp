#include "ferret/sim/exploration_run.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "support/test_maps.hpp"

namespace ferret {
namespace {

ExplorationSettings settings(const std::string& method) {
  ExplorationSettings s;
  s.method = method;
  s.time_limit_s = 120;
  return s;
}

const Pose2 kStart{0.5, 1.0, 0.0};
const Eigen::Vector2d kBehindPartition{3.2, 0.8};  // out of sight from the start

class EveryMethod : public ::testing::TestWithParam<const char*> {};

TEST_P(EveryMethod, FindsTheObjectBehindThePartition) {
  const auto map = test::small_hidden_space();
  const auto r = run_exploration(map, kStart, kBehindPartition, settings(GetParam()), 5);
  EXPECT_TRUE(r.found) << r.end_reason;
  EXPECT_EQ(r.end_reason, "found");
  EXPECT_LE((r.found_W - kBehindPartition).norm(), 0.2);
  EXPECT_GT(r.path_m, 2.0);  // it had to go round the partition
  EXPECT_GT(r.decisions, 0);
  EXPECT_LT(r.time_s, 120.0);
}

INSTANTIATE_TEST_SUITE_P(Policies, EveryMethod,
                         ::testing::Values("cdos", "cdos-literal", "cdos-fg", "cdos-closest", "rapid", "nearest", "oracle"));

TEST(ExplorationRun, SameSeedSameRunAndTheOracleIsFastest) {
  const auto map = test::small_hidden_space();
  const auto a = run_exploration(map, kStart, kBehindPartition, settings("cdos"), 9);
  const auto b = run_exploration(map, kStart, kBehindPartition, settings("cdos"), 9);
  EXPECT_EQ(a.time_s, b.time_s);
  EXPECT_EQ(a.path_m, b.path_m);
  EXPECT_EQ(a.decisions, b.decisions);
  const auto oracle = run_exploration(map, kStart, kBehindPartition, settings("oracle"), 9);
  const auto rapid = run_exploration(map, kStart, kBehindPartition, settings("rapid"), 9);
  EXPECT_LE(oracle.time_s, a.time_s);
  EXPECT_LE(oracle.time_s, rapid.time_s);
}

TEST(ExplorationRun, ObjectInViewIsFoundQuicklyAndRecordsTheRun) {
  const auto map = test::small_hidden_space();
  auto s = settings("cdos");
  s.record = true;
  const auto r = run_exploration(map, kStart, {1.8, 2.3}, s, 2);  // 1.5 m away, 40 degrees left
  ASSERT_TRUE(r.found);
  EXPECT_LT(r.time_s, 5.0);
  ASSERT_TRUE(r.grid && r.objects);
  EXPECT_TRUE(r.objects->found_cell().has_value());
  EXPECT_EQ(r.trajectory.size(), static_cast<std::size_t>(std::lround(r.time_s * 20)) + 1);
  EXPECT_FALSE(r.decision_log.empty());
}

TEST(ExplorationRun, RejectsUnknownMethodsAndStartsInWalls) {
  const auto map = test::small_hidden_space();
  EXPECT_THROW((void)run_exploration(map, kStart, kBehindPartition, settings("random"), 1), std::invalid_argument);
  EXPECT_THROW((void)run_exploration(map, {2.2, 0.5, 0.0}, kBehindPartition, settings("cdos"), 1),
               std::invalid_argument);
}

}  // namespace
}  // namespace ferret
