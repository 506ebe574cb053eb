#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "exploration_room.hpp"
#include "ferret/core/error.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/planning/policies.hpp"

namespace ferret {
namespace {

using World = test::HalfSeenRoom;

PolicyOptions options() { return PolicyOptions::from(MissionConfig{}, 4.0, 2.0); }

TEST(Policy, RegistryKnowsTheBuiltInsAndRejectsUnknownNames) {
  const auto names = exploration_policy_names();
  for (const char* n :
       {"cdos", "cdos-literal", "cdos-fg", "cdos-closest", "rapid", "nearest", "oracle", "bayes"}) {
    EXPECT_TRUE(has_exploration_policy(n)) << n;
    EXPECT_EQ(make_exploration_policy(n, options())->name(), n);
  }
  EXPECT_FALSE(has_exploration_policy("random"));
  EXPECT_THROW((void)make_exploration_policy("random", options()), InputError);
}

TEST(Policy, RapidChoosesTheLeastChangeOfVelocity) {
  World w;
  // Hand-built F_v: straight ahead, 30 degrees left, 60 degrees right.
  const auto& g = w.geo;
  const Cell ahead = g.cell_at(1.975, 1.0), left = g.cell_at(1.5, 1.0 + std::tan(deg_to_rad(30))),
             right = g.cell_at(1.0, 1.0 - 0.5 * std::tan(deg_to_rad(60)));
  w.sets.visible = {left, ahead, right};
  auto goal = RapidFrontierPolicy::choose_visible(w.state(), 2.0);
  ASSERT_TRUE(goal);
  EXPECT_EQ(goal->cell, ahead);  // at rest, the heading breaks the tie
  w.v = {std::cos(deg_to_rad(-55)) * 2.0, std::sin(deg_to_rad(-55)) * 2.0};  // moving right
  goal = RapidFrontierPolicy::choose_visible(w.state(), 2.0);
  EXPECT_EQ(goal->cell, right);
  w.v = {0.0, 1.0};  // moving left (+y) at 1 m/s
  goal = RapidFrontierPolicy::choose_visible(w.state(), 2.0);
  EXPECT_EQ(goal->cell, left);
  // |v_max u - v| for the chosen cell, by hand.
  const Eigen::Vector2d u = (g.center(left) - w.pose.position()).normalized();
  EXPECT_NEAR(goal->score, (2.0 * u - w.v).norm(), 1e-9);
}

TEST(Policy, RapidFallsBackToTheNearestFrontierByPath) {
  World w;
  w.pose = {0.5, 1.0, M_PI};  // facing away from the frontier: F_v empty
  w.refresh();
  ASSERT_TRUE(w.sets.visible.empty());
  ASSERT_FALSE(w.sets.global.empty());
  auto policy = make_exploration_policy("rapid", options());
  const auto goal = policy->choose(w.state());
  ASSERT_TRUE(goal);
  EXPECT_EQ(to_string(goal->reason), "nearest");
  EXPECT_EQ(goal->cell.i, 39);       // the frontier column
  EXPECT_NEAR(goal->cell.j, 20, 1);  // straight across
  ASSERT_TRUE(goal->heading_rad);
  EXPECT_NEAR(*goal->heading_rad, 0.0, 1e-9);  // facing the unknown
}

TEST(Policy, CdosWithoutEvidenceChoosesAsRapidDoes) {
  World w;
  w.v = {0.3, 0.8};
  auto cdos = make_exploration_policy("cdos", options());
  auto rapid = make_exploration_policy("rapid", options());
  const auto a = cdos->choose(w.state()), b = rapid->choose(w.state());
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->cell, b->cell);
}

TEST(Policy, CdosGoesTowardsEvidenceAndFacesIt) {
  World w;
  const Eigen::Vector2d object{3.0, 1.8};
  CameraFrame frame;  // one far detection: weak evidence
  frame.view = {w.pose, 4.0, {}};
  const Eigen::Vector2d to_object = object - w.pose.position();
  frame.detections = {
      {std::atan2(to_object.y(), to_object.x()), to_object.norm(), 1.0 / to_object.norm()}};
  w.objects.integrate_frame(frame);
  ASSERT_FALSE(w.objects.evidence_cells().empty());
  auto cdos = make_exploration_policy("cdos", options());
  const auto goal = cdos->choose(w.state());
  ASSERT_TRUE(goal);
  EXPECT_EQ(to_string(goal->reason), "curiosity");
  EXPECT_GT(goal->score, 0.0);
  // Among the visible frontier (x = 1.975, |y - 1| <= 1.5 * tan 30), the cell nearest the evidence.
  EXPECT_EQ(goal->cell.i, 39);
  EXPECT_NEAR(goal->p_W.y(), object.y(), 0.03);  // level with the evidence (the disk is symmetric)
  ASSERT_TRUE(goal->heading_rad);
  const Eigen::Vector2d to = object - goal->p_W;
  EXPECT_NEAR(*goal->heading_rad, std::atan2(to.y(), to.x()), 0.12);  // within the object's radius
}

TEST(Policy, OracleHeadsForAPoseThatSeesTheObject) {
  World w;
  auto oracle = make_exploration_policy("oracle", options());
  ASSERT_TRUE(oracle->needs_oracle());
  auto s = w.state();
  const Eigen::Vector2d object{3.5, 1.0};  // in the unknown half
  s.oracle_object_W = object;
  const auto goal = oracle->choose(s);
  ASSERT_TRUE(goal);
  EXPECT_EQ(to_string(goal->reason), "oracle");
  EXPECT_LE((goal->p_W - object).norm(), options().view_distance_m);
  EXPECT_NEAR(goal->p_W.x(), 3.5 - options().view_distance_m, 0.06);  // straight towards it
  ASSERT_GE(goal->path_W.size(), 2u);
  EXPECT_NEAR((goal->path_W.back() - goal->p_W).norm(), 0.0, 1e-9);
}

TEST(GridPathPlanner, DistancesDetoursAndUnreachableCells) {
  const GridGeometry geo{0.0, 0.0, 0.1, 30, 30};
  IrGrid::Options o;
  o.clearance_m = 0.0;
  IrGrid g(geo, o);
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 30; ++i) g.update_cell({i, j}, false);
  GridPathPlanner p(geo);
  p.compute(g, {0, 0}, GridPathPlanner::Traversal::kKnownFree);
  EXPECT_NEAR(p.distance_m({10, 0}), 1.0, 1e-6);
  EXPECT_NEAR(p.distance_m({10, 10}), 1.4, 1e-6);  // 10 diagonal steps at cost 7/5
  // A wall at i = 15 for j < 25: the way round is longer than straight.
  for (int j = 0; j < 25; ++j) g.update_cell({15, j}, true);
  p.compute(g, {10, 0}, GridPathPlanner::Traversal::kKnownFree);
  EXPECT_GT(p.distance_m({20, 0}), 4.5);
  const auto path = p.path_to({20, 0});
  ASSERT_GE(path.size(), 3u);
  for (const auto& q : path)
    EXPECT_FALSE(geo.cell_at(q.x(), q.y()).i == 15 && geo.cell_at(q.x(), q.y()).j < 25);
  // Closed off: unreachable.
  for (int i = 15; i < 30; ++i) g.update_cell({i, 25}, true);
  for (int i = 15; i < 30; ++i) g.update_cell({i, 25}, true);
  p.compute(g, {10, 0}, GridPathPlanner::Traversal::kKnownFree);
  EXPECT_FALSE(p.reachable({20, 0}));
  EXPECT_TRUE(p.path_to({20, 0}).empty());
}

}  // namespace
}  // namespace ferret

