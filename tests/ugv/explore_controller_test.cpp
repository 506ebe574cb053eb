#include "ferret/ugv/explore_controller.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/mission/exploration_run.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/sim/sim_ugv_base.hpp"
#include "ferret/tether_model/taut_tether.hpp"
#include "support/test_maps.hpp"

namespace ferret {
namespace {

const Pose2 kEntry{0.5, 1.0, 0.0};
const Eigen::Vector2d kBehindPartition{3.2, 0.8};  // out of sight from the entry

struct Search {
  int reach_rejections = 0, refused_choices = 0, decisions = 0;
  std::vector<Pose2> trajectory;
};

// The search on the small hidden space with a tether of `budget_m` on the floor,
// until it has explored what the tether reaches (or `time_s` ran out).
Search search(const std::string& planner, double budget_m, double time_s = 120.0,
              const std::string& method = "cdos") {
  const auto truth = test::small_hidden_space();
  ExplorationSettings settings;
  settings.method = method;
  HiddenSpaceSim sim(truth, kBehindPartition, settings.sensors, 5);
  SimUgvOptions base_options;
  base_options.battery_endurance_s = std::numeric_limits<double>::infinity();
  SimUgvBase base(sim, kEntry, base_options);
  ExploreOptions options = explore_options(settings, 5, kBehindPartition);
  options.planner = parse_frontier_planner(planner, "test");
  options.tether_budget_m = budget_m;
  ExploreController controller(truth.geometry, kEntry, options);
  Search run;
  for (long step = 0; step * controller.tick_s() < time_s; ++step) {
    const Pose2 pose = base.odometry();
    run.trajectory.push_back(pose);
    controller.observe_scan(base.ir_scan());
    if (controller.frame_due(step))
      (void)controller.observe_frame(base.camera_frame(step * controller.tick_s()));
    const auto command = controller.decide(step, pose);
    if (command.explored) break;
    base.command_velocity(command.velocity.v_mps, command.velocity.w_radps);
    base.step(controller.tick_s());
  }
  run.reach_rejections = controller.reach_rejections();
  run.refused_choices = controller.refused_choices();
  run.decisions = controller.decisions();
  return run;
}

// The tether as the OMPL planner's goal validity: with 2 m of tether on the floor the
// frontiers round the partition are out of reach. The grid policy chooses them and the
// controller refuses them afterwards; PRM asks first and never chooses one.
TEST(ExploreController, TheOmplPlannerNeverChoosesAGoalOutOfTheTethersReach) {
  const Search grid = search("grid", 2.0);
  EXPECT_GT(grid.refused_choices, 0);  // the setting does put goals out of reach
  const Search ompl = search("ompl", 2.0);
  EXPECT_GT(ompl.decisions, 0);
  EXPECT_GT(ompl.reach_rejections, 0);  // PRM met such goals...
  EXPECT_EQ(ompl.refused_choices, 0);   // ...and chose none of them
}

TEST(ExploreController, TheOmplPlannerRepeatsGivenTheSeed) {
  const Search a = search("ompl", 2.0, 20.0), b = search("ompl", 2.0, 20.0);
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (std::size_t k = 0; k < a.trajectory.size(); ++k) {
    EXPECT_EQ(a.trajectory[k].x_m, b.trajectory[k].x_m) << k;
    EXPECT_EQ(a.trajectory[k].y_m, b.trajectory[k].y_m) << k;
  }
}

// The pillar [4.8, 5.2]^2 in a 10 m square, the entry west of it.
const GridGeometry kPillarMap{0.0, 0.0, 0.05, 200, 200};
const Pose2 kPillarEntry{2.0, 5.0, 0.0};

struct PillarDrive {
  TautTether truth;  ///< the real line: round the pillar's convex corners
  Eigen::Vector2d p_W;
  double t_s = 0.0;
};

// Drives the controller's tether from the entry along `legs` in 5 cm steps, 0.1 s
// apart, the real line alongside.
PillarDrive drive_round_pillar(ExploreController& controller,
                               const std::vector<Eigen::Vector2d>& legs) {
  std::vector<TetherCorner> pillar;
  const std::array<std::pair<Eigen::Vector2d, std::uint8_t>, 4> corners{
      {{{4.8, 4.8}, 1u << 0}, {{5.2, 4.8}, 1u << 1}, {{5.2, 5.2}, 1u << 2}, {{4.8, 5.2}, 1u << 3}}};
  for (const auto& [p, q] : corners) pillar.push_back({p, q});
  PillarDrive d{TautTether(TetherCorners::from_list(pillar), kPillarEntry.position()),
                kPillarEntry.position()};
  for (const auto& to : legs)
    while ((to - d.p_W).norm() > 1e-9) {
      const Eigen::Vector2d step = to - d.p_W;
      d.p_W += step.norm() > 0.05 ? Eigen::Vector2d(0.05 * step.normalized()) : step;
      d.t_s += 0.1;
      controller.follow_tether({d.p_W.x(), d.p_W.y(), 0.0}, d.t_s);
      d.truth.move_to(d.p_W);
    }
  return d;
}

// A path round a pillar the IR never saw (G stays unknown): the real tether wraps the
// pillar; the estimate (G's obstacles only) lies straight and falls short of it; the
// bound the reach check uses (unknown space too) does not.
TEST(ExploreController, TheReachBoundCoversATetherRoundAnObstacleTheIrNeverSaw) {
  ExploreOptions options;
  options.tether_budget_m = 100.0;
  ExploreController controller(kPillarMap, kPillarEntry, options);
  // Below the pillar, up its right side, and over it.
  const PillarDrive d = drive_round_pillar(controller, {{5.0, 3.5}, {8.0, 5.0}, {5.0, 6.5}});
  ASSERT_FALSE(d.truth.wrap_points().empty());
  // By hand: (2,5) -> (4.8,4.8) -> (5.2,4.8) -> (5.2,5.2) -> (5,6.5).
  EXPECT_NEAR(d.truth.length_m(), std::hypot(2.8, 0.2) + 0.8 + std::hypot(0.2, 1.3), 1e-9);
  EXPECT_NEAR(controller.tether_length_m(), (d.p_W - kPillarEntry.position()).norm(),
              1e-9);  // straight
  EXPECT_GE(controller.reach_length_m(), d.truth.length_m());
}

// The IR saw the pillar's near face only, and the robot drove round the pillar: the
// real line wraps its body. Wrapped as seen (a shell one cell deep) the estimate falls
// short by about twice the body's depth; taking the body 0.2 m behind the face into
// the unknown space brings it nearer the truth, and never past the bound.
TEST(ExploreController, TheEstimateWrapsTheBodyBehindAFaceTheIrSaw) {
  struct Lengths {
    double estimate_m, bound_m, truth_m;
  };
  const auto drive_round = [&](double depth_m) {
    ExploreOptions options;
    options.tether_budget_m = 100.0;
    options.tether_obstacle_depth_m = depth_m;
    ExploreController controller(kPillarMap, kPillarEntry, options);
    // From below, the IR sees the face y = 4.8 (rays from (5, 3.5) up to it).
    RangeScan scan;
    scan.X_WS = {5.0, 3.5, std::numbers::pi / 2};
    for (double b = -0.14; b <= 0.14; b += 0.01) scan.beams.push_back({b, 1.3 / std::cos(b)});
    for (int k = 0; k < 5; ++k) controller.observe_scan(scan);
    // Below the pillar, up its right side, over it and down its left side.
    const PillarDrive d = drive_round_pillar(
        controller, {{5.0, 3.5}, {8.0, 5.0}, {5.0, 6.5}, {3.5, 5.0}, {4.0, 3.8}});
    controller.follow_tether({d.p_W.x(), d.p_W.y(), 0.0},
                             d.t_s + 10.0);  // a replay over G as it is
    return Lengths{controller.tether_length_m(), controller.reach_length_m(), d.truth.length_m()};
  };
  const Lengths face = drive_round(0.0), body = drive_round(0.2);
  // By hand, the truth wraps all four corners: (2,5) -> (4.8,4.8) -> (5.2,4.8) ->
  // (5.2,5.2) -> (4.8,5.2) -> (4,3.8).
  EXPECT_NEAR(face.truth_m, std::hypot(2.8, 0.2) + 3 * 0.4 + std::hypot(0.8, 1.4), 1e-9);
  EXPECT_EQ(face.truth_m, body.truth_m);
  EXPECT_LT(face.estimate_m, face.truth_m - 0.5);  // the shell: about twice 0.35 m short
  EXPECT_GT(body.estimate_m, face.estimate_m + 0.3);
  EXPECT_LT(std::abs(body.estimate_m - body.truth_m),
            0.5 * std::abs(face.estimate_m - face.truth_m));
  EXPECT_LE(body.estimate_m, body.bound_m + 1e-9);
  EXPECT_GE(body.bound_m, body.truth_m);
}

// A policy that asks the tether about the farthest reachable frontier cell before it
// reads the frontier sets (a refusal blacklists the cell), then drives to the nearest
// frontier. The controller extracts the sets only when a policy asks for them; they
// must still be the cycle's, taken before that blacklisting.
struct ReachFirstCounts {
  int refusals = 0, refused_cell_in_sets = 0;
};
ReachFirstCounts reach_first_counts;

class ReachFirstPolicy : public ExplorationPolicy {
 public:
  [[nodiscard]] std::string_view name() const override { return "reach-first-probe"; }
  [[nodiscard]] std::optional<ExplorationGoal> choose(const ExplorationState& s) override {
    const GridGeometry& g = s.grid.geometry();
    if (s.within_reach) {
      std::optional<Cell> far;
      double far_m = -1.0;
      for (const std::size_t idx : s.tracker.frontier_cells()) {
        const Cell c = g.cell_of_index(idx);
        if (s.tracker.blacklisted(c) || !s.paths.reachable(c) || s.paths.distance_m(c) <= far_m)
          continue;
        far_m = s.paths.distance_m(c);
        far = c;
      }
      if (far && !s.within_reach(*far, s.paths.path_to(*far))) {
        ++reach_first_counts.refusals;
        const auto& global = s.frontier_sets().global;
        if (std::find(global.begin(), global.end(), *far) != global.end())
          ++reach_first_counts.refused_cell_in_sets;
      }
    }
    std::optional<ExplorationGoal> best;
    for (const Cell& c : s.frontier_sets().global)
      if (!s.tracker.blacklisted(c) && (!best || s.paths.distance_m(c) < best->score)) {
        best = ExplorationGoal{};
        best->cell = c;
        best->p_W = g.center(c);
        best->score = s.paths.distance_m(c);
        best->reason = {GoalRule::kNearest};
      }
    return best;
  }
};

TEST(ExploreController, APolicyAskingTheTetherFirstStillReadsTheCyclesFrontierSets) {
  register_exploration_policy("reach-first-probe", [](const PolicyOptions&) {
    return std::make_unique<ReachFirstPolicy>();
  });
  reach_first_counts = {};
  const Search run = search("grid", 2.0, 30.0, "reach-first-probe");
  EXPECT_GT(run.decisions, 0);
  EXPECT_GT(reach_first_counts.refusals, 0);  // the setting does refuse far frontiers
  EXPECT_EQ(reach_first_counts.refused_cell_in_sets, reach_first_counts.refusals);
}

TEST(ExploreController, AnUnknownPlannerIsRefused) {
  // The planner is an enum: a name that is none is refused where the text is parsed.
  EXPECT_THROW((void)parse_frontier_planner("rrt", "--planner"), InputError);
  ExploreOptions options;
  options.planner = FrontierPlanner::kOmpl;  // the sampler serves cdos and rapid, not nearest
  options.method = "nearest";
  EXPECT_THROW(ExploreController(test::small_hidden_space().geometry, kEntry, options), InputError);
}

TEST(ExploreController, ABumpMarksTheCellsAtTheBodysFrontOccupiedAndNoOthers) {
  // A 12 cm body facing +y in a free room of 2.5 cm cells: the cells it marks are those
  // within a cell outside its disc and at most 60 degrees off its heading.
  GridGeometry g;
  g.resolution_m = 0.025;
  g.width = 80;
  g.height = 80;
  ExploreOptions options;
  options.robot.body_radius_m = 0.06;
  const Pose2 pose{1.0, 1.0, std::numbers::pi / 2.0};
  ExploreController controller(g, pose, options);
  const int marked = controller.mark_bumped(pose);
  EXPECT_GT(marked, 3);
  int occupied = 0;
  for (int j = 0; j < g.height; ++j)
    for (int i = 0; i < g.width; ++i) {
      if (controller.grid().label({i, j}) != GridLabel::kOccupied) continue;
      ++occupied;
      const Eigen::Vector2d d = g.center({i, j}) - pose.position();
      EXPECT_GE(d.norm(), 0.06 - 0.0125 - 1e-9) << i << ", " << j;
      EXPECT_LE(d.norm(), 0.06 + 0.025 + 1e-9) << i << ", " << j;
      EXPECT_GE(d.y(), 0.5 * d.norm() - 1e-9) << i << ", " << j;  // within 60 degrees of +y
    }
  EXPECT_EQ(occupied, marked);
  // The cell straight ahead of the body's front is among them, the one behind is not.
  EXPECT_EQ(controller.grid().label(g.cell_at(1.0, 1.07)), GridLabel::kOccupied);
  EXPECT_NE(controller.grid().label(g.cell_at(1.0, 0.93)), GridLabel::kOccupied);
  // Marked again, nothing new; a point robot (the paper's) marks nothing.
  EXPECT_EQ(controller.mark_bumped(pose), 0);
  options.robot.body_radius_m = 0.0;
  ExploreController point(g, pose, options);
  EXPECT_EQ(point.mark_bumped(pose), 0);
}

}  // namespace
}  // namespace ferret
