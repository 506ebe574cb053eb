#include "ferret/planning/policies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace ferret {
namespace {
double direction_rad(const Eigen::Vector2d& v) { return std::atan2(v.y(), v.x()); }

bool still_a_goal(const ExplorationState& s, Cell c) {
  return s.tracker.is_frontier(c) && !s.tracker.blacklisted(c) && s.paths.reachable(c);
}
}  // namespace

std::optional<double> frontier_heading_rad(const IrGrid& grid, Cell c) {
  const GridGeometry& g = grid.geometry();
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  constexpr int kR = 3;
  for (int dj = -kR; dj <= kR; ++dj)
    for (int di = -kR; di <= kR; ++di) {
      const Cell n{c.i + di, c.j + dj};
      if ((di == 0 && dj == 0) || !g.contains(n) || grid.label(n) != GridLabel::kUnknown) continue;
      sum += Eigen::Vector2d(di, dj).normalized();
    }
  if (sum.norm() < 1e-9) return std::nullopt;
  return direction_rad(sum);
}

std::size_t cdos_argmax(std::span<const ScoredFrontier> scored, const Eigen::Vector2d& tie_anchor) {
  std::size_t best = 0;
  double best_dist = 0.0;
  for (std::size_t k = 0; k < scored.size(); ++k) {
    const double dist = (scored[k].p_W - tie_anchor).norm();
    if (k == 0 || scored[k].loss > scored[best].loss + 1e-12 ||
        (std::abs(scored[k].loss - scored[best].loss) <= 1e-12 && dist < best_dist)) {
      best = k;
      best_dist = dist;
    }
  }
  return best;
}

std::optional<ExplorationGoal> NearestFrontierPolicy::choose(const ExplorationState& s) {
  if (!committed_ || !still_a_goal(s, *committed_)) {
    committed_.reset();
    float best = kUnreachable;
    for (const Cell& c : s.frontier_sets().global) {
      const float d = s.paths.distance_m(c);
      if (d < best) {
        best = d;
        committed_ = c;
      }
    }
  }
  if (!committed_) return std::nullopt;
  ExplorationGoal goal;
  goal.cell = *committed_;
  goal.p_W = s.grid.geometry().center(goal.cell);
  goal.heading_rad = frontier_heading_rad(s.grid, goal.cell);
  goal.score = s.paths.distance_m(goal.cell);
  goal.reason = {GoalRule::kNearest};
  return goal;
}

std::optional<ExplorationGoal> RapidFrontierPolicy::choose_visible(const ExplorationState& s,
                                                                   double max_velocity_mps) {
  if (s.frontier_sets().visible.empty()) return std::nullopt;
  // At rest every direction asks the same change |v_max u|: a small velocity along
  // the heading makes the current heading break the tie.
  Eigen::Vector2d v = s.v_W;
  if (v.norm() < 0.05)
    v = 0.05 * Eigen::Vector2d(std::cos(s.X_WG.yaw_rad), std::sin(s.X_WG.yaw_rad));
  const GridGeometry& g = s.grid.geometry();
  const Eigen::Vector2d p = s.X_WG.position();
  std::optional<ExplorationGoal> best;
  for (const Cell& c : s.frontier_sets().visible) {
    const Eigen::Vector2d to = g.center(c) - p;
    const double dist = to.norm();
    const Eigen::Vector2d u =
        dist > 1e-9 ? Eigen::Vector2d(to / dist) : Eigen::Vector2d(v.normalized());
    const double change = (max_velocity_mps * u - v).norm();
    if (!best || change < best->score - 1e-12) {
      best = ExplorationGoal{};
      best->cell = c;
      best->p_W = g.center(c);
      best->score = change;
    }
  }
  best->reason = {GoalRule::kRapid};
  return best;
}

std::optional<ExplorationGoal> RapidFrontierPolicy::choose(const ExplorationState& s) {
  if (committed_ && still_a_goal(s, committed_->cell)) return committed_;
  committed_ = choose_visible(s, options_.max_velocity_mps);
  if (committed_) return committed_;
  return fallback_.choose(s);
}

CdosPolicy::CdosPolicy(const PolicyOptions& options, bool literal, std::string name)
    : options_(options), literal_(literal), name_(std::move(name)), baseline_(options) {
  if (literal_) {
    options_.curiosity.use_labels = true;
    options_.curiosity.cap_prediction = false;
    options_.cdos_candidates_global = false;
  }
}

std::optional<ExplorationGoal> CdosPolicy::choose(const ExplorationState& s) {
  if (committed_ && s.paths.reachable(committed_->cell) && !s.tracker.blacklisted(committed_->cell))
    return committed_;
  committed_.reset();
  auto goal = choose_fresh(s);
  if (goal && goal->reason.rule == GoalRule::kCuriosity) {
    committed_ = goal;
    baseline_.goal_done();  // the baseline's goal is abandoned
  }
  return goal;
}

std::optional<ExplorationGoal> CdosPolicy::choose_fresh(const ExplorationState& s) {
  const auto evidence = collect_evidence(s.objects);
  if (!literal_ && evidence.empty())
    return baseline_.choose(s);  // no evidence: choose as the baseline does
  const auto& candidates =
      options_.cdos_candidates_global ? s.frontier_sets().global : s.frontier_sets().visible;
  if (candidates.empty()) return fallback_.choose(s);  // Algorithm 1: F_v empty -> nearest in F_g
  const GridGeometry& g = s.grid.geometry();
  const Eigen::Vector2d p = s.X_WG.position();
  const auto scored = score_frontiers(candidates, g, p, evidence, options_.curiosity);
  // argmax L(C) (paper eq. (action_select)). Ties: the confidence floor makes the
  // predicted gain flat beyond eta / conf_floor of the evidence, so cdos breaks ties
  // towards the strongest evidence (what the loss says without the floor).
  if (literal_ &&
      std::all_of(scored.begin(), scored.end(), [](const auto& sf) { return sf.loss <= 1e-12; }))
    return baseline_.choose(s);  // the paper gives no rule: the baseline's
  const Eigen::Vector2d tie_anchor =
      literal_ || evidence.empty() ? p : strongest_evidence(evidence).p_W;
  const ScoredFrontier* best = &scored[cdos_argmax(scored, tie_anchor)];
  if (!literal_ && best->loss <= 1e-12)  // curiosity is silent here: choose as the baseline does
    return baseline_.choose(s);
  ExplorationGoal goal;
  goal.cell = best->cell;
  goal.p_W = best->p_W;
  goal.score = best->loss;
  goal.reason = {GoalRule::kCuriosity};
  if (!literal_) {
    // The paper's "pointing towards o_i": face the strongest evidence on arrival.
    const Eigen::Vector2d to = strongest_evidence(evidence).p_W - goal.p_W;
    if (to.norm() > 1e-6) goal.heading_rad = direction_rad(to);
  }
  return goal;
}

std::optional<ExplorationGoal> OraclePolicy::choose(const ExplorationState& s) {
  if (!s.oracle_object_W) return fallback_.choose(s);
  if (!planner_) planner_.emplace(s.grid.geometry());
  const double escape_m = s.grid.options().clearance_m + 2 * s.grid.geometry().resolution_m;
  planner_->compute(s.grid, s.paths.start(), GridPathPlanner::Traversal::kNotOccupied, escape_m);
  auto goal =
      viewing_goal(s.grid, s.tracker, *planner_, *s.oracle_object_W, options_.view_distance_m);
  if (!goal) return fallback_.choose(s);
  goal->path_W = planner_->path_to(goal->cell);
  goal->reason = {GoalRule::kOracle};
  return goal;
}

}  // namespace ferret
