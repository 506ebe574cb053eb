#include "ferret/planning/next_goal.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "exploration_room.hpp"
#include "ferret/core/error.hpp"

namespace ferret {
namespace {

using World = test::HalfSeenRoom;

// The maps of a search loop as a client would send them: occupancy probabilities (or -1
// for unknown) and the object map's probabilities.
NextGoalRequest request_from(const World& w) {
  NextGoalRequest r;
  r.geometry = w.geo;
  for (std::size_t k = 0; k < w.geo.size(); ++k) {
    const Cell c = w.geo.cell_of_index(k);
    r.occupancy.push_back(
        w.grid.label(c) == GridLabel::kUnknown ? -1.0f : static_cast<float>(w.grid.probability(c)));
    r.object_probability.push_back(static_cast<float>(w.objects.probability(c)));
    r.object_confidence.push_back(static_cast<float>(w.objects.last_confidence(k)));
  }
  r.pose = w.pose;
  r.velocity_W = w.v;
  r.ir_fov_rad = deg_to_rad(60);
  r.ir_range_m = 4.0;
  r.camera_range_m = 4.0;
  return r;
}

// One detection of an object at `object_W` seen from the robot (policy_test's evidence).
void see_object(World& w, const Eigen::Vector2d& object_W) {
  CameraFrame frame;
  frame.view = {w.pose, 4.0, {}};
  const Eigen::Vector2d to = object_W - w.pose.position();
  frame.detections = {{std::atan2(to.y(), to.x()), to.norm(), 1.0 / to.norm()}};
  w.objects.integrate_frame(frame);
}

TEST(NextGoal, TheMapsSentAsProbabilitiesGiveThePolicysOwnChoice) {
  for (const char* method : {"cdos", "rapid", "nearest"}) {
    World w;
    w.v = {0.3, 0.8};
    see_object(w, {3.0, 1.8});
    auto policy = make_exploration_policy(method, PolicyOptions::from(MissionConfig{}, 4.0, 2.0));
    const auto direct = policy->choose(w.state());
    NextGoalRequest r = request_from(w);
    r.method = method;
    const auto served = next_exploration_goal(r);
    ASSERT_TRUE(direct && served) << method;
    EXPECT_EQ(served->cell, direct->cell) << method;
    EXPECT_EQ(served->reason, direct->reason) << method;
    EXPECT_NEAR(served->score, direct->score, 1e-5) << method;
    // One detection: without the confidences the service takes each cell's probability
    // for its last confidence, which is what one fusion from the prior left there.
    r.object_confidence.clear();
    const auto implied = next_exploration_goal(r);
    ASSERT_TRUE(implied);
    EXPECT_EQ(implied->cell, direct->cell) << method;
    // A path over known free cells from the robot to the goal.
    ASSERT_GE(served->path_W.size(), 2u) << method;
    EXPECT_LT((served->path_W.front() - w.pose.position()).norm(), 0.1) << method;
    EXPECT_LT((served->path_W.back() - served->p_W).norm(), 0.1) << method;
    for (const Eigen::Vector2d& p : served->path_W)
      EXPECT_EQ(w.grid.label(w.geo.cell_at(p.x(), p.y())), GridLabel::kFree) << method;
  }
}

TEST(NextGoal, CdosFollowsTheObjectMapItIsSent) {
  // The same half-seen room; only the object map differs: evidence above the robot's
  // line or below it. The goal follows it to the frontier's matching end.
  for (const double y_object : {1.8, 0.2}) {
    World w;
    NextGoalRequest r = request_from(w);
    for (std::size_t k = 0; k < w.geo.size(); ++k)
      if ((w.geo.center(w.geo.cell_of_index(k)) - Eigen::Vector2d(3.0, y_object)).norm() < 0.3)
        r.object_probability[k] = 0.8f;
    const auto goal = next_exploration_goal(r);
    ASSERT_TRUE(goal);
    EXPECT_EQ(to_string(goal->reason), "curiosity");
    EXPECT_NEAR(goal->p_W.y(), y_object, 0.35) << "evidence at y = " << y_object;
    // Without evidence the choice is rapid's: straight ahead at rest.
    r.object_probability.clear();
    const auto plain = next_exploration_goal(r);
    ASSERT_TRUE(plain);
    EXPECT_NEAR(plain->p_W.y(), 1.0, 0.06);
  }
}

TEST(NextGoal, ARoomSeenWholeHasNothingLeftToExplore) {
  // 1 x 1 m, walls round it, every cell known: no frontier.
  NextGoalRequest r;
  r.geometry = {0.0, 0.0, 0.05, 20, 20};
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 20; ++i)
      r.occupancy.push_back(i == 0 || j == 0 || i == 19 || j == 19 ? 0.97f : 0.12f);
  r.pose = {0.5, 0.5, 0.0};
  EXPECT_FALSE(next_exploration_goal(r).has_value());
  // One unknown cell in the room makes its neighbours a frontier again.
  r.occupancy[static_cast<std::size_t>(10 * 20 + 12)] = -1.0f;
  const auto goal = next_exploration_goal(r);
  ASSERT_TRUE(goal);
  EXPECT_LE(std::abs(goal->cell.i - 12) + std::abs(goal->cell.j - 10), 2);
}

TEST(NextGoal, BadRequestsNameTheField) {
  World w;
  const NextGoalRequest good = request_from(w);
  const auto field_of = [](const NextGoalRequest& r) -> std::string {
    try {
      (void)next_exploration_goal(r);
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), "NextGoalRequest");
      return e.field();
    }
    return "(accepted)";
  };
  EXPECT_EQ(field_of(good), "(accepted)");
  NextGoalRequest r = good;
  r.occupancy.pop_back();
  EXPECT_EQ(field_of(r), "occupancy");
  r = good;
  r.occupancy[5] = 1.5f;
  EXPECT_EQ(field_of(r), "occupancy[5]");
  r = good;
  r.occupancy[7] = std::nanf("");
  EXPECT_EQ(field_of(r), "occupancy[7]");
  r = good;
  r.object_probability.resize(3);
  EXPECT_EQ(field_of(r), "object_probability");
  r = good;
  r.object_probability[9] = -0.1f;
  EXPECT_EQ(field_of(r), "object_probability[9]");
  r = good;
  r.object_confidence.resize(2);
  EXPECT_EQ(field_of(r), "object_confidence");
  r = good;
  r.object_confidence[4] = 2.0f;
  EXPECT_EQ(field_of(r), "object_confidence[4]");
  r = good;
  r.pose = {-1.0, 1.0, 0.0};  // outside the grid
  EXPECT_EQ(field_of(r), "pose");
  r = good;
  r.pose.yaw_rad = INFINITY;
  EXPECT_EQ(field_of(r), "pose");
  r = good;
  r.method = "random";
  EXPECT_EQ(field_of(r), "method");
  r.method = "oracle";  // it would need to know where the object is
  EXPECT_EQ(field_of(r), "method");
  r = good;
  r.geometry.resolution_m = 0.0;
  EXPECT_EQ(field_of(r), "resolution_m");
  r = good;
  r.geometry.width = 100000;
  EXPECT_EQ(field_of(r), "width");
  r = good;
  r.velocity_W.x() = NAN;
  EXPECT_EQ(field_of(r), "velocity");
}

}  // namespace
}  // namespace ferret
