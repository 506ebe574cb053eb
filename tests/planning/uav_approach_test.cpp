#include "ferret/planning/uav_approach.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "ferret/core/error.hpp"
#include "plan_check.hpp"
#include "waypoints.hpp"

namespace ferret {
namespace {

using test::uav_at;

const std::string kDefaultWorld = std::string(FERRET_SOURCE_DIR) + "/examples/worlds/default.yaml";
const std::string kRover = std::string(FERRET_SOURCE_DIR) + "/tests/data/robots/rover.urdf";

const PlanningWorld& default_world() {
  static const PlanningWorld world = load_planning_world(kDefaultWorld);
  return world;
}

// A 20 x 20 m yard (z from -0.2 to 5 m) with a 4 m wall across x = 0 open at y > 6.
std::filesystem::path write_yard() {
  const auto path = std::filesystem::temp_directory_path() /
                    ("uav_approach_yard_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(path)
      << "name: yard\nresolution_m: 0.1\nbounds_m: {min: [-10, -10, -0.2], max: [10, 10, 5]}\n"
         "ground: {height_m: 0.0}\nboxes:\n"
         "  - {name: wall, center_m: [0, -2], size_m: [0.4, 16, 4]}\n";
  return path;
}

TEST(UavApproach, PlansToTheHoverPoseOfAHiddenSpaceAndThePlanIsValid) {
  UavApproachRequest req;
  req.start = uav_at(-20, -20, 3, 0);
  req.hidden_space = "house_void";
  const PlanResult r = plan_uav_approach(default_world(), req);
  ASSERT_TRUE(r.solved) << r.status;
  // house_void's entry is at (-6.85, 7) in its +x wall, its floor at z = 0: the hover
  // pose is 1 m out along the normal, 1.5 m up, facing the opening (yaw pi).
  const Waypoint& goal = r.plan.states.back();
  EXPECT_NEAR(goal.x_m, -5.85, 1e-9);
  EXPECT_NEAR(goal.y_m, 7.0, 1e-9);
  EXPECT_NEAR(goal.z_m, 1.5, 1e-9);
  EXPECT_NEAR(std::abs(goal.yaw_rad), M_PI, 1e-9);
  // Every field `ferret plan` fills.
  EXPECT_EQ(r.plan.robot, PlanRobot::kUav);
  EXPECT_EQ(std::filesystem::path(r.plan.robot_model).filename(), "m100.urdf");
  EXPECT_EQ(r.plan.unknown_policy, UnknownPolicy::kFree);
  EXPECT_EQ(r.plan.max_velocity_mps, 5.0);  // the mission's uav_limits: the M100 has no wheels
  EXPECT_EQ(r.plan.max_yaw_rate_radps, 1.0);
  EXPECT_EQ(r.plan.planner, "rrtconnect");
  EXPECT_EQ(r.plan.seed, 1u);
  EXPECT_EQ(r.plan.world, kDefaultWorld);
  EXPECT_FALSE(test::check_plan(default_world(), r.plan).has_value());
}

TEST(UavApproach, TheGeofenceDefaultsToTheWorldsBounds) {
  const auto yard = write_yard();
  const PlanningWorld world = load_planning_world(yard);
  UavApproachRequest req;
  req.start = uav_at(-5, -5, 2, 0);
  req.goal = uav_at(5, -5, 2, 0);
  const PlanResult r = plan_uav_approach(world, req);
  ASSERT_TRUE(r.solved) << r.status;
  // bounds_m {[-10, -10, -0.2], [10, 10, 5]}: x, y as they are; z from 0.5 m above
  // max(-0.2, 0) to 0.5 m below the top.
  ASSERT_TRUE(r.plan.bounds.has_value());
  EXPECT_EQ(r.plan.bounds->lo, Eigen::Vector3d(-10, -10, 0.5));
  EXPECT_EQ(r.plan.bounds->hi, Eigen::Vector3d(10, 10, 4.5));
  EXPECT_GE(r.plan.states.size(), 3u);  // round the wall, through the gap at y > 6
  EXPECT_FALSE(test::check_plan(world, r.plan).has_value());

  // A fence that ends at y = 5 and below the wall's top (4 m) closes the way: no path,
  // and the plan says which fence.
  req.bounds = Aabb3{{-10, -10, 0.5}, {10, 5, 3.5}};
  req.time_limit_s = 0.3;
  const PlanResult closed = plan_uav_approach(world, req);
  EXPECT_FALSE(closed.solved);
  EXPECT_TRUE(closed.plan.states.empty());
  EXPECT_EQ(closed.plan.bounds->hi.y(), 5.0);
  std::filesystem::remove(yard);
}

TEST(UavApproach, WithTheMiniUgvHangingThePlanIsOfTheLoadedUav) {
  UavApproachRequest req;
  req.start = uav_at(-20, -20, 3, 0);
  req.hidden_space = "house_void";
  req.tether_released_m = 0.5;  // hovering 1.5 m up, the miniUGV hangs clear of the ground
  const PlanResult r = plan_uav_approach(default_world(), req);
  ASSERT_TRUE(r.solved) << r.status;
  EXPECT_EQ(r.plan.robot, PlanRobot::kUavWithUgv);
  EXPECT_EQ(r.plan.released_length_m, 0.5);
  EXPECT_FALSE(test::check_plan(default_world(), r.plan).has_value());
}

TEST(UavApproach, AHiddenSpaceTheWorldLacksIsAnInputErrorListingThoseItHas) {
  UavApproachRequest req;
  req.start = uav_at(-20, -20, 3, 0);
  req.hidden_space = "wine_cellar";
  try {
    (void)plan_uav_approach(default_world(), req);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "hidden_space");
    const std::string what = e.what();
    EXPECT_NE(what.find("wine_cellar"), std::string::npos) << what;
    EXPECT_NE(what.find("house_void, garage_void"), std::string::npos) << what;
  }
}

TEST(UavApproach, BadRequestsAreInputErrorsNamingTheField) {
  auto field_of = [](const UavApproachRequest& req) -> std::string {
    try {
      (void)plan_uav_approach(default_world(), req);
    } catch (const InputError& e) {
      return e.field();
    }
    return "(no error)";
  };
  UavApproachRequest ok;
  ok.start = uav_at(-20, -20, 3, 0);
  ok.hidden_space = "house_void";

  UavApproachRequest both = ok;
  both.goal = uav_at(0, 0, 2, 0);
  EXPECT_EQ(field_of(both), "goal");
  UavApproachRequest neither = ok;
  neither.hidden_space.clear();
  EXPECT_EQ(field_of(neither), "goal");
  UavApproachRequest nan_start = ok;
  nan_start.start.y_m = std::nan("");
  EXPECT_EQ(field_of(nan_start), "start");
  UavApproachRequest planner = ok;
  planner.planner = "rrt-connect";
  EXPECT_EQ(field_of(planner), "planner");
  UavApproachRequest time = ok;
  time.time_limit_s = 0.0;
  EXPECT_EQ(field_of(time), "time_limit_s");
  UavApproachRequest inf_time = ok;
  inf_time.time_limit_s = INFINITY;
  EXPECT_EQ(field_of(inf_time), "time_limit_s");
  UavApproachRequest tether = ok;
  tether.tether_released_m = 150.0;
  EXPECT_EQ(field_of(tether), "tether_released_m");
  UavApproachRequest flat = ok;
  flat.bounds = Aabb3{{-10, -10, 2}, {10, 10, 2}};
  EXPECT_EQ(field_of(flat), "bounds");
  UavApproachRequest far = ok;  // a geofence 4e9 m wide: beyond any map, and it hung
  far.bounds = Aabb3{{-30, -30, 1}, {30, 4e9, 5}};
  EXPECT_EQ(field_of(far), "bounds");
  UavApproachRequest ground_robot = ok;
  ground_robot.robot.urdf = kRover;
  EXPECT_EQ(field_of(ground_robot), "robot");  // a URDF of the other kind of robot

  try {
    (void)plan_uav_approach(default_world(), planner);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rrtconnect"), std::string::npos)
        << e.what();  // lists the choices
  }
}

}  // namespace
}  // namespace ferret