namespace ferret {
namespace {

TEST(Policy, RapidKeepsItsGoalWhileItIsAFrontierAndCdosDropsTheBaselineForEvidence) {
  World w;
  auto rapid = make_exploration_policy("rapid", options());
  const auto first = rapid->choose(w.state());
  ASSERT_TRUE(first);
  EXPECT_TRUE(rapid->keeps_goal(w.objects, w.tracker));
  w.v = {0.0, 2.0};  // a new velocity would change the rapid choice, but the goal is kept
  EXPECT_EQ(rapid->choose(w.state())->cell, first->cell);
  // Resolved (no longer a frontier): a new goal.
  for (int j = 0; j < 40; ++j) w.grid.update_cell({40, j}, false);
  w.refresh();
  EXPECT_FALSE(rapid->keeps_goal(w.objects, w.tracker));
  rapid->goal_done();
  EXPECT_FALSE(rapid->keeps_goal(w.objects, w.tracker));

  World u;
  auto cdos = make_exploration_policy("cdos", options());
  ASSERT_EQ(to_string(cdos->choose(u.state())->reason), "rapid");
  EXPECT_TRUE(cdos->keeps_goal(u.objects, u.tracker));
  u.objects.fuse(u.geo.cell_at(3.0, 1.5), 0.6);  // evidence appears: decide again
  EXPECT_FALSE(cdos->keeps_goal(u.objects, u.tracker));
}

TEST(GridPathPlanner, ARobotInsideTheClearanceBandCanLeaveItButNeverStopsInIt) {
  const GridGeometry geo{0.0, 0.0, 0.05, 60, 40};
  IrGrid::Options o;
  o.clearance_m = 0.15;
  IrGrid g(geo, o);
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 60; ++i) g.update_cell({i, j}, false);
  for (int j = 0; j < 40; ++j) g.update_cell({30, j}, true);  // a wall at x = 1.5 .. 1.55
  const Cell robot = geo.cell_at(1.43, 1.0);                  // 7 cm from it: inside the band
  GridPathPlanner p(geo);
  p.compute(g, robot, GridPathPlanner::Traversal::kKnownFree);
  EXPECT_FALSE(p.reachable(geo.cell_at(0.5, 1.0)));  // no escape band: stuck
  p.compute(g, robot, GridPathPlanner::Traversal::kKnownFree, 1.0);
  EXPECT_TRUE(p.reachable(geo.cell_at(0.5, 1.0)));
  EXPECT_FALSE(p.reachable(geo.cell_at(1.40, 1.5)));  // band cells are crossed, never goals
  const auto path = p.path_to(geo.cell_at(0.5, 1.0));
  ASSERT_GE(path.size(), 2u);
  EXPECT_LT(path[1].x(), 1.36);  // leaves the band straight away
}

}  // namespace
}  // namespace ferret
