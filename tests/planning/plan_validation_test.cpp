#include "ferret/planning/plan_validation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <type_traits>

#include "ferret/core/error.hpp"
#include "ferret/planning/floor_from_map.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/planning/ugv_planner.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "support/cli_runner.hpp"
#include "test_maps.hpp"
#include "waypoints.hpp"

namespace ferret {
namespace {

using test::ugv_at;

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

PlanFile ugv_plan(std::vector<Waypoint> states, double budget_m = 14.0) {
  PlanFile p;
  p.robot = PlanRobot::kUgv;
  p.states = std::move(states);
  p.tether = PlanTether{{0.0, 4.0}, {}, budget_m + 1.0, 1.0};
  return p;
}

// Limits unlike any robot's defaults in the acceleration, so a test that passes is
// not passing on a shipped value.
constexpr MotionLimits kLimits{2.0, 2.0, 2.0};

ValidationOptions options(const Fixture& f, const MotionLimits& limits = kLimits) {
  ValidationOptions o(limits, default_resolution(PlanRobot::kUgv));
  o.geofence = ugv_policy_bounds(f.space);
  o.observed = f.tree.get();
  return o;
}

ValidationReport check(const Fixture& f, const PlanFile& p, const MotionLimits& limits = kLimits) {
  CollisionChecker checker(f.map, ugv_shape());
  return validate_plan(p, checker, f.corners, options(f, limits));
}

std::vector<ViolationKind> kinds(const ValidationReport& r) {
  std::vector<ViolationKind> out;
  for (const auto& v : r.violations) out.push_back(v.kind);
  return out;
}

// The limits are the robot's, always given: no default could be right for every robot.
static_assert(!std::is_default_constructible_v<ValidationOptions>);

TEST(PlanValidation, PlannerOutputIsValid) {
  Fixture f;
  UgvPlanner planner(f.map, f.space);
  UgvPlanRequest req;
  req.start = {1.0, 1.0, 0.0};
  req.goal = {11.0, 2.0, 0.0};
  req.tether = {15.0, 1.0};
  const UgvPlan result = planner.plan(req);
  ASSERT_TRUE(result.solved) << result.status;
  // The planner times its paths at the speed limits and has no acceleration model
  // (each drive starts at full speed): every check but acceleration must pass.
  const auto r =
      check(f, ugv_plan(result.states), {2.0, std::numeric_limits<double>::infinity(), 2.0});
  EXPECT_TRUE(r.valid()) << r.violations.front().describe();
  EXPECT_LE(r.margins.peak_speed_mps, 2.0 + 1e-9);
  EXPECT_GT(r.margins.min_clearance_m, 0.0);  // it never touches
  EXPECT_LE(*r.margins.peak_tether_m, 14.0);
}

TEST(PlanValidation, ThroughAWall) {
  Fixture f;
  // Straight through the block from (2, 4) to (10, 4), at 1 m/s.
  const auto r = check(f, ugv_plan({ugv_at(0, 2, 4, 0), ugv_at(8, 10, 4, 0)}));
  ASSERT_EQ(r.violations.size(), 1u);  // one segment, one collision (its first pose)
  const Violation& v = r.violations[0];
  EXPECT_EQ(v.kind, ViolationKind::kCollision);
  EXPECT_EQ(v.from_index, 0u);
  EXPECT_EQ(v.to_index, 1u);
  // The first colliding pose: the box's front (6.5 cm ahead) meets x = 3.
  EXPECT_NEAR(v.p_W.x(), 3.0 - 0.065, 0.021);
  EXPECT_NEAR(v.t_s, v.p_W.x() - 2.0, 1e-9);
  EXPECT_NEAR(v.s, v.t_s / 8.0, 1e-12);
  EXPECT_EQ(v.part, "ugv_body");
  // The voxel hit: the block's first column (centre x = 3.025), in front of the robot.
  ASSERT_TRUE(v.obstacle);
  EXPECT_NEAR(v.obstacle->p_W.x(), 3.025, 1e-9);
  EXPECT_LE(std::abs(v.obstacle->p_W.y() - 4.0), 0.06 + 0.025 + 1e-9);
  EXPECT_GT(v.obstacle->p_W.z(), 0.0);  // not the floor
  EXPECT_EQ(r.margins.min_clearance_m, 0.0);
}

// A deadline stops a long check part-way through a segment, and a check cut short is
// never reported as a pass: ValidationCancelled, not a report without the collision.
TEST(PlanValidation, ACancelledCheckStopsInsideASegmentAndIsNeverAPass) {
  Fixture f;
  // Through the block, then on along y = 4 for 7 m more: 1 000 poses at 1 cm.
  const PlanFile p = ugv_plan({ugv_at(0, 1, 4, 0), ugv_at(10, 11, 4, 0)});
  CollisionChecker checker(f.map, ugv_shape());
  int asked = 0;
  ValidationOptions o = options(f);
  o.cancelled = [&] { return ++asked > 3; };  // true from the 4th question on
  EXPECT_THROW((void)validate_plan(p, checker, f.corners, o), ValidationCancelled);
  EXPECT_GE(asked, 4);  // asked inside the segment's poses, not only between states
  // Never asked to stop: the same plan's collision is found.
  o.cancelled = [] { return false; };
  const ValidationReport r = validate_plan(p, checker, f.corners, o);
  ASSERT_EQ(r.violations.size(), 1u);
  EXPECT_EQ(r.violations[0].kind, ViolationKind::kCollision);
}

TEST(PlanValidation, ThroughUnknownSpace) {
  Fixture f;
  const PlanFile p = ugv_plan({ugv_at(0, 9.5, 7.4, 0), ugv_at(2.5, 11.9, 7.4, 0)});
  const auto r = check(f, p);
  ASSERT_EQ(r.violations.size(), 1u);
  EXPECT_EQ(r.violations[0].kind, ViolationKind::kUnknownSpace);
  EXPECT_GT(r.violations[0].p_W.x(), 10.4);
  EXPECT_LT(r.violations[0].p_W.x(), 10.5);
  EXPECT_NEAR(r.violations[0].obstacle->p_W.x(), 10.525, 1e-9);  // the patch's first voxel
  EXPECT_EQ(r.violations[0].describe().substr(r.violations[0].describe().find(": ")),
            ": collision of ugv_body with unknown space (voxel at 10.525, 7.375, 0.025)");
  // Without the observed map, the same voxel is a plain collision.
  CollisionChecker checker(f.map, ugv_shape());
  ValidationOptions blind = options(f);
  blind.observed = nullptr;
  EXPECT_EQ(kinds(validate_plan(p, checker, f.corners, blind)),
            std::vector{ViolationKind::kCollision});
  // With unknown space free (as plain FCL sees it) the same plan passes.
  CollisionMapOptions free;
  free.unknown = UnknownPolicy::kFree;
  CollisionChecker lenient(CollisionMap::build(*f.tree, free), ugv_shape());
  EXPECT_TRUE(validate_plan(p, lenient, f.corners, options(f)).valid());
}

TEST(PlanValidation, OverTheTetherLimit) {
  Fixture f;
  // Round the right end of the block from the top: 3.354 + 6 + |(9,5.5) - (10,1.5)|.
  const std::vector<Waypoint> s{ugv_at(0, 1, 6.5, 0), ugv_at(5, 10, 6.5, 0),
                                ugv_at(6, 10, 6.5, -1.5708), ugv_at(9, 10, 1.5, -1.5708)};
  const double need = std::hypot(3.0, 1.5) + 6.0 + std::hypot(1.0, 4.0);
  const auto fits = check(f, ugv_plan(s, need + 0.01));
  EXPECT_TRUE(fits.valid());
  EXPECT_NEAR(*fits.margins.peak_tether_m, need, 0.01);
  EXPECT_NEAR(*fits.margins.tether_budget_m, need + 0.01, 1e-9);
  const auto r = check(f, ugv_plan(s, need - 0.01));
  ASSERT_EQ(r.violations.size(), 1u);
  const Violation& v = r.violations[0];
  EXPECT_EQ(v.kind, ViolationKind::kTetherLength);
  EXPECT_EQ(v.from_index, 3u);
  EXPECT_EQ(v.to_index, 3u);
  EXPECT_NEAR(v.value, need, 0.01);
  EXPECT_NEAR(v.limit, need - 0.01, 1e-9);
  // The budget from the caller: 5 m is over at states 1, 2 and 3 (9.6 m and more).
  ValidationOptions o = options(f);
  o.tether_max_m = 5.0;
  CollisionChecker checker(f.map, ugv_shape());
  const auto early = validate_plan(ugv_plan(s, 100.0), checker, f.corners, o);
  ASSERT_EQ(early.violations.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(early.violations[k].kind, ViolationKind::kTetherLength);
    EXPECT_EQ(early.violations[k].from_index, k + 1);
  }
}

TEST(PlanValidation, SpeedYawRateTimeAndFence) {
  Fixture f;
  auto kind = [&](std::vector<Waypoint> s) {
    const auto r = check(f, ugv_plan(std::move(s)));
    return r.valid() ? std::string("valid") : std::string(to_string(r.violations.front().kind));
  };
  EXPECT_EQ(kind({ugv_at(0, 1, 1, 0), ugv_at(1, 3, 1, 0)}), "valid");  // 2 m/s: the limit
  EXPECT_EQ(kind({ugv_at(0, 1, 1, 0), ugv_at(0.9, 3, 1, 0)}), "speed");
  EXPECT_EQ(kind({ugv_at(0, 1, 1, 0), ugv_at(0.5, 1, 1, 1.5)}), "yaw_rate");
  EXPECT_EQ(kind({ugv_at(1, 1, 1, 0), ugv_at(0, 1.5, 1, 0)}), "time_order");
  EXPECT_EQ(kind({ugv_at(0, 1, 1, 0), ugv_at(10, 1, -1, 0)}), "geofence");
  const auto fast = check(f, ugv_plan({ugv_at(0, 1, 1, 0), ugv_at(0.5, 3, 1, 0)}));
  ASSERT_EQ(fast.violations.size(), 1u);
  EXPECT_NEAR(fast.violations[0].value, 4.0, 1e-12);
  EXPECT_EQ(fast.violations[0].limit, 2.0);
  EXPECT_NEAR(fast.margins.peak_speed_mps, 4.0, 1e-12);
}

TEST(PlanValidation, Acceleration) {
  Fixture f;
  // At rest for 0.1 s, then 1.9 m/s for 0.1 s: 1.9 m/s in the 0.1 s mean of the two
  // segments' durations is 19 m/s^2, reported at state 1 across segments 0-1 and 1-2.
  const auto r =
      check(f, ugv_plan({ugv_at(0, 1, 1, 0), ugv_at(0.1, 1, 1, 0), ugv_at(0.2, 1.19, 1, 0)}));
  ASSERT_EQ(r.violations.size(), 1u);
  const Violation& v = r.violations[0];
  EXPECT_EQ(v.kind, ViolationKind::kAcceleration);
  EXPECT_EQ(v.from_index, 0u);
  EXPECT_EQ(v.to_index, 2u);
  EXPECT_NEAR(v.t_s, 0.1, 1e-12);
  EXPECT_NEAR(v.s, 0.5, 1e-9);
  EXPECT_NEAR(v.value, 19.0, 1e-9);
  EXPECT_EQ(v.limit, 2.0);
  // Just legal: 0.9 s at rest, 1.9 m/s for 1 s, 0.9 s at rest: 1.9 / 0.95 = 2 m/s^2
  // at both ends. 0.1 s less at rest is 1.9 / 0.9 = 2.11 m/s^2: over.
  const auto legal = check(f, ugv_plan({ugv_at(0, 1, 1, 0), ugv_at(0.9, 1, 1, 0),
                                        ugv_at(1.9, 2.9, 1, 0), ugv_at(2.8, 2.9, 1, 0)}));
  EXPECT_TRUE(legal.valid()) << legal.violations.front().describe();
  EXPECT_NEAR(legal.margins.peak_acceleration_mps2, 2.0, 1e-9);
  const auto over =
      check(f, ugv_plan({ugv_at(0, 1, 1, 0), ugv_at(0.8, 1, 1, 0), ugv_at(1.8, 2.9, 1, 0)}));
  ASSERT_EQ(kinds(over), std::vector{ViolationKind::kAcceleration});
  EXPECT_NEAR(over.violations[0].value, 1.9 / 0.9, 1e-9);
  // A 90 degree corner at 1 m/s without stopping: |(0,1) - (1,0)| / 1 s = 1.414 m/s^2.
  const auto corner =
      check(f, ugv_plan({ugv_at(0, 1, 1, 0), ugv_at(1, 2, 1, 0), ugv_at(2, 2, 2, 0)}));
  EXPECT_TRUE(corner.valid());
  EXPECT_NEAR(corner.margins.peak_acceleration_mps2, std::sqrt(2.0), 1e-9);
  // A repeated state (no time, no motion) is not a stop.
  EXPECT_TRUE(check(f, ugv_plan({ugv_at(0, 1, 1, 0), ugv_at(1, 2, 1, 0), ugv_at(1, 2, 1, 0),
                                 ugv_at(2, 3, 1, 0)}))
                  .valid());
  // Across a jump back in time there is no acceleration to speak of (at rest, then
  // 1.9 m/s for 0.5 s after it would be 2.53 m/s^2): time order only.
  EXPECT_EQ(kinds(check(f, ugv_plan({ugv_at(0, 2, 1, 0), ugv_at(1, 2, 1, 0), ugv_at(0.5, 2, 1, 0),
                                     ugv_at(1.0, 2.95, 1, 0)}))),
            std::vector{ViolationKind::kTimeOrder});
}

TEST(PlanValidation, EveryViolationWithItsSegment) {
  Fixture f;
  const std::vector<Waypoint> s{
      ugv_at(0, 1, 1, 0),        ugv_at(2, 2, 4, 0),
      ugv_at(10, 10, 4, 0),       // 1-2: through the block
      ugv_at(10.5, 11, 4, 0),     //
      ugv_at(10.6, 11.5, 4, 0),   // 3-4: 5 m/s; at 3: 1 -> 5 m/s over 0.3 s
      ugv_at(20.6, 11.5, -1, 0),  // 5: outside the geofence
  };
  const auto r = check(f, ugv_plan(s, 100.0));
  ASSERT_EQ(kinds(r), (std::vector{ViolationKind::kCollision, ViolationKind::kAcceleration,
                                   ViolationKind::kSpeed, ViolationKind::kGeofence}));
  EXPECT_EQ(r.violations[0].from_index, 1u);
  EXPECT_EQ(r.violations[0].to_index, 2u);
  EXPECT_NEAR(r.violations[0].p_W.x(), 3.0 - 0.065, 0.021);
  EXPECT_EQ(r.violations[1].from_index, 2u);
  EXPECT_EQ(r.violations[1].to_index, 4u);
  EXPECT_NEAR(r.violations[1].value, (5.0 - 2.0) / 0.3, 1e-6);
  EXPECT_EQ(r.violations[2].from_index, 3u);
  EXPECT_EQ(r.violations[2].to_index, 4u);
  EXPECT_NEAR(r.violations[2].value, 5.0, 1e-9);
  EXPECT_EQ(r.violations[3].from_index, 5u);
  EXPECT_EQ(r.violations[3].to_index, 5u);
}

TEST(PlanValidation, PartIsTheUrdfLink) {
  Fixture f;
  const RobotDescription ugv = load_robot_description(find_model("miniugv.urdf"));
  const RobotShape urdf_shape = robot_shape_from_description(ugv);
  CollisionChecker checker(f.map, plan_robot_shape(PlanRobot::kUgv, 0.0, &urdf_shape));
  const auto r = validate_plan(ugv_plan({ugv_at(0, 2, 4, 0), ugv_at(8, 10, 4, 0)}), checker,
                               f.corners, options(f));
  ASSERT_EQ(r.violations.size(), 1u);
  // The chassis reaches furthest forward (6.5 cm): it meets the block first.
  EXPECT_EQ(r.violations[0].part, "chassis_link");
  const auto& parts = r.inputs.parts;
  EXPECT_NE(std::find(parts.begin(), parts.end(), "front_left_wheel_link"), parts.end());
}

TEST(PlanValidation, YawMustBeRadians) {
  PlanFile p = ugv_plan({ugv_at(0, 1, 1, 3.1416), ugv_at(1, 2, 1, -3.1416)});
  EXPECT_NO_THROW(check_yaw_is_radians(p, "plan.csv"));  // pi, rounded
  p.states.push_back(ugv_at(2, 3, 1, 90.0));
  try {
    check_yaw_is_radians(p, "plan.csv");
    FAIL() << "degrees accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "plan.csv");
    EXPECT_NE(e.field().find("states[2]"), std::string::npos) << e.field();
    EXPECT_NE(e.expected().find("degrees"), std::string::npos) << e.expected();
  }
  p.states.back().yaw_rad = 3.2;
  EXPECT_THROW(check_yaw_is_radians(p, "plan.csv"), InputError);
}

// A 6 x 4 m space at 0.05 m on a 10 cm floor slab (top at z = 0), known free up to
// 0.1 m, with a 0.4 x 0.4 m pillar at [2.8, 3.2] x [1.8, 2.2]; the tether enters at (0, 2).
struct PillarSpace {
  test::TempDir dir;
  std::filesystem::path bt = dir / "pillar.bt", plan = dir / "plan.json";
  PillarSpace() {
    octomap::OcTree tree(0.05);
    test::fill_box(tree, {0, 0, -0.1}, {6, 4, 0}, true);
    test::fill_box(tree, {0, 0, 0}, {6, 4, 0.1}, false);
    test::fill_box(tree, {2.8, 1.8, 0}, {3.2, 2.2, 0.1}, true);
    tree.updateInnerOccupancy();
    tree.writeBinary(bt.string());
  }
};

// North of the pillar to the east, south, then west under it: the tether wraps the
// pillar's two northern corners and its south-east one, 2.81 + 0.4 + 0.4 + 2.34 = 5.95 m
// at the end; lying straight it would never be longer than 5.10 m.
std::string pillar_plan(double budget_m) {
  return R"({"format": "ferret-plan", "version": 1, "robot": "ugv", "tether": {"entry": [0, 2], "total_length_m": )" +
         std::to_string(budget_m + 1.0) + R"(, "entry_offset_m": 1.0}, "states": [
      {"t_s": 0, "x_m": 1, "y_m": 2.6, "z_m": 0, "yaw_rad": 0},
      {"t_s": 4, "x_m": 5, "y_m": 2.6, "z_m": 0, "yaw_rad": 0},
      {"t_s": 6, "x_m": 5, "y_m": 1.0, "z_m": 0, "yaw_rad": 0},
      {"t_s": 10, "x_m": 1, "y_m": 1.0, "z_m": 0, "yaw_rad": 0}]})";
}

