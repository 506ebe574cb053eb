// A ground robot's URDF shapes are placed on the floor whatever its base frame: the
// rover's base frame is at its body centre, 0.07 m above the ground, the miniUGV's on
// the ground; the UAV keeps its own frame.

#include "ferret/planning/robot_shape.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>

#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

const ShapePart& part(const RobotShape& s, const std::string& name) {
  const auto it = std::find_if(s.parts.begin(), s.parts.end(),
                               [&](const ShapePart& p) { return p.name == name; });
  EXPECT_NE(it, s.parts.end()) << name;
  return *it;
}

TEST(RobotShape, AGroundRobotsShapesRestOnTheFloor) {
  const auto rover =
      load_robot_description(std::string(FERRET_SOURCE_DIR) + "/tests/data/robots/rover.urdf");
  const RobotShape s = robot_shape_from_description(rover);
  // Body centre 0.07 m up; wheel centres 0.03 m below it, radius 0.04: bottoms at 0.
  EXPECT_NEAR(part(s, "body").X_BS.translation().z(), 0.07, 1e-12);
  EXPECT_NEAR(part(s, "wheel_fl").X_BS.translation().z(), 0.04, 1e-12);
  const UgvGeometry g = ugv_geometry_from_description(rover);
  EXPECT_NEAR(g.body_size_m.x(), 0.30, 1e-12);
  EXPECT_NEAR(g.body_size_m.y(), 0.26, 1e-12);
  EXPECT_NEAR(g.body_size_m.z(), 0.12, 1e-12);  // wheel bottoms to the body's top

  // The miniUGV's base frame is already on the floor: nothing moves.
  const auto ugv = load_robot_description(find_model("miniugv.urdf"));
  EXPECT_NEAR(part(robot_shape_from_description(ugv), "chassis_link").X_BS.translation().z(), 0.035,
              1e-12);
  // A UAV's shapes stay in its base frame.
  const auto uav = load_robot_description(find_model("m100.urdf"));
  ASSERT_GT(uav.ground_offset_m, 0.0);
  const RobotShape u = robot_shape_from_description(uav);
  for (std::size_t k = 0; k < u.parts.size(); ++k)
    EXPECT_TRUE(u.parts[k].X_BS.isApprox(uav.collision_shapes[k].X_BS)) << k;
}

}  // namespace
}  // namespace ferret
