#include "ferret/planning/ugv_planner.hpp"

#include <gtest/gtest.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/SE2StateSpace.h>

#include "ferret/planning/collision_checker.hpp"
#include "test_maps.hpp"

namespace ferret {
namespace {

using V = Eigen::Vector2d;
namespace ob = ompl::base;

std::shared_ptr<const CollisionMap> hidden_map(const std::vector<Eigen::Vector4d>& blocks) {
  CollisionMapOptions opt;
  opt.unknown = UnknownPolicy::kOccupied;  // the hidden-space policy
  opt.bounds = Aabb3{{0, 0, 0}, {12, 8, 0.1}};
  return CollisionMap::build(*test::hidden_space(blocks), opt);
}

HiddenSpaceFrame frame() {
  HiddenSpaceFrame f;
  f.lo_m = {0.0, 0.0};
  f.hi_m = {12.0, 8.0};
  f.p_WE = {0.0, 4.0};
  return f;
}

// Every state collision-free by FCL alone, every segment too, and the tether in budget.
void expect_valid(UgvPlanner& planner, const UgvPlan& plan, const TetherParams& tether) {
  ASSERT_TRUE(plan.solved) << plan.status;
  ASSERT_GE(plan.states.size(), 2u);
  for (std::size_t k = 0; k < plan.states.size(); ++k) {
    const Waypoint& w = plan.states[k];
    EXPECT_FALSE(planner.checker().in_collision_fcl(w.pose())) << k;
    EXPECT_LE(tether.entry_offset_m + w.tether_length_m, tether.total_length_m + 1e-9) << k;
    if (k > 0) {
      EXPECT_GE(w.t_s, plan.states[k - 1].t_s);
      EXPECT_FALSE(
          first_collision(planner.checker(), plan.states[k - 1], w, CheckResolution{}, true))
          << k;
      // Turn in place or drive straight along the heading, never both.
      const Waypoint& p = plan.states[k - 1];
      const bool turns = std::abs(wrap_angle_rad(w.yaw_rad - p.yaw_rad)) > 1e-9;
      const bool moves = std::hypot(w.x_m - p.x_m, w.y_m - p.y_m) > 1e-9;
      EXPECT_FALSE(turns && moves) << k;
      if (moves) {
        const double h = std::atan2(w.y_m - p.y_m, w.x_m - p.x_m);
        EXPECT_LT(std::min(std::abs(wrap_angle_rad(h - w.yaw_rad)),
                           std::abs(wrap_angle_rad(h + std::numbers::pi - w.yaw_rad))),
                  1e-6);
      }
    }
  }
}

TEST(UgvPlanner, PlansAroundObstaclesWithinTheTether) {
  const auto map = hidden_map({{3, 4, 0, 6}, {7, 8, 2, 8}});
  UgvPlannerOptions opt;
  opt.final_check_fcl_only = true;
  UgvPlanner planner(map, frame(), {}, opt);
  UgvPlanRequest req;
  req.start = {1.0, 4.0, 0.0};
  req.goal = {11.0, 4.0, 1.5};
  req.tether = {20.0, 1.0};  // the taut slalom is 14.2 m
  const UgvPlan plan = planner.plan(req);
  ASSERT_NO_FATAL_FAILURE(expect_valid(planner, plan, req.tether));
  EXPECT_NEAR(plan.states.back().x_m, 11.0, 1e-9);
  EXPECT_NEAR(plan.states.back().yaw_rad, 1.5, 1e-9);
  // The slalom wraps the tether on the first wall's top end and the second's bottom.
  EXPECT_GE(plan.final_wraps.size(), 2u);
  // Deterministic given the seed.
  const UgvPlan again = planner.plan(req);
  ASSERT_EQ(again.states.size(), plan.states.size());
  for (std::size_t k = 0; k < plan.states.size(); ++k)
    EXPECT_EQ(again.states[k].x_m, plan.states[k].x_m);
}

TEST(UgvPlanner, RejectsBadEndpoints) {
  const auto map = hidden_map({{3, 4, 0, 6}});
  UgvPlannerOptions opt;
  opt.time_limit_s = 0.2;
  UgvPlanner planner(map, frame(), {}, opt);
  UgvPlanRequest req;
  req.start = {1.0, 4.0, 0.0};
  req.tether = {15.0, 1.0};
  req.goal = {3.5, 3.0, 0.0};
  EXPECT_EQ(planner.plan(req).status, "goal in collision");
  req.goal = {13.0, 3.0, 0.0};
  EXPECT_EQ(planner.plan(req).status, "goal outside the hidden space");
  req.goal = {11.0, 3.0, 0.0};
  req.tether = {5.0, 1.0};  // 4 m of tether; the goal is 10 m away
  EXPECT_FALSE(planner.plan(req).solved);
}

// The scenario of examples/scenarios/tether_detour.yaml: the miniUGV came over the
// top of a long block and stands at its right end. The goal is just below it; the
// short way continues round the block and would need 13.48 m of taut tether. With
// 12.5 m the planner must go back over the top and round the left end instead.
TEST(UgvPlanner, ShortestPathInfeasibleForTheTether) {
  const auto map = hidden_map({{3, 9, 2.5, 5.5}});
  UgvPlannerOptions opt;
  opt.time_limit_s = 2.0;
  UgvPlanner planner(map, frame(), {}, opt);
  UgvPlanRequest req;
  req.driven = {{1.0, 6.5}, {10.0, 6.5}};
  req.start = {10.0, 4.5, -1.57};
  req.goal = {10.0, 1.5, -1.57};
  req.tether = {13.5, 1.0};
  const UgvPlan plan = planner.plan(req);
  ASSERT_EQ(plan.initial_wraps.size(), 2u);
  EXPECT_TRUE(plan.initial_wraps[0].p_W.isApprox(V{3, 5.5}));
  ASSERT_NO_FATAL_FAILURE(expect_valid(planner, plan, req.tether));
  // It went round the left: the tether now bends at the block's bottom-left corner only.
  ASSERT_EQ(plan.final_wraps.size(), 1u);
  EXPECT_TRUE(plan.final_wraps[0].p_W.isApprox(V{3, 2.5}));
  EXPECT_NEAR(plan.states.back().tether_length_m, std::hypot(3.0, 1.5) + std::hypot(7.0, 1.0),
              1e-9);
  double driven = 0.0;
  for (std::size_t k = 1; k < plan.states.size(); ++k)
    driven += (plan.states[k].position() - plan.states[k - 1].position()).norm();
  EXPECT_GT(driven, 15.0);  // far longer than the 3 m straight drive

  // A goal further down, (11, 0.5), needs 14.83 m one way and 11.69 m the other, and
  // lies 11.54 m from the entry (0, 4) in a straight line. With 11.6 m neither way fits
  // (the start needs 10.77 m): the search runs out of time.
  req.goal = {11.0, 0.5, -1.57};
  req.tether = {12.6, 1.0};
  UgvPlannerOptions quick = opt;
  quick.time_limit_s = 0.3;
  UgvPlanner limited(map, frame(), {}, quick);
  const UgvPlan none = limited.plan(req);
  EXPECT_FALSE(none.solved);
  EXPECT_EQ(none.status, "no tether-feasible path found within the time limit");
  EXPECT_EQ(none.failure, PlanFailure::kTimeout);
  EXPECT_TRUE(none.states.empty());
  // With 11 m even the straight line is too long: refused at once, without a search.
  req.tether = {12.0, 1.0};
  const UgvPlan short_tether = limited.plan(req);
  EXPECT_FALSE(short_tether.solved);
  EXPECT_EQ(short_tether.failure, PlanFailure::kTetherTooShort);
  EXPECT_EQ(short_tether.tree_size, 0u);
  EXPECT_TRUE(short_tether.states.empty());
  // A cancel flag already raised stops the search before its time limit.
  req.tether = {12.6, 1.0};
  UgvPlannerOptions cancelled = quick;
  cancelled.time_limit_s = 30.0;
  cancelled.cancelled = [] { return true; };
  UgvPlanner stopped(map, frame(), {}, cancelled);
  const UgvPlan gone = stopped.plan(req);
  EXPECT_FALSE(gone.solved);
  EXPECT_EQ(gone.failure, PlanFailure::kCancelled);
  EXPECT_LT(gone.planning_time_s, 5.0);  // not the 30 s limit (a bound, not a timing)
}

TEST(UgvPlanner, ReturnRetracesTheTether) {
  const auto map = hidden_map({{3, 9, 2.5, 5.5}});
  UgvPlanner planner(map, frame());
  UgvPlanRequest req;
  req.driven = {{1.0, 6.5}, {10.0, 6.5}};
  req.start = {10.0, 4.5, -1.57};
  req.goal = {1.0, 4.0, 3.14};
  req.tether = {15.0, 1.0};
  const UgvPlan back = planner.plan_return(req);
  ASSERT_NO_FATAL_FAILURE(expect_valid(planner, back, req.tether));
  EXPECT_TRUE(back.final_wraps.empty());
  EXPECT_NEAR(back.states.back().tether_length_m, 1.0, 1e-9);
  // The tether only shortens on the way back.
  for (std::size_t k = 1; k < back.states.size(); ++k)
    EXPECT_LE(back.states[k].tether_length_m, back.states[k - 1].tether_length_m + 1e-9);
}

// Pitfall (OMPL 1.5: coarse discrete checks, under-counted segments in curved
// spaces): a straight drive between two free states that clips a thin post. OMPL's
// discrete validator at a coarse resolution accepts it; ours checks every 2 cm.
TEST(UgvPlanner, MotionClippingACornerIsRejected) {
  const auto map = hidden_map({{6.0, 6.05, 3.95, 4.0}});  // one 5 cm voxel post
  UgvPlanner planner(map, frame());
  const Waypoint a = planner.waypoint({5.0, 4.02, 0.0}), b = planner.waypoint({7.0, 4.02, 0.0});
  EXPECT_FALSE(planner.checker().in_collision(a.pose()));
  EXPECT_FALSE(planner.checker().in_collision(b.pose()));
  EXPECT_TRUE(first_collision(planner.checker(), a, b, CheckResolution{}));

  auto space = std::make_shared<ob::SE2StateSpace>();
  ob::RealVectorBounds bounds(2);
  bounds.setLow(0);
  bounds.setHigh(0, 12);
  bounds.setHigh(1, 8);
  space->setBounds(bounds);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([&](const ob::State* s) {
    const auto* se2 = s->as<ob::SE2StateSpace::StateType>();
    return !planner.checker().in_collision(
        planner.waypoint({se2->getX(), se2->getY(), se2->getYaw()}).pose());
  });
  // A coarse resolution (3% of the space's extent, ~0.5 m), as is common to save time.
  si->setStateValidityCheckingResolution(0.03);
  si->setup();
  ob::ScopedState<ob::SE2StateSpace> s1(space), s2(space);
  s1->setXY(5.0, 4.02);
  s1->setYaw(0.0);
  s2->setXY(7.0, 4.02);
  s2->setYaw(0.0);
  EXPECT_TRUE(si->checkMotion(s1.get(), s2.get()));  // the trap
}

}  // namespace
}  // namespace ferret
