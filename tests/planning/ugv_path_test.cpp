#include "ferret/planning/ugv_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "plan_check.hpp"

namespace ferret {
namespace {

const std::string kSource = FERRET_SOURCE_DIR;
const std::string kDetourWorld = kSource + "/examples/scenarios/tether_detour.yaml";
const std::string kDefaultWorld = kSource + "/examples/worlds/default.yaml";
const std::string kRover = kSource + "/tests/data/robots/rover.urdf";

const PlanningWorld& detour() {
  static const PlanningWorld world = load_planning_world(kDetourWorld);
  return world;
}

// The detour scenario (examples/scenarios/tether_detour.yaml): the miniUGV came in over
// the 6 x 3 m block and stands at its right end; the goal 3 m below needs the long way
// round within a 12.5 m budget.
UgvPathRequest detour_request() {
  UgvPathRequest req;
  req.start = {10.0, 4.5, -1.57};
  req.goal = {10.0, 1.5, -1.57};
  req.driven = {{1.0, 6.5}, {10.0, 6.5}};
  req.tether_budget_m = 12.5;
  return req;
}

double max_speed_mps(const PlanFile& plan) {
  double v = 0.0;
  for (std::size_t k = 1; k < plan.states.size(); ++k) {
    const double dt = plan.states[k].t_s - plan.states[k - 1].t_s;
    if (dt > 0)
      v = std::max(v, (plan.states[k].position() - plan.states[k - 1].position()).norm() / dt);
  }
  return v;
}

TEST(UgvPath, TheDetourStaysWithinTheBudgetAndThePlanIsValid) {
  const UgvPathResult r = plan_ugv_path(detour(), detour_request());
  ASSERT_TRUE(r.solved) << r.status;
  // Round the block's left end: the tether from the entry (-0.1, 4) bends at the
  // block's bottom-left corner (3, 2.5) to the goal (10, 1.5).
  EXPECT_NEAR(r.plan.states.back().tether_length_m, std::hypot(3.1, 1.5) + std::hypot(7.0, 1.0),
              1e-6);
  EXPECT_EQ(r.tether_budget_m, 12.5);
  ASSERT_TRUE(r.plan.tether.has_value());
  EXPECT_EQ(r.plan.tether->total_length_m, 13.5);      // l_0 (1 m) + the budget
  EXPECT_EQ(r.plan.tether->initial_wraps.size(), 2u);  // the block's two top corners
  EXPECT_TRUE(r.plan.tether->p_WE.isApprox(Eigen::Vector2d(-0.1, 4.0), 1e-12));
  EXPECT_EQ(r.plan.unknown_policy, UnknownPolicy::kOccupied);
  EXPECT_EQ(r.plan.planner, "TetheredRRT");
  EXPECT_EQ(std::filesystem::path(r.plan.robot_model).filename(), "miniugv.urdf");
  EXPECT_EQ(r.plan.max_velocity_mps, 2.0);  // the miniUGV's wheels allow the mission's 2 m/s
  EXPECT_FALSE(test::check_plan(detour(), r.plan).has_value());
}

// The rover's wheels (r = 0.04 m, 12.5 rad/s) cap it at 0.5 m/s, below the mission's
// 2 m/s: its plan is timed for 0.5 m/s, and the validator with the rover's own limits
// accepts it (with the mission's ugv_limits the plan would be four times too fast).
TEST(UgvPath, ARobotsWheelLimitCapsThePlansSpeed) {
  UgvPathRequest req = detour_request();
  req.robot.urdf = kRover;
  const UgvPathResult r = plan_ugv_path(detour(), req);
  ASSERT_TRUE(r.solved) << r.status;
  EXPECT_DOUBLE_EQ(r.plan.max_velocity_mps.value(), 0.5);
  EXPECT_LE(max_speed_mps(r.plan), 0.5 + 1e-9);
  EXPECT_GT(max_speed_mps(r.plan), 0.45);  // the straight drives go at the limit
  EXPECT_EQ(std::filesystem::path(r.plan.robot_model).filename(), "rover.urdf");
  const RobotDescription rover = load_robot_description(kRover);
  EXPECT_FALSE(test::check_plan(detour(), r.plan, rover.limits).has_value());
  // The same path driven at the miniUGV's plan speed would break the rover's limit.
  const UgvPathResult fast = plan_ugv_path(detour(), detour_request());
  ASSERT_TRUE(fast.solved);
  const auto too_fast = test::check_plan(detour(), fast.plan, rover.limits);
  ASSERT_TRUE(too_fast.has_value());
  EXPECT_EQ(too_fast->kind, ViolationKind::kSpeed) << too_fast->describe();
}

// The rover's base frame is at its body's centre, 0.07 m above the ground (the
// miniUGV's on the ground): its shapes are lifted so the wheels' bottom is 1 cm above
// the floor, not 6 cm below it.
TEST(UgvPath, AGroundRobotsShapeRestsOnTheFloorWhereverItsBaseFrameIs) {
  const LoadedPlanRobot rover = load_plan_robot(PlanRobot::kUgv, {kRover, false}, {});
  bool body_found = false;
  for (const ShapePart& p : rover.shape.parts) {
    if (p.kind == ShapePart::Kind::kBox && p.box_size_m.isApprox(Eigen::Vector3d(0.3, 0.2, 0.1))) {
      EXPECT_NEAR(p.X_BS.translation().z(), 0.08, 1e-12);  // 0 + (0.01 - (-0.07))
      body_found = true;
    }
    if (p.kind == ShapePart::Kind::kCylinder) {
      EXPECT_NEAR(p.X_BS.translation().z(), 0.05, 1e-12);  // the wheels: -0.03 + 0.08
    }
  }
  EXPECT_TRUE(body_found);
  EXPECT_NEAR(rover.ugv.body_size_m.z(), 0.12, 1e-12);  // wheel bottom -0.07 to body top 0.05
}

TEST(UgvPath, TheHiddenSpaceByNameByTheStartOrByABoxIsTheSame) {
  const UgvPathResult by_start = plan_ugv_path(detour(), detour_request());
  UgvPathRequest named = detour_request();
  named.hidden_space = "cellar";
  const UgvPathResult by_name = plan_ugv_path(detour(), named);
  ASSERT_TRUE(by_start.solved && by_name.solved);
  UgvPathRequest boxed = detour_request();
  boxed.bounds = Aabb3{{0, 0, 0}, {12, 8, 0.4}};  // the cellar's 12 x 8 m interior, floor z = 0
  boxed.p_WE = by_start.plan.tether->p_WE;        // (-0.1, 4) as the world YAML computes it
  const UgvPathResult by_box = plan_ugv_path(detour(), boxed);
  ASSERT_TRUE(by_box.solved);
  EXPECT_EQ(plan_to_json(by_name.plan), plan_to_json(by_start.plan));
  EXPECT_EQ(plan_to_json(by_box.plan), plan_to_json(by_start.plan));
}

TEST(UgvPath, AHiddenSpaceTheWorldLacksIsAnInputErrorListingThoseItHas) {
  const PlanningWorld world = load_planning_world(kDefaultWorld);
  UgvPathRequest req;
  req.start = {-7.3, 7.0, M_PI};
  req.goal = {-9.0, 7.0, M_PI};
  req.hidden_space = "attic";
  try {
    (void)plan_ugv_path(world, req);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "hidden_space");
    const std::string what = e.what();
    EXPECT_NE(what.find("attic"), std::string::npos) << what;
    EXPECT_NE(what.find("house_void, garage_void"), std::string::npos) << what;
  }
}

TEST(UgvPath, WithoutAHiddenSpaceOrAnEntryTheRequestIsAnInputError) {
  auto field_of = [](const UgvPathRequest& req) -> std::string {
    try {
      (void)plan_ugv_path(detour(), req);
    } catch (const InputError& e) {
      return e.field();
    }
    return "(no error)";
  };
  UgvPathRequest outside = detour_request();
  outside.start = {-0.5, -0.5, 0.0};      // outside the cellar, no box given
  EXPECT_EQ(field_of(outside), "start");  // where the search for a hidden space failed
  UgvPathRequest no_entry = outside;
  no_entry.bounds = Aabb3{{-1, -1, 0}, {0, 0, 0.4}};  // a box alone gives no entry
  EXPECT_EQ(field_of(no_entry), "p_WE");
  UgvPathRequest budget = detour_request();
  budget.tether_budget_m = -1.0;
  EXPECT_EQ(field_of(budget), "tether_budget_m");
  UgvPathRequest nan_goal = detour_request();
  nan_goal.goal.x_m = std::nan("");
  EXPECT_EQ(field_of(nan_goal), "goal");
  UgvPathRequest aerial = detour_request();
  aerial.robot.urdf = find_model("m100.urdf");
  EXPECT_EQ(field_of(aerial), "robot");  // a URDF of the other kind of robot
}

TEST(UgvPath, NoTetherFeasiblePathIsNotSolvedAndHasNoStates) {
  UgvPathRequest req = detour_request();
  // 14.8 m or 11.7 m of tether; 11.64 m in a straight line from the entry (-0.1, 4).
  req.goal = {11.0, 0.5, -1.57};
  req.tether_budget_m = 11.66;
  req.time_limit_s = 0.3;
  const UgvPathResult r = plan_ugv_path(detour(), req);
  EXPECT_FALSE(r.solved);
  EXPECT_NE(r.status.find("no tether-feasible path"), std::string::npos) << r.status;
  EXPECT_EQ(r.failure, PlanFailure::kTimeout);
  EXPECT_TRUE(r.plan.states.empty());
  req.tether_budget_m = 11.0;  // shorter than the straight line: no search at all
  const UgvPathResult too_short = plan_ugv_path(detour(), req);
  EXPECT_EQ(too_short.failure, PlanFailure::kTetherTooShort);
  EXPECT_TRUE(too_short.plan.states.empty());
}

TEST(UgvPath, APreparedSetupPlansWhatTheOneCallPlans) {
  const PlanningWorld world = detour();
  const UgvPathRequest req = detour_request();
  const UgvPathSetup setup = prepare_ugv_path(world, req, ugv_request_space(world, req));
  UgvPathResult once = plan_ugv_path(world, req);
  UgvPathResult twice = plan_ugv_path(world, req, setup);
  ASSERT_TRUE(once.solved);
  ASSERT_TRUE(twice.solved);
  once.plan.planning_time_s = twice.plan.planning_time_s = 0.0;  // wall time differs
  EXPECT_EQ(plan_to_json(once.plan), plan_to_json(twice.plan));
}

// A map_server map (a 2D hidden space, as `ferret explore` searches) is planned in as
// one hidden space: its walls stand on a floor at z = 0, the entry comes with the
// request. Ground truth is the 2D map itself: the miniUGV's inscribed circle (0.06 m,
// half its 0.12 m width) never covers an occupied or unknown cell's centre, and FCL
// on the extruded map agrees.
TEST(UgvPath, AMapServerMapIsOneHiddenSpaceWhoseWallsThePlanGoesRound) {
  const std::string yaml = kSource + "/examples/maps/sparse.yaml";
  const PlanningWorld world = load_planning_world(yaml);
  ASSERT_TRUE(world.map_2d.has_value());
  EXPECT_FALSE(world.spec.has_value());
  const OccupancyMap2D truth = load_map_server(yaml);
  UgvPathRequest req;
  req.start = {1.0, 4.0, 0.0};
  req.goal = {10.0, 4.0, 0.0};
  req.p_WE = Eigen::Vector2d(0.2, 4.0);
  // The straight line crosses the block at x 8.5..9.3: the plan must go round it.
  bool blocked = false;
  for (double x = 1.0; x <= 10.0; x += 0.01)
    blocked |= truth.state_at(x, 4.0) == CellState::kOccupied;
  ASSERT_TRUE(blocked);
  const UgvPathResult r = plan_ugv_path(world, req);
  ASSERT_TRUE(r.solved) << r.status;
  EXPECT_EQ(test::check_plan(world, r.plan), std::nullopt);
  EXPECT_NEAR(r.plan.bounds->lo.x(), 0.0, 1e-12);
  EXPECT_NEAR(r.plan.bounds->hi.y(), 8.0, 1e-12);
  EXPECT_NEAR(r.plan.bounds->lo.z(), 0.0, 1e-12);
  double length = 0.0;
  const double r_in = 0.06, res = truth.geometry.resolution_m;
  for (std::size_t k = 1; k < r.plan.states.size(); ++k) {
    const Eigen::Vector2d a = r.plan.states[k - 1].position().head<2>(),
                          b = r.plan.states[k].position().head<2>();
    length += (b - a).norm();
    const int n = static_cast<int>(std::ceil((b - a).norm() / 0.01)) + 1;
    for (int q = 0; q <= n; ++q) {
      const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(q) / n);
      for (double dx = -r_in; dx <= r_in + 1e-9; dx += res / 2)
        for (double dy = -r_in; dy <= r_in + 1e-9; dy += res / 2) {
          if (std::hypot(dx, dy) > r_in) continue;
          const Cell c = truth.geometry.cell_at(p.x() + dx, p.y() + dy);
          const Eigen::Vector2d centre(truth.geometry.origin_x_m + (c.i + 0.5) * res,
                                       truth.geometry.origin_y_m + (c.j + 0.5) * res);
          if ((centre - p).norm() > r_in) continue;
          ASSERT_EQ(truth.state_at(centre.x(), centre.y()), CellState::kFree)
              << "state " << k << " at " << p.transpose() << " covers cell " << c.i << "," << c.j;
        }
    }
  }
  EXPECT_GT(length, 9.0 + 0.1);
  // The map names no entry, and no hidden space by name.
  UgvPathRequest no_entry = req;
  no_entry.p_WE.reset();
  EXPECT_THROW(
      {
        try {
          (void)plan_ugv_path(world, no_entry);
        } catch (const InputError& e) {
          EXPECT_EQ(e.field(), "p_WE");
          throw;
        }
      },
      InputError);
  UgvPathRequest named = req;
  named.hidden_space = "cellar";
  EXPECT_THROW((void)plan_ugv_path(world, named), InputError);
}

}  // namespace
}  // namespace ferret
