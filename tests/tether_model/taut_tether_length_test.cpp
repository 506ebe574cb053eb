#include "ferret/tether_model/taut_tether_length.hpp"

#include <gtest/gtest.h>

namespace ferret::tether {
namespace {

// The block x in [1, 3.5], y in [0.5, 2] of examples/trajectories/default.yaml as the
// planner's corner set, against the fixed wrap points the scripted scenario uses.
TEST(TautTetherLengthModel, AgreesWithTheFixedWrapPointsAlongTheDefaultRoute) {
  auto corners = TetherCorners::from_list({{{3.5, 0.5}, 0b0010},    // block on the (-x, +y) side
                                           {{3.5, 2.0}, 0b0100},    // (-x, -y)
                                           {{1.0, 0.5}, 0b0001},    // (+x, +y)
                                           {{1.0, 2.0}, 0b1000}});  // (+x, -y)
  const Eigen::Vector2d start(0.3, 0.0);
  TautTetherLengthModel planner(TautTether(corners, Eigen::Vector2d::Zero(), start), 1.0);
  const FixedWrapTether fixed(1.0, Eigen::Vector2d::Zero(), {{{3.5, 0.5}, +1}, {{3.5, 2.0}, +1}});
  const std::vector<Eigen::Vector2d> route = {{0.3, 0.0}, {4.2, 0.0}, {4.2, 3.0}, {1.5, 3.0},
                                              {4.2, 3.0}, {4.2, 0.0}, {0.3, 0.0}};
  std::size_t max_wraps = 0;
  for (std::size_t leg = 0; leg + 1 < route.size(); ++leg) {
    for (int i = 1; i <= 50; ++i) {
      const Eigen::Vector2d p = route[leg] + (route[leg + 1] - route[leg]) * (i / 50.0);
      // A prediction from the previous pose equals the tether once it gets there.
      const double predicted = planner.required_length_m(p);
      planner.advance(p);
      EXPECT_NEAR(predicted, 1.0 + planner.tether().length_m(), 1e-12);
      EXPECT_NEAR(planner.required_length_m(p), fixed.required_length_m(p), 1e-9)
          << "leg " << leg << " step " << i;
      max_wraps = std::max(max_wraps, planner.tether().wrap_points().size());
    }
  }
  EXPECT_EQ(max_wraps, 2u);
  EXPECT_TRUE(planner.tether().wrap_points().empty());  // unwound on the way back
}

}  // namespace
}  // namespace ferret::tether