TEST(PlanValidation, TetherFloorFromTheMapNotTheBounds) {
  PillarSpace world;
  const double pillar_wrapped = std::hypot(2.8, 0.2) + 0.4 + 0.4 + std::hypot(2.2, 0.8);
  for (const double z0 : {-0.2, -0.1, -0.05, 0.0}) {
    SCOPED_TRACE("bounds z0 = " + std::to_string(z0));
    ValidateRequest request;
    request.bounds = Aabb3{{0, 0, z0}, {6, 4, 0.12}};
    std::ofstream(world.plan) << pillar_plan(5.5);
    const auto r = validate_plan_file(world.plan, world.bt, request);
    ASSERT_TRUE(r.inputs.floor_z_m);
    EXPECT_NEAR(*r.inputs.floor_z_m, 0.0, 1e-9);
    EXPECT_EQ(r.inputs.floor_source, "map");
    ASSERT_EQ(kinds(r), std::vector{ViolationKind::kTetherLength});
    EXPECT_EQ(r.violations[0].from_index, 3u);
    EXPECT_NEAR(r.violations[0].value, pillar_wrapped, 0.1);
    // With enough tether the same plan is valid.
    std::ofstream(world.plan) << pillar_plan(6.5);
    const auto fits = validate_plan_file(world.plan, world.bt, request);
    EXPECT_TRUE(fits.valid()) << fits.violations.front().describe();
  }
}

