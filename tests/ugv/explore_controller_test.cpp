#include "ferret/ugv/explore_controller.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/planning/exploration_policy.hpp"
#include "ferret/sim/exploration_run.hpp"
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
  options.planner = planner;
  options.tether_budget_m = budget_m;
  ExploreController controller(truth.geometry, kEntry, options);
  Search run;
  for (long step = 0; step * controller.tick_s() < time_s; ++step) {
    const Pose2 pose = base.odometry();
    run.trajectory.push_back(pose);
    controller.observe_scan(base.ir_scan());
    if (controller.frame_due(step)) (void)controller.observe_frame(base.camera_frame(step * controller.tick_s()));
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

// A path round a pillar the IR never saw (G stays unknown): the real tether wraps the
// pillar; the estimate (G's obstacles only) lies straight and falls short of it; the
// bound the reach check uses (unknown space too) does not.
TEST(ExploreController, TheReachBoundCoversATetherRoundAnObstacleTheIrNeverSaw) {
  const GridGeometry geo{0.0, 0.0, 0.05, 200, 200};
  ExploreOptions options;
  options.tether_budget_m = 100.0;
  const Pose2 entry{2.0, 5.0, 0.0};
  ExploreController controller(geo, entry, options);
  // The pillar [4.8, 5.2]^2 as the truth has it (its convex corners).
  std::vector<TetherCorner> pillar;
  const std::array<std::pair<Eigen::Vector2d, std::uint8_t>, 4> corners{
      {{{4.8, 4.8}, 1u << 0}, {{5.2, 4.8}, 1u << 1}, {{5.2, 5.2}, 1u << 2}, {{4.8, 5.2}, 1u << 3}}};
  for (const auto& [p, q] : corners) pillar.push_back({p, q});
  TautTether truth(TetherCorners::from_list(pillar), entry.position());
  // Below the pillar, up its right side, and over it: 5 cm steps, 0.1 s apart.
  const std::vector<Eigen::Vector2d> legs{{5.0, 3.5}, {8.0, 5.0}, {5.0, 6.5}};
  Eigen::Vector2d p = entry.position();
  double t = 0.0;
  for (const auto& to : legs)
    while ((to - p).norm() > 1e-9) {
      const Eigen::Vector2d d = to - p;
      p += d.norm() > 0.05 ? Eigen::Vector2d(0.05 * d.normalized()) : d;
      t += 0.1;
      controller.follow_tether({p.x(), p.y(), 0.0}, t);
      truth.move_to(p);
    }
  ASSERT_FALSE(truth.wrap_points().empty());
  // By hand: (2,5) -> (4.8,4.8) -> (5.2,4.8) -> (5.2,5.2) -> (5,6.5).
  EXPECT_NEAR(truth.length_m(), std::hypot(2.8, 0.2) + 0.8 + std::hypot(0.2, 1.3), 1e-9);
  EXPECT_NEAR(controller.tether_length_m(), (p - entry.position()).norm(), 1e-9);  // straight
  EXPECT_GE(controller.reach_length_m(), truth.length_m());
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
        if (s.tracker.blacklisted(c) || !s.paths.reachable(c) || s.paths.distance_m(c) <= far_m) continue;
        far_m = s.paths.distance_m(c);
        far = c;
      }
      if (far && !s.within_reach(*far, s.paths.path_to(*far))) {
        ++reach_first_counts.refusals;
        const auto& global = s.frontier_sets().global;
        if (std::find(global.begin(), global.end(), *far) != global.end()) ++reach_first_counts.refused_cell_in_sets;
      }
    }
    std::optional<ExplorationGoal> best;
    for (const Cell& c : s.frontier_sets().global)
      if (!s.tracker.blacklisted(c) && (!best || s.paths.distance_m(c) < best->score)) {
        best = ExplorationGoal{};
        best->cell = c;
        best->p_W = g.center(c);
        best->score = s.paths.distance_m(c);
        best->reason = "probe";
      }
    return best;
  }
};

TEST(ExploreController, APolicyAskingTheTetherFirstStillReadsTheCyclesFrontierSets) {
  register_exploration_policy("reach-first-probe",
                              [](const PolicyOptions&) { return std::make_unique<ReachFirstPolicy>(); });
  reach_first_counts = {};
  const Search run = search("grid", 2.0, 30.0, "reach-first-probe");
  EXPECT_GT(run.decisions, 0);
  EXPECT_GT(reach_first_counts.refusals, 0);  // the setting does refuse far frontiers
  EXPECT_EQ(reach_first_counts.refused_cell_in_sets, reach_first_counts.refusals);
}

TEST(ExploreController, AnUnknownPlannerIsRefused) {
  ExploreOptions options;
  options.planner = "rrt";
  EXPECT_THROW(ExploreController(test::small_hidden_space().geometry, kEntry, options), std::invalid_argument);
}

}  // namespace
}  // namespace ferret
