#include "ferret/sim/sim_ugv_base.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "support/test_maps.hpp"

namespace ferret {
namespace {

OccupancyMap2D room() { return test::room_with_partition(); }

void drive(SimUgvBase& base, double v_mps, int steps) {
  for (int k = 0; k < steps; ++k) {
    base.command_velocity(v_mps, 0.0);
    base.step(0.05);
  }
}

TEST(SimUgvBase, AWallStopsTheBodyAtItsFaceAndEachStretchAgainstItIsOneContact) {
  const OccupancyMap2D map = room();
  HiddenSpaceSim sim(map, {3.5, 2.5}, SensorOptions{}, 3);
  SimUgvOptions o;
  o.body_radius_m = 0.06;
  SimUgvBase base(sim, {1.0, 1.0, 0.0}, o);
  // 0.5 m/s, steps of 2.5 cm towards the face at x = 2.5. A contact counts from
  // 0.06 - 0.025 = 0.035 m: the step from x = 2.45 to 2.475 would press 0.01 m in, and
  // is not taken.
  drive(base, 0.5, 59);
  EXPECT_NEAR(base.true_pose().x_m, 2.45, 1e-9);
  EXPECT_EQ(base.body_contacts(), 1);
  EXPECT_EQ(base.deepest_contact_m(), 0.0);
  // Pushing on is the same contact and goes nowhere; turning on the spot still turns.
  drive(base, 0.5, 10);
  EXPECT_NEAR(base.true_pose().x_m, 2.45, 1e-9);
  EXPECT_EQ(base.body_contacts(), 1);
  base.command_velocity(0.0, 1.0);
  base.step(0.05);
  EXPECT_NEAR(base.true_pose().yaw_rad, 0.05, 1e-9);
  base.command_velocity(0.0, -1.0);
  base.step(0.05);
  // Back off, and press again: a second contact.
  drive(base, -0.5, 10);
  EXPECT_NEAR(base.true_pose().x_m, 2.2, 1e-9);
  drive(base, 0.5, 12);
  EXPECT_NEAR(base.true_pose().x_m, 2.45, 1e-9);
  EXPECT_EQ(base.body_contacts(), 2);
}

TEST(SimUgvBase, ABodyWithinTheRastersHalfCellOfAWallIsNoContact) {
  // Along the wall 5 cm from its face: the disc of 6 cm reaches 1 cm over the blocked
  // cells' edge, which the truth's raster cannot tell from the face itself.
  const OccupancyMap2D map = room();
  HiddenSpaceSim sim(map, {3.5, 2.5}, SensorOptions{}, 3);
  SimUgvOptions o;
  o.body_radius_m = 0.06;
  SimUgvBase base(sim, {2.45, 0.3, std::numbers::pi / 2}, o);
  drive(base, 0.5, 40);
  EXPECT_GT(base.true_pose().y_m, 1.2);
  EXPECT_EQ(base.body_contacts(), 0);
  EXPECT_EQ(base.deepest_contact_m(), 0.0);
  // Without a body radius (the default) nothing is counted or stopped, even through
  // the wall.
  SimUgvBase ghost(sim, {2.0, 1.0, 0.0}, SimUgvOptions{});
  drive(ghost, 0.5, 60);
  EXPECT_GT(ghost.true_pose().x_m, 2.9);
  EXPECT_EQ(ghost.body_contacts(), 0);
}

}  // namespace
}  // namespace ferret
