#include "ferret/tether_model/tether_modes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ferret::tether {
namespace {

TetherModeSwitcher::Options paper_options() {
  TetherModeSwitcher::Options o;  // L = 15, l_0 = Z_W = 1, hysteresis 0.02, tolerance 0.005
  return o;
}

TEST(TetherModeSwitcher, ModesFromReleasedLengthWithHysteresis) {
  TetherModeSwitcher s(paper_options());
  EXPECT_EQ(s.update(0.0, 0.0), TetherMode::kAerial);
  EXPECT_EQ(s.update(0.1, 0.02), TetherMode::kAerial);  // inside the band above 0.005
  EXPECT_EQ(s.update(0.2, 0.03), TetherMode::kLowering);
  EXPECT_EQ(s.update(0.3, 0.01), TetherMode::kLowering);  // not back to aerial until <= 0.005
  EXPECT_EQ(s.update(0.4, 0.004), TetherMode::kAerial);
  EXPECT_EQ(s.update(0.5, 0.5), TetherMode::kLowering);
  EXPECT_EQ(s.update(0.6, 1.0), TetherMode::kLowering);  // l_0 reached, but not l_0 + hysteresis
  EXPECT_EQ(s.update(0.7, 1.02), TetherMode::kHiddenSpace);
  EXPECT_EQ(s.update(0.8, 0.99), TetherMode::kHiddenSpace);  // within l_0 - hysteresis
  EXPECT_EQ(s.update(0.9, 0.97), TetherMode::kLowering);
  ASSERT_EQ(s.transitions().size(), 5u);
  EXPECT_EQ(s.transitions()[3].from, TetherMode::kLowering);
  EXPECT_EQ(s.transitions()[3].to, TetherMode::kHiddenSpace);
  EXPECT_DOUBLE_EQ(s.transitions()[3].t_s, 0.7);
  EXPECT_DOUBLE_EQ(s.transitions()[3].released_m, 1.02);
}

TEST(TetherModeSwitcher, BoundariesFromTheMissionsTether) {
  TetherParams tether;
  tether.total_length_m = 8.0;
  tether.entry_offset_m = 2.5;
  TetherModeSwitcher s(TetherModeSwitcher::Options::from_mission(tether, 2.4));
  EXPECT_DOUBLE_EQ(s.options().total_length_m, 8.0);
  EXPECT_EQ(s.update(0.0, 2.4), TetherMode::kLowering);  // Z_W < l_t < l_0: still lowering
  EXPECT_EQ(s.update(0.1, 2.52), TetherMode::kHiddenSpace);
}

TEST(TetherModeSwitcher, EncoderJitterAtABoundaryDoesNotToggle) {
  TetherModeSwitcher s(paper_options(), TetherMode::kHiddenSpace);
  for (int k = 0; k < 100; ++k) (void)s.update(k * 0.02, 1.0 + 0.015 * std::sin(k));
  EXPECT_EQ(s.mode(), TetherMode::kHiddenSpace);
  EXPECT_TRUE(s.transitions().empty());
}

TEST(TetherModeSwitcher, JumpsStraightToTheRightModeAndRejectsBadOptions) {
  TetherModeSwitcher s(paper_options());
  EXPECT_EQ(s.update(0.0, 5.0), TetherMode::kHiddenSpace);
  EXPECT_EQ(s.update(1.0, 0.0), TetherMode::kAerial);
  auto o = paper_options();
  o.entry_offset_m = 20.0;  // l_0 > L
  EXPECT_THROW(TetherModeSwitcher{o}, std::invalid_argument);
  o = paper_options();
  o.hysteresis_m = 0.5;  // bands overlap
  EXPECT_THROW(TetherModeSwitcher{o}, std::invalid_argument);
  EXPECT_EQ(to_string(TetherMode::kHiddenSpace), "hidden-space");
}

TEST(TouchdownGuard, TiltOfRollAndPitch) {
  EXPECT_NEAR(TouchdownGuard::tilt_rad(0.3, 0.0), 0.3, 1e-12);
  EXPECT_NEAR(TouchdownGuard::tilt_rad(0.3, 0.4), std::acos(std::cos(0.3) * std::cos(0.4)), 1e-12);
}

TEST(TouchdownGuard, PausesOnAPoorAngleAndReliftsOnABadOne) {
  TouchdownGuard::Options o;  // pause 0.35 rad, relift 0.61 rad, 10 cm, settle 0.5 s, 0.2 m/s
  TouchdownGuard g(o);
  EXPECT_EQ(g.update(0.0, 0.05, 0.0, 0.50), LoweringAction::kLower);
  EXPECT_DOUBLE_EQ(g.spool_velocity_mps(), 0.2);
  EXPECT_EQ(g.update(0.1, 0.45, 0.0, 0.52), LoweringAction::kPause);
  EXPECT_DOUBLE_EQ(g.spool_velocity_mps(), 0.0);
  EXPECT_EQ(g.update(0.2, 0.0, 0.7, 0.52), LoweringAction::kRelift);
  EXPECT_DOUBLE_EQ(g.spool_velocity_mps(), -0.2);
  // The re-lift runs to 0.42 m even when the miniUGV hangs level again.
  EXPECT_EQ(g.update(0.3, 0.0, 0.0, 0.47), LoweringAction::kRelift);
  EXPECT_EQ(g.update(0.4, 0.0, 0.0, 0.42), LoweringAction::kPause);
  // Then it waits for a calm attitude over the settle time before lowering again.
  EXPECT_EQ(g.update(0.8, 0.0, 0.0, 0.42), LoweringAction::kPause);
  EXPECT_EQ(g.update(0.95, 0.0, 0.0, 0.42), LoweringAction::kLower);
  EXPECT_THROW(TouchdownGuard(TouchdownGuard::Options{0.5, 0.4}), std::invalid_argument);
}

TEST(TouchdownGuard, LiftsOncePerBadSpellThenHolds) {
  TouchdownGuard g(TouchdownGuard::Options{});
  EXPECT_EQ(g.update(0.0, 0.7, 0.0, 0.60), LoweringAction::kRelift);
  EXPECT_EQ(g.update(0.1, 0.7, 0.0, 0.55), LoweringAction::kRelift);
  EXPECT_EQ(g.update(0.2, 0.7, 0.0, 0.50),
            LoweringAction::kPause);  // lifted 10 cm, still bad: hold
  EXPECT_EQ(g.update(0.3, 0.7, 0.0, 0.50), LoweringAction::kPause);
  EXPECT_EQ(g.update(0.4, 0.5, 0.0, 0.50), LoweringAction::kPause);   // better, not good
  EXPECT_EQ(g.update(0.5, 0.7, 0.0, 0.50), LoweringAction::kRelift);  // a new bad spell
}

}  // namespace
}  // namespace ferret::tether
