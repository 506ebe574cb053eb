#pragma once
// The built-in exploration policies (see exploration_policy.hpp for the interface
// and docs/object_search.md for the behaviour of each).

#include <optional>
#include <span>
#include <string>

#include "ferret/planning/exploration_policy.hpp"

namespace ferret {

/// The direction from a frontier cell towards the unknown cells around it (mean of
/// the unit vectors to unknown cells within 3 cells); none if there are none.
[[nodiscard]] std::optional<double> frontier_heading_rad(const IrGrid& grid, Cell c);

/// The cdos goal among scored candidates (@pre non-empty): the largest loss L(C);
/// losses within 1e-12 are equal and the one nearest `tie_anchor` wins (the
/// confidence floor makes the loss flat far from the evidence).
[[nodiscard]] std::size_t cdos_argmax(std::span<const ScoredFrontier> scored,
                                      const Eigen::Vector2d& tie_anchor);

/// Classic frontier: the reachable F_g cell of least path distance, facing the
/// unknown. Commits to its goal while it stays a reachable, non-blacklisted frontier.
class NearestFrontierPolicy final : public ExplorationPolicy {
 public:
  explicit NearestFrontierPolicy(const PolicyOptions& options = {}) { (void)options; }
  [[nodiscard]] std::string_view name() const override { return "nearest"; }
  [[nodiscard]] std::optional<ExplorationGoal> choose(const ExplorationState& state) override;
  void goal_done() override { committed_.reset(); }
  [[nodiscard]] bool keeps_goal(const ObjectMap&, const FrontierTracker& tracker) const override {
    return committed_ && tracker.is_frontier(*committed_) && !tracker.blacklisted(*committed_);
  }

 private:
  std::optional<Cell> committed_;
};

/// Rapid frontier (Cieslewski et al. 2017): the F_v cell whose direction asks the
/// least change of velocity, |v_max u(g) - v|; at rest the heading breaks the tie.
/// Where F_v is empty, the nearest F_g cell (classic). The goal is kept while it is
/// still a frontier: in open space the IR resolves it long before the robot gets
/// there and a new one is chosen (the method stays reactive), while a frontier that
/// no view resolves is reached and blacklisted. Re-choosing every cycle instead lets
/// the robot circle unresolvable frontiers forever.
class RapidFrontierPolicy final : public ExplorationPolicy {
 public:
  explicit RapidFrontierPolicy(const PolicyOptions& options) : options_(options) {}
  [[nodiscard]] std::string_view name() const override { return "rapid"; }
  [[nodiscard]] std::optional<ExplorationGoal> choose(const ExplorationState& state) override;
  void goal_done() override {
    committed_.reset();
    fallback_.goal_done();
  }
  [[nodiscard]] bool keeps_goal(const ObjectMap& objects,
                                const FrontierTracker& tracker) const override {
    if (!committed_) return fallback_.keeps_goal(objects, tracker);
    return tracker.is_frontier(committed_->cell) && !tracker.blacklisted(committed_->cell);
  }

  /// The rapid rule on F_v alone (none if F_v is empty).
  [[nodiscard]] static std::optional<ExplorationGoal> choose_visible(const ExplorationState& state,
                                                                     double max_velocity_mps);

 private:
  PolicyOptions options_;
  NearestFrontierPolicy fallback_;
  std::optional<ExplorationGoal> committed_;
};

/// Curiosity-driven object search. `literal` selects the paper read to the letter.
///  cdos: argmax of the curiosity loss over F_v (raw probabilities, capped
///    prediction) among evidence cells, goal heading facing the strongest evidence,
///    driven to before the next choice;
///    with no evidence (or no positive loss) the rapid rule; F_v empty: nearest F_g.
///  cdos-literal: the loss on relabelled probabilities (eq. (cap_O)), uncapped
///    prediction, argmax over F_v (all zero, as is usual: the rapid rule; other ties:
///    the candidate nearest the robot), heading left to the path; F_v empty: nearest
///    F_g (Algorithm 1).
class CdosPolicy final : public ExplorationPolicy {
 public:
  /// @param name  the registered name (variants with other PolicyOptions, e.g. "cdos-fg")
  CdosPolicy(const PolicyOptions& options, bool literal, std::string name = {});
  [[nodiscard]] std::string_view name() const override {
    return !name_.empty() ? std::string_view(name_) : literal_ ? "cdos-literal" : "cdos";
  }
  [[nodiscard]] std::optional<ExplorationGoal> choose(const ExplorationState& state) override;
  void goal_done() override {
    committed_.reset();
    baseline_.goal_done();
    fallback_.goal_done();
  }
  /// A curiosity goal is kept until reached; without one, the baseline's goal is kept
  /// only while O holds no evidence (new evidence calls for a curiosity decision).
  [[nodiscard]] bool keeps_goal(const ObjectMap& objects,
                                const FrontierTracker& tracker) const override {
    if (committed_) return !tracker.blacklisted(committed_->cell);
    return objects.evidence_cells().empty() && baseline_.keeps_goal(objects, tracker);
  }

 private:
  [[nodiscard]] std::optional<ExplorationGoal> choose_fresh(const ExplorationState& state);

  PolicyOptions options_;
  bool literal_;
  std::string name_;
  RapidFrontierPolicy baseline_;  ///< where curiosity is silent
  NearestFrontierPolicy fallback_;
  /// A curiosity goal is driven to before deciding again (Algorithm 1: "goto g*");
  /// without evidence the policy stays as reactive as the baseline.
  std::optional<ExplorationGoal> committed_;
};

/// Knows the object: drives the shortest path (through unknown cells too, as far as
/// G allows) towards the nearest pose that sees it. Falls back to the nearest frontier
/// while no viewing pose is reachable.
class OraclePolicy final : public ExplorationPolicy {
 public:
  explicit OraclePolicy(const PolicyOptions& options) : options_(options) {}
  [[nodiscard]] std::string_view name() const override { return "oracle"; }
  [[nodiscard]] std::optional<ExplorationGoal> choose(const ExplorationState& state) override;
  [[nodiscard]] bool needs_oracle() const override { return true; }

 private:
  PolicyOptions options_;
  std::optional<GridPathPlanner> planner_;
  NearestFrontierPolicy fallback_;
};

}  // namespace ferret
