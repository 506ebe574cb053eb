// The OMPL frontier policies: "cdos+ompl" and "rapid+ompl". They weigh the frontier
// cells by the CDOS or the rapid rule (frontier_sampler.hpp) and let PRM, fed by the
// frontier valid-state sampler and a frontier goal region, find the path to a
// frontier: OMPL picks the goal (the best-weighted one it connects within the
// tether's reach) and plans the way there. They commit to goals as the grid policies
// cdos and rapid do, so the two planners differ in how a goal is reached, not in when
// the search changes its mind. Each plan runs on a work budget seeded from the run's
// seed and the decision's number, so runs repeat exactly (also side by side in
// threads). Where PRM finds nothing, the goal is the best-weighted frontier whose grid
// path is within reach, and the exploration loop follows the grid path to it.

#include <cmath>

#include "ferret/planning/curiosity.hpp"
#include "ferret/planning/frontier_sampler.hpp"
#include "ferret/planning/policies.hpp"

namespace ferret {
namespace {

constexpr std::size_t kMaxFallbacks = 32;  ///< grid goals tried for reach when PRM finds none

class OmplFrontierPolicy final : public ExplorationPolicy {
 public:
  OmplFrontierPolicy(const PolicyOptions& options, bool cdos)
      : options_(options), cdos_(cdos), name_(cdos ? "cdos+ompl" : "rapid+ompl") {}
  [[nodiscard]] std::string_view name() const override { return name_; }

  std::optional<ExplorationGoal> choose(const ExplorationState& s) override {
    // A curiosity goal is driven to (as cdos does: Algorithm 1's "goto g*").
    if (committed_ && curious() && s.paths.reachable(committed_->cell) &&
        !s.tracker.blacklisted(committed_->cell) && replan(s))
      return committed_;
    auto candidates = std::make_shared<FrontierCandidates>(
        cdos_ ? cdos_candidates(s, options_.curiosity, options_.max_velocity_mps,
                                options_.cdos_candidates_global)
              : rapid_candidates(s, options_.max_velocity_mps));
    // Any other goal is kept while it is a frontier, unless curiosity now speaks (as
    // rapid and nearest keep theirs).
    if (committed_ && !curious() && candidates->rule != GoalRule::kCuriosity &&
        s.tracker.is_frontier(committed_->cell) && !s.tracker.blacklisted(committed_->cell) &&
        s.paths.reachable(committed_->cell) && replan(s))
      return committed_;
    committed_.reset();
    if (candidates->empty()) return std::nullopt;
    ExplorationGoal goal;
    if (!plan(s, candidates, goal)) return std::nullopt;
    goal.p_W = s.grid.geometry().center(goal.cell);
    const int k = candidates->find(goal.p_W.x(), goal.p_W.y());
    goal.score = k >= 0 ? candidates->weights[static_cast<std::size_t>(k)] : 0.0;
    // The grid policies' headings: curiosity faces the strongest evidence (the paper's
    // "pointing towards o_i"), nearest faces the unknown, rapid leaves it to the path.
    const auto evidence = collect_evidence(s.objects);
    if (candidates->rule == GoalRule::kCuriosity && !evidence.empty()) {
      const Eigen::Vector2d to = strongest_evidence(evidence).p_W - goal.p_W;
      if (to.norm() > 1e-6) goal.heading_rad = std::atan2(to.y(), to.x());
    } else if (candidates->rule == GoalRule::kNearest) {
      goal.heading_rad = frontier_heading_rad(s.grid, goal.cell);
    }
    committed_ = goal;
    return goal;
  }

  void goal_done() override { committed_.reset(); }
  [[nodiscard]] bool keeps_goal(const ObjectMap& objects,
                                const FrontierTracker& tracker) const override {
    if (!committed_ || tracker.blacklisted(committed_->cell)) return false;
    if (curious()) return true;
    // New evidence calls for a curiosity decision (cdos).
    return tracker.is_frontier(committed_->cell) && (!cdos_ || objects.evidence_cells().empty());
  }

 private:
  [[nodiscard]] bool curious() const {
    return committed_ && committed_->reason.rule == GoalRule::kCuriosity;
  }

  // The best-weighted candidate whose grid path is within reach (PRM found none).
  static bool fallback(const ExplorationState& s, const FrontierCandidates& candidates,
                       ExplorationGoal& goal) {
    std::size_t tried = 0;
    for (const std::size_t k : candidates.order) {
      const Cell c = candidates.cells[k];
      if (s.tracker.blacklisted(c) || !s.paths.reachable(c)) continue;
      if (s.within_reach) {
        if (tried++ >= kMaxFallbacks) return false;
        if (!s.within_reach(c, s.paths.path_to(c))) continue;
      }
      goal.cell = c;
      goal.reason = {candidates.rule, FrontierPlanner::kGrid};
      return true;  // path_W empty: the caller follows the grid path
    }
    return false;
  }

  // The way to the best-weighted candidate PRM connects within reach (or, where PRM
  // finds none, the best one whose grid path is within reach): goal's cell, path, reason.
  bool plan(const ExplorationState& s, std::shared_ptr<const FrontierCandidates> candidates,
            ExplorationGoal& goal) {
    const FrontierPlan plan = plan_to_frontier(s, candidates, FrontierPlanBudget{},
                                               derive_seed(options_.seed, {decisions_++}));
    if (!plan.solved) return fallback(s, *candidates, goal);
    goal.cell = plan.goal;
    goal.path_W = plan.path_W;
    goal.reason = {candidates->rule, FrontierPlanner::kOmpl};
    return true;
  }

  // The committed goal's path planned again from where the robot is, over G as it is
  // now (as the grid planner's path is); false if the goal is out of reach now.
  bool replan(const ExplorationState& s) {
    auto one = std::make_shared<FrontierCandidates>();
    one->geometry = s.grid.geometry();
    one->cells = {committed_->cell};
    one->weights = {1.0};
    one->rule = committed_->reason.rule;
    one->finalize();
    ExplorationGoal again;
    if (!plan(s, one, again)) return false;
    committed_->path_W = std::move(again.path_W);
    committed_->reason = std::move(again.reason);
    return true;
  }

  PolicyOptions options_;
  bool cdos_;
  std::string name_;
  std::optional<ExplorationGoal> committed_;
  std::uint64_t decisions_ = 0;
};

}  // namespace

void register_ompl_frontier_policies(ExplorationPolicies& policies) {
  policies.add_variant(
      "cdos", FrontierPlanner::kOmpl, "cdos+ompl",
      "cdos goals and paths by PRM with the frontier sampler",
      [](const PolicyOptions& o) { return std::make_unique<OmplFrontierPolicy>(o, true); });
  policies.add_variant(
      "rapid", FrontierPlanner::kOmpl, "rapid+ompl",
      "rapid goals and paths by PRM with the frontier sampler",
      [](const PolicyOptions& o) { return std::make_unique<OmplFrontierPolicy>(o, false); });
}

}  // namespace ferret
