#include "ferret/planning/plan_validation.hpp"

#include <gtest/gtest.h>

#include "ferret/planning/planning_world.hpp"
#include "ferret/planning/ugv_planner.hpp"
#include "test_maps.hpp"

namespace ferret {
namespace {

// The detour scenario's hidden space in code: 12 x 8 m, a 6 x 3 m block, and an
// unobserved 1 x 0.9 m patch at [10.5, 11.5] x [7, 7.9] (unknown, not free).
struct Fixture {
  std::unique_ptr<octomap::OcTree> tree;
  HiddenSpaceFrame space;
  std::shared_ptr<const CollisionMap> map;
  std::shared_ptr<const TetherCorners> corners;
  Fixture() {
    tree = test::hidden_space({{3, 9, 2.5, 5.5}}, {{10.5, 11.5, 7.0, 7.9}});
    space.p_WE = {0.0, 4.0};
    map = ugv_collision_map(*tree, space);
    corners = tether_corners_from_map(*map, space, UgvGeometry{});
  }
};

Waypoint at(double t, double x, double y, double yaw) {
  Waypoint w;
  w.t_s = t;
  w.x_m = x;
  w.y_m = y;
  w.yaw_rad = yaw;
  return w;
}

PlanFile ugv_plan(std::vector<Waypoint> states, double budget_m = 14.0) {
  PlanFile p;
  p.robot = PlanRobot::kUgv;
  p.states = std::move(states);
  p.tether = PlanTether{{0.0, 4.0}, {}, budget_m + 1.0, 1.0};
  return p;
}

ValidationOptions options(const Fixture& f) {
  ValidationOptions o;
  o.resolution = default_resolution(PlanRobot::kUgv);
  o.geofence = ugv_policy_bounds(f.space);
  return o;
}

std::optional<Violation> check(const Fixture& f, const PlanFile& p) {
  CollisionChecker checker(f.map, ugv_shape());
  return validate_plan(p, checker, f.corners, options(f));
}

TEST(PlanValidation, PlannerOutputIsValid) {
  Fixture f;
  UgvPlanner planner(f.map, f.space);
  UgvPlanRequest req;
  req.start = {1.0, 1.0, 0.0};
  req.goal = {11.0, 2.0, 0.0};
  req.tether = {15.0, 1.0};
  const UgvPlan result = planner.plan(req);
  ASSERT_TRUE(result.solved) << result.status;
  PlanFile p = ugv_plan(result.states);
  EXPECT_FALSE(check(f, p)) << check(f, p)->reason;
}

TEST(PlanValidation, ThroughAWall) {
  Fixture f;
  // Straight through the block from (2, 4) to (10, 4), at 1 m/s.
  const auto v = check(f, ugv_plan({at(0, 2, 4, 0), at(8, 10, 4, 0)}));
  ASSERT_TRUE(v);
  EXPECT_EQ(v->index, 1u);
  EXPECT_EQ(v->reason, "collision");
  // The first colliding pose: the box's front (6.5 cm ahead) meets x = 3.
  EXPECT_NEAR(v->p_W.x(), 3.0 - 0.065, 0.021);
  EXPECT_NEAR(v->t_s, v->p_W.x() - 2.0, 1e-9);
}

TEST(PlanValidation, ThroughUnknownSpace) {
  Fixture f;
  const PlanFile p = ugv_plan({at(0, 9.5, 7.4, 0), at(2.5, 11.9, 7.4, 0)});
  const auto v = check(f, p);
  ASSERT_TRUE(v);
  EXPECT_EQ(v->reason, "collision");
  EXPECT_GT(v->p_W.x(), 10.4);
  EXPECT_LT(v->p_W.x(), 10.5);
  // With unknown space free (as plain FCL sees it) the same plan passes.
  CollisionMapOptions free;
  free.unknown = UnknownPolicy::kFree;
  CollisionChecker lenient(CollisionMap::build(*f.tree, free), ugv_shape());
  EXPECT_FALSE(validate_plan(p, lenient, f.corners, options(f)));
}

TEST(PlanValidation, OverTheTetherLimit) {
  Fixture f;
  // Round the right end of the block from the top: 3.354 + 6 + |(9,5.5) - (10,1.5)|.
  const std::vector<Waypoint> s{at(0, 1, 6.5, 0), at(5, 10, 6.5, 0), at(6, 10, 6.5, -1.5708),
                                at(9, 10, 1.5, -1.5708)};
  const double need = std::hypot(3.0, 1.5) + 6.0 + std::hypot(1.0, 4.0);
  EXPECT_FALSE(check(f, ugv_plan(s, need + 0.01)));
  const auto v = check(f, ugv_plan(s, need - 0.01));
  ASSERT_TRUE(v);
  EXPECT_EQ(v->index, 3u);
  EXPECT_NE(v->reason.find("tether too long"), std::string::npos) << v->reason;
  // The same path with the tether budget from the command line.
  ValidationOptions o = options(f);
  o.tether_max_m = 5.0;
  CollisionChecker checker(f.map, ugv_shape());
  const auto early = validate_plan(ugv_plan(s, 100.0), checker, f.corners, o);
  ASSERT_TRUE(early);
  EXPECT_EQ(early->index, 1u);
}

TEST(PlanValidation, SpeedYawRateTimeAndFence) {
  Fixture f;
  auto reason = [&](std::vector<Waypoint> s) {
    const auto v = check(f, ugv_plan(std::move(s)));
    return v ? v->reason : std::string("valid");
  };
  EXPECT_EQ(reason({at(0, 1, 1, 0), at(1, 3, 1, 0)}), "valid");            // 2 m/s: the limit
  EXPECT_EQ(reason({at(0, 1, 1, 0), at(0.9, 3, 1, 0)}).substr(0, 8), "too fast");
  EXPECT_EQ(reason({at(0, 1, 1, 0), at(0.5, 1, 1, 1.5)}).substr(0, 8), "yaw rate");
  EXPECT_EQ(reason({at(1, 1, 1, 0), at(0, 1.5, 1, 0)}), "time does not increase");
  EXPECT_EQ(reason({at(0, 1, 1, 0), at(10, 1, -1, 0)}), "outside the geofence");
}

}  // namespace
}  // namespace ferret
