#include "ferret/tether_model/required_length.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace ferret::tether {
namespace {

// The block x in [1, 3.5], y in [0.5, 2] beside the entry (examples/trajectories/default.yaml).
FixedWrapTether block_tether() {
  return FixedWrapTether(1.0, Eigen::Vector2d::Zero(), {{{3.5, 0.5}, +1}, {{3.5, 2.0}, +1}});
}

TEST(FixedWrapTether, StraightWithoutWrapPoints) {
  const FixedWrapTether t(1.5, Eigen::Vector2d(1.0, 1.0));
  EXPECT_DOUBLE_EQ(t.required_length_m({4.0, 5.0}), 1.5 + 5.0);
}

TEST(FixedWrapTether, WrapsOnlyRoundCornersTheTetherTurnsAt) {
  const auto t = block_tether();
  const double to_first = 1.0 + std::hypot(3.5, 0.5);
  EXPECT_EQ(t.engaged_count({4.2, 0.0}), 0u);
  EXPECT_DOUBLE_EQ(t.required_length_m({4.2, 0.0}), 1.0 + 4.2);
  EXPECT_EQ(t.engaged_count({4.2, 3.0}), 1u);
  EXPECT_DOUBLE_EQ(t.required_length_m({4.2, 3.0}), to_first + std::hypot(0.7, 2.5));
  EXPECT_EQ(t.engaged_count({1.5, 3.0}), 2u);
  EXPECT_DOUBLE_EQ(t.required_length_m({1.5, 3.0}), to_first + 1.5 + std::hypot(2.0, 1.0));
  EXPECT_DOUBLE_EQ(t.length_to_wrap_point_m(1), to_first + 1.5);
  EXPECT_THROW((void)t.length_to_wrap_point_m(2), std::out_of_range);
}

TEST(FixedWrapTether, LengthIsContinuousWhenACornerEngages) {
  const auto t = block_tether();
  // Up past the block and behind it: each corner engages when the tether is straight through it.
  double previous = t.required_length_m({4.2, 0.0});
  for (int i = 1; i <= 600; ++i) {
    const Eigen::Vector2d p =
        i <= 300 ? Eigen::Vector2d(4.2, 0.01 * i) : Eigen::Vector2d(4.2 - 0.009 * (i - 300), 3.0);
    const double l = t.required_length_m(p);
    EXPECT_LT(std::abs(l - previous), 0.0101) << "step " << i;
    previous = l;
  }
}

TEST(UgvMotion, ExtrapolationCapsSpeedAndAccelerationTime) {
  UgvMotion m;
  m.v_WG = {1.9, 0.0};
  m.a_WG = {1.0, 0.0};
  // Accelerates for 0.1 s to the 2 m/s cap, then coasts: 0.195 + 1.8.
  const UgvMotion f = m.extrapolated(1.0, 2.0);
  EXPECT_NEAR(f.p_WG.x(), 1.9 * 0.1 + 0.5 * 0.01 + 2.0 * 0.9, 1e-12);
  EXPECT_NEAR(f.v_WG.x(), 2.0, 1e-12);
  EXPECT_EQ(f.a_WG.norm(), 0.0);
  // With the acceleration limited to 0.05 s.
  const UgvMotion g = m.extrapolated(1.0, 5.0, 0.05);
  EXPECT_NEAR(g.p_WG.x(), 1.9 * 0.05 + 0.5 * 0.0025 + 1.95 * 0.95, 1e-12);
  // Decelerating is never capped.
  m.a_WG = {-1.0, 0.0};
  EXPECT_NEAR(m.extrapolated(0.5, 2.0).p_WG.x(), 1.9 * 0.5 - 0.125, 1e-12);
}

TEST(RequiredLengthRate, RadialAndTangentialMotion) {
  const FixedWrapTether t(1.0, Eigen::Vector2d::Zero());
  UgvMotion m;
  m.p_WG = {3.0, 0.0};
  m.v_WG = {0.5, 0.0};
  EXPECT_NEAR(required_length_rate_mps(t, m), 0.5, 1e-9);
  m.v_WG = {0.0, 0.5};
  EXPECT_NEAR(required_length_rate_mps(t, m), 0.0, 1e-6);
}

// A preview of the cubic p(t) = (t^3 - t, 2 t): the Hermite interpolation through
// knots with exact positions and velocities reproduces it exactly.
TEST(UgvMotionPreview, HermiteKnotsReproduceACubicAndContinuePastTheEnd) {
  auto p = [](double t) { return Eigen::Vector2d(t * t * t - t, 2.0 * t); };
  auto v = [](double t) { return Eigen::Vector2d(3.0 * t * t - 1.0, 2.0); };
  UgvMotionPreview preview;
  EXPECT_TRUE(preview.empty());
  EXPECT_EQ(preview.at(0.3), Eigen::Vector2d::Zero());
  preview.step_s = 0.1;
  for (int i = 0; i <= 4; ++i) {
    preview.displacement_m.push_back(p(0.1 * i));
    preview.velocity_mps.push_back(v(0.1 * i));
  }
  ASSERT_FALSE(preview.empty());
  for (double t : {0.0, 0.03, 0.1, 0.17, 0.25, 0.399}) {
    EXPECT_NEAR((preview.at(t) - p(t)).norm(), 0.0, 1e-12) << t;
    EXPECT_NEAR((preview.velocity_at(t) - v(t)).norm(), 0.0, 1e-12) << t;
  }
  // Past the last knot (0.4 s) the plan goes on at its last velocity.
  EXPECT_NEAR((preview.at(0.6) - (p(0.4) + 0.2 * v(0.4))).norm(), 0.0, 1e-12);
  EXPECT_NEAR((preview.velocity_at(0.6) - v(0.4)).norm(), 0.0, 1e-12);
  // Knots and velocities of different counts are no preview.
  preview.velocity_mps.pop_back();
  EXPECT_TRUE(preview.empty());
}

TEST(UgvMotionPreview, PlannedMotionAddsTheDisplacementToTheFilteredPosition) {
  UgvMotionPreview preview;
  preview.step_s = 0.5;
  preview.displacement_m = {Eigen::Vector2d::Zero(), Eigen::Vector2d(0.25, 0.0)};
  preview.velocity_mps = {Eigen::Vector2d(0.5, 0.0), Eigen::Vector2d(0.5, 0.0)};
  UgvMotion at_message;
  at_message.p_WG = {2.0, 1.0};
  at_message.a_WG = {3.0, 0.0};  // the preview, not the acceleration, decides
  const UgvMotion m = planned_motion(at_message, preview, 0.2);
  EXPECT_NEAR((m.p_WG - Eigen::Vector2d(2.1, 1.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((m.v_WG - Eigen::Vector2d(0.5, 0.0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(m.a_WG.norm(), 0.0);
}

}  // namespace
}  // namespace ferret::tether
