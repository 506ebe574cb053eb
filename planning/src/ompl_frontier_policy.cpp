// The OMPL frontier policies: "cdos+ompl" and "rapid+ompl". They weigh the frontier
// cells by the CDOS or the rapid rule (frontier_sampler.hpp) and let PRM, fed by the
// frontier valid-state sampler and a frontier goal region, find the path to a
// frontier: OMPL both picks the goal (by the weights) and plans the way there. Each
// plan runs on a work budget seeded from the run's seed and the decision's number,
// so runs repeat exactly (also side by side in threads). Where PRM finds nothing,
// the goal is the best-weighted frontier and the exploration loop plans the grid
// path to it.

#include <cmath>

#include "ferret/planning/curiosity.hpp"
#include "ferret/planning/frontier_sampler.hpp"
#include "ferret/planning/policies.hpp"

namespace ferret {
namespace {

class OmplFrontierPolicy final : public ExplorationPolicy {
 public:
  OmplFrontierPolicy(const PolicyOptions& options, bool cdos)
      : options_(options), cdos_(cdos), name_(cdos ? "cdos+ompl" : "rapid+ompl") {}
  [[nodiscard]] std::string_view name() const override { return name_; }

  std::optional<ExplorationGoal> choose(const ExplorationState& s) override {
    if (committed_ && s.tracker.is_frontier(committed_->cell) && !s.tracker.blacklisted(committed_->cell) &&
        s.paths.reachable(committed_->cell)) {
      trim_path(*committed_, s.X_WG.position());
      return committed_;
    }
    committed_.reset();
    auto candidates = std::make_shared<FrontierCandidates>(
        cdos_ ? cdos_candidates(s, options_.curiosity, options_.max_velocity_mps) : rapid_candidates(s, options_.max_velocity_mps));
    if (candidates->empty()) return std::nullopt;
    const FrontierPlan plan = plan_to_frontier(s, candidates, FrontierPlanBudget{},
                                               derive_seed(options_.seed, {decisions_++}));
    ExplorationGoal goal;
    if (plan.solved) {
      goal.cell = plan.goal;
      goal.path_W = plan.path_W;
      goal.reason = candidates->rule + "+ompl";
    } else {
      const auto best = std::max_element(candidates->weights.begin(), candidates->weights.end());
      goal.cell = candidates->cells[static_cast<std::size_t>(best - candidates->weights.begin())];
      goal.reason = candidates->rule + "+grid";
    }
    goal.p_W = s.grid.geometry().center(goal.cell);
    const int k = candidates->find(goal.p_W.x(), goal.p_W.y());
    goal.score = k >= 0 ? candidates->weights[static_cast<std::size_t>(k)] : 0.0;
    // Face the strongest evidence when curiosity chose (the paper's "pointing
    // towards o_i"), the unknown otherwise.
    const auto evidence = collect_evidence(s.objects);
    if (candidates->rule == "curiosity" && !evidence.empty()) {
      const Eigen::Vector2d to = strongest_evidence(evidence).p_W - goal.p_W;
      if (to.norm() > 1e-6) goal.heading_rad = std::atan2(to.y(), to.x());
    } else {
      goal.heading_rad = frontier_heading_rad(s.grid, goal.cell);
    }
    committed_ = goal;
    return goal;
  }

  void goal_done() override { committed_.reset(); }
  [[nodiscard]] bool keeps_goal(const ObjectMap&, const FrontierTracker& tracker) const override {
    return committed_ && tracker.is_frontier(committed_->cell) && !tracker.blacklisted(committed_->cell);
  }

 private:
  // The committed path from where the robot is now: from the waypoint it is closest to.
  static void trim_path(ExplorationGoal& goal, const Eigen::Vector2d& robot) {
    if (goal.path_W.empty()) return;
    std::size_t nearest = 0;
    for (std::size_t k = 1; k < goal.path_W.size(); ++k)
      if ((goal.path_W[k] - robot).norm() < (goal.path_W[nearest] - robot).norm()) nearest = k;
    std::vector<Eigen::Vector2d> rest{robot};
    rest.insert(rest.end(), goal.path_W.begin() + static_cast<std::ptrdiff_t>(std::min(nearest + 1, goal.path_W.size() - 1)),
                goal.path_W.end());
    goal.path_W = std::move(rest);
  }

  PolicyOptions options_;
  bool cdos_;
  std::string name_;
  std::optional<ExplorationGoal> committed_;
  std::uint64_t decisions_ = 0;
};

// Registered when the planning library loads, beside the built-in policies.
const bool kRegistered = [] {
  register_exploration_policy("cdos+ompl", [](const PolicyOptions& o) {
    return std::make_unique<OmplFrontierPolicy>(o, true);
  });
  register_exploration_policy("rapid+ompl", [](const PolicyOptions& o) {
    return std::make_unique<OmplFrontierPolicy>(o, false);
  });
  return true;
}();

}  // namespace
}  // namespace ferret