TEST(PlanValidation, BadRequestsAreBadInput) {
  PillarSpace world;
  std::ofstream(world.plan) << pillar_plan(5.5);
  ValidateRequest request;
  request.bounds = Aabb3{{0, 0, 0}, {6, 4, 0.12}};
  EXPECT_FALSE(validate_plan_file(world.plan, world.bt, request).valid());
  request.bounds->hi.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)validate_plan_file(world.plan, world.bt, request), InputError);
  request.bounds = Aabb3{{0, 0, 0.2}, {6, 4, 0.12}};  // z0 > z1
  EXPECT_THROW((void)validate_plan_file(world.plan, world.bt, request), InputError);
  request.bounds.reset();  // a miniUGV in an OctoMap: the box is required
  EXPECT_THROW((void)validate_plan_file(world.plan, world.bt, request), InputError);
  request.bounds = Aabb3{{0, 0, 0}, {6, 4, 0.12}};
  request.tether_budget_m = 0.0;
  EXPECT_THROW((void)validate_plan_file(world.plan, world.bt, request), InputError);
  request.tether_budget_m = 6.0;  // overrides the plan's 5.5
  EXPECT_TRUE(validate_plan_file(world.plan, world.bt, request).valid());
  request.floor_z_m = -0.2;  // an explicit floor wins over the map's (and here sees no pillar)
  const auto r = validate_plan_file(world.plan, world.bt, request);
  EXPECT_EQ(r.inputs.floor_source, "--floor-z");
  EXPECT_EQ(*r.inputs.floor_z_m, -0.2);
}

TEST(PlanValidation, FloorFromMap) {
  PillarSpace world;
  octomap::OcTree tree(world.bt.string());
  // Wherever the box starts: below the slab, inside it, at its top, above it.
  for (const double z0 : {-0.5, -0.05, 0.0, 0.05})
    EXPECT_NEAR(*floor_z_from_map(tree, Aabb3{{0, 0, z0}, {6, 4, 0.12}}), 0.0, 1e-9) << z0;
  EXPECT_FALSE(floor_z_from_map(tree, Aabb3{{20, 20, 0}, {21, 21, 1}}));  // nothing there
}

}  // namespace
}  // namespace ferret
