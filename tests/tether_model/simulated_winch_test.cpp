#include "ferret/tether_model/simulated_winch.hpp"

#include <gtest/gtest.h>

namespace ferret::tether {
namespace {

void run(SimulatedWinch& w, double seconds, double tension_n) {
  for (int i = 0; i < static_cast<int>(seconds / 0.001 + 0.5); ++i) w.advance(0.001, tension_n);
}

TEST(SimulatedWinch, ProfileRampsAtTheAccelerationLimitAndTheSpoolFollows) {
  SimulatedWinch w(SimulatedWinch::Options{});  // 2 m/s^2, 0.6 m/s
  w.command_velocity_mps(0.3);
  run(w, 0.05, 0.0);
  EXPECT_NEAR(w.profile_target_mps(), 0.1, 1e-9);
  run(w, 0.95, 0.0);
  EXPECT_NEAR(w.speed_mps(), 0.3, 0.003);
  // Ramp 0.15 s (0.0225 m) plus lag behind it; roughly 0.3 m/s for the rest.
  EXPECT_GT(w.released_m(), 0.22);
  EXPECT_LT(w.released_m(), 0.28);
  w.command_velocity_mps(5.0);
  EXPECT_DOUBLE_EQ(w.read_state().speed_mps, w.speed_mps());
  run(w, 1.0, 0.0);
  EXPECT_NEAR(w.speed_mps(), 0.6, 0.005);  // clamped to the limit
}

TEST(SimulatedWinch, HoldsAgainstTensionWithTorqueAndPaysOutWithout) {
  SimulatedWinch::Options o;
  o.initial_released_m = 5.0;
  SimulatedWinch w(o);
  run(w, 2.0, 5.0);
  EXPECT_NEAR(w.speed_mps(), 0.0, 1e-3);
  // The velocity loop's I term takes the load after the line has given F / Ki = 5 / 640 m.
  EXPECT_NEAR(w.released_m() - 5.0, 5.0 / 640.0, 0.001);
  EXPECT_DOUBLE_EQ(w.read_state().tension_n, 5.0);
  w.set_torque_enabled(false);
  run(w, 0.5, 5.0);
  EXPECT_GT(w.speed_mps(), 1.0);  // (5 - friction) / 0.4 kg accelerates the limp spool
}

TEST(SimulatedWinch, FrictionHoldsASmallPullAndTheLineEndsAtL) {
  SimulatedWinch::Options o;
  o.initial_released_m = 14.9;
  SimulatedWinch w(o);
  w.set_torque_enabled(false);
  run(w, 0.5, 0.2);  // below the 0.3 N Coulomb friction
  EXPECT_DOUBLE_EQ(w.released_m(), 14.9);
  w.set_torque_enabled(true);
  w.command_velocity_mps(0.6);
  run(w, 2.0, 0.0);
  EXPECT_DOUBLE_EQ(w.released_m(), 15.0);
  EXPECT_THROW(SimulatedWinch(SimulatedWinch::Options{.initial_released_m = 16.0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace ferret::tether
