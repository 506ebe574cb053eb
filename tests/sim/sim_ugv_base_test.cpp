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

TEST(SimUgvBase, ABodyPressedIntoAWallIsOneContactAndItsDepthIsBeyondTheRastersHalfCell) {
  const OccupancyMap2D map = room();
  HiddenSpaceSim sim(map, {3.5, 2.5}, SensorOptions{}, 3);
  SimUgvOptions o;
  o.body_radius_m = 0.06;
  SimUgvBase base(sim, {1.0, 1.0, 0.0}, o);
  // 0.5 m/s for 59 steps of 0.05 s: the centre at x = 2.475, 2.5 cm from the face. A
  // contact counts from 0.06 - 0.025 = 0.035 m: at most 0.01 m into the body.
  drive(base, 0.5, 59);
  EXPECT_NEAR(base.true_pose().x_m, 2.475, 1e-9);
  EXPECT_EQ(base.body_contacts(), 1);
  EXPECT_NEAR(base.deepest_contact_m(), 0.01, 1e-9);
  // Counted, not stopped: the base does not model the push. Back off and press again:
  // a second contact, no deeper.
  drive(base, -0.5, 10);
  EXPECT_EQ(base.body_contacts(), 1);
  drive(base, 0.5, 10);
  EXPECT_EQ(base.body_contacts(), 2);
  EXPECT_NEAR(base.deepest_contact_m(), 0.01, 1e-9);
}

TEST(SimUgvBase, ABodyWithinTheRastersHalfCellOfAWallIsNoContact) {
  // Along the wall 5 cm from its face: the disc of 6 cm reaches 1 cm over the blocked
  // cells' edge, which the truth's raster cannot tell from the face itself.
  const OccupancyMap2D map = room();
  HiddenSpaceSim sim(map, {3.5, 2.5}, SensorOptions{}, 3);
  SimUgvBase base(sim, {2.45, 0.3, std::numbers::pi / 2}, SimUgvOptions{});
  drive(base, 0.5, 40);
  EXPECT_GT(base.true_pose().y_m, 1.2);
  EXPECT_EQ(base.body_contacts(), 0);
  EXPECT_EQ(base.deepest_contact_m(), 0.0);
  // Without a body radius nothing is counted, even through the wall.
  SimUgvOptions none;
  none.body_radius_m = 0.0;
  SimUgvBase ghost(sim, {2.0, 1.0, 0.0}, none);
  drive(ghost, 0.5, 60);
  EXPECT_EQ(ghost.body_contacts(), 0);
}

}  // namespace
}  // namespace ferret
