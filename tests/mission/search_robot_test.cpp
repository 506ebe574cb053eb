// The object search takes its sensors and speed from a robot description: the rover's
// 2.5 m IR, 50 deg array, 68.75 deg / 320 px / 3 m camera and 0.5 m/s wheels, which
// differ from the miniUGV's 4 m / 30 deg / 90 deg / 640 px / 2 m/s in every value.

#include "ferret/mission/search_robot.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ferret/core/error.hpp"
#include "support/test_maps.hpp"

namespace ferret {
namespace {

constexpr double kPi = std::numbers::pi;

RobotDescription rover() {
  return load_robot_description(std::string(FERRET_SOURCE_DIR) + "/tests/data/robots/rover.urdf");
}

TEST(SearchRobot, SensorOptionsAreTheRoversRoles) {
  const SensorOptions s = sensor_options_for(rover());
  EXPECT_DOUBLE_EQ(s.camera_fov_rad, 1.2);
  EXPECT_DOUBLE_EQ(s.camera_range_m, 3.0);
  EXPECT_EQ(s.image_width_px, 320);
  EXPECT_NEAR(s.ir_fov_rad, 50 * kPi / 180, 1e-9);
  EXPECT_DOUBLE_EQ(s.ir_range_m, 2.5);
  // Two fans of 5 beams 5 deg apart, centred at -15 and +15 deg: -25..-5 and 5..25.
  ASSERT_EQ(s.ir_bearings_rad.size(), 10u);
  EXPECT_NEAR(s.ir_bearings_rad.front(), -25 * kPi / 180, 1e-9);
  EXPECT_NEAR(s.ir_bearings_rad[4], -5 * kPi / 180, 1e-9);
  EXPECT_NEAR(s.ir_bearings_rad[5], 5 * kPi / 180, 1e-9);
  EXPECT_NEAR(s.ir_bearings_rad.back(), 25 * kPi / 180, 1e-9);
  // A URDF does not say the noise: the base's stays.
  SensorOptions base;
  base.ir_noise_m = 0.123;
  EXPECT_DOUBLE_EQ(sensor_options_for(rover(), base).ir_noise_m, 0.123);
}

TEST(SearchRobot, RobotOptionsAreTheWheelLimitAndTheMission) {
  const RobotOptions r = robot_options_for(rover());
  EXPECT_DOUBLE_EQ(r.max_velocity_mps, 0.5);
  EXPECT_DOUBLE_EQ(r.max_yaw_rate_radps, 2.0);  // mission default
  // The rover reaches 0.2 m from its base (body corner at (0.15, 0.1), wheels to 0.13 in y
  // at x = 0.14): the clearance is at least that.
  EXPECT_GE(r.clearance_m, std::hypot(0.14, 0.13) - 1e-9);
}

TEST(SearchRobot, AMissingRoleIsAnInputErrorNamingIt) {
  const auto r = robot_description_from_string(
      R"(<robot name="bare"><link name="b"><collision><geometry><box size="1 1 1"/></geometry></collision></link></robot>)",
      "bare.urdf");
  try {
    (void)sensor_options_for(r);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "bare.urdf");
    EXPECT_EQ(e.field(), "role[object_camera]");
  }
}

/// The largest distance from an observed (non-unknown) cell of G to the driven path.
double farthest_observed_m(const EpisodeResult& r) {
  const GridGeometry& g = r.grid->geometry();
  double farthest = 0.0;
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) {
      if (r.grid->label({i, j}) == GridLabel::kUnknown) continue;
      const Eigen::Vector2d c = g.center({i, j});
      double nearest = 1e9;
      for (const Pose2& p : r.trajectory) nearest = std::min(nearest, (c - p.position()).norm());
      farthest = std::max(farthest, nearest);
    }
  return farthest;
}

TEST(SearchRobot, TheRoversIrSeesNoFartherThanItsRange) {
  const auto map = test::small_hidden_space();
  const Pose2 start{0.5, 1.0, 0.0};
  const Eigen::Vector2d object{3.2, 0.8};
  const EpisodeResult r = run_search(map, start, object, "nearest", rover(), 3, {}, true);
  ASSERT_TRUE(r.grid);
  ASSERT_FALSE(r.trajectory.empty());
  // A cell marked by a beam lies within D_IR of a pose; its centre is at most half a
  // cell diagonal farther.
  const double slack = 0.05 * std::sqrt(2.0);
  EXPECT_LE(farthest_observed_m(r), 2.5 + slack);
  // The same search with the miniUGV's 4 m IR marks cells beyond 2.5 m: the bound
  // above is the rover's range, not the room's size.
  const auto miniugv =
      load_robot_description(std::string(FERRET_SOURCE_DIR) + "/urdf/models/miniugv.urdf");
  const EpisodeResult m = run_search(map, start, object, "nearest", miniugv, 3, {}, true);
  EXPECT_GT(farthest_observed_m(m), 2.5 + slack);
}

TEST(SearchRobot, TheRoverNeverDrivesFasterThanItsWheelsAllow) {
  const auto map = test::small_hidden_space();
  const EpisodeResult r =
      run_search(map, {0.5, 1.0, 0.0}, {3.2, 0.8}, "cdos", rover(), 5, {}, true);
  ASSERT_GT(r.trajectory.size(), 10u);
  const double dt = 1.0 / SensorOptions{}.ir_rate_hz;
  double fastest = 0.0;
  for (std::size_t k = 1; k < r.trajectory.size(); ++k)
    fastest = std::max(fastest,
                       (r.trajectory[k].position() - r.trajectory[k - 1].position()).norm() / dt);
  EXPECT_LE(fastest, 0.5 + 1e-9);
  EXPECT_GT(fastest, 0.25);  // it did drive
}

}  // namespace
}  // namespace ferret
