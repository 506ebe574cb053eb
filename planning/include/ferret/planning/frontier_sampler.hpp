#pragma once
// CDOS as an OMPL frontier valid-state sampler (an OMPL extension point, so OMPL
// types appear here). The sampler draws miniUGV states (SE2) at frontier cells of
// the IR grid G, each cell chosen in proportion to its weight: for `cdos` the
// curiosity loss of the candidate (F_v first, F_g when F_v is empty; the rapid rule
// where no cell has object evidence, as the CDOS policy does), for `rapid` a weight
// that falls with the change of velocity the candidate asks (F_v) or its path
// distance (F_g). A FrontierGoal region offers the candidates as goals, best-weighted
// first, and judges a goal's path against the tether's reach.
//
// OMPL 1.5 calls a custom valid-state sampler only from planners that ask the
// SpaceInformation for one (PRM, LazyPRM, SPARS, EST, BKPIECE1, SBL, STRIDE); RRT,
// RRTConnect, RRT* and FMT ignore it (ompl#810). samples_drawn() lets a test prove
// the sampler was called.

#include <ompl/base/ValidStateSampler.h>
#include <ompl/base/goals/GoalSampleableRegion.h>

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/random.hpp"
#include "ferret/planning/exploration_policy.hpp"

namespace ferret {

/// Frontier cells with sampling weights.
struct FrontierCandidates {
  GridGeometry geometry;
  std::vector<Cell> cells;
  std::vector<double> weights;     ///< > 0, same length as cells
  std::vector<double> cumulative;  ///< prefix sums of weights (for drawing)
  /// Candidate indices, heaviest first (ties in the cells' order); the constructors
  /// below put the grid policy's choice first.
  std::vector<std::size_t> order;
  GoalRule rule = GoalRule::kNone;  ///< what set the weights: curiosity, rapid or nearest

  /// Sets `cumulative`, `order` and the cell index; `first` (if any) heads `order`
  /// (the grid policy's own choice, so that near-ties resolve as there).
  void finalize(std::optional<std::size_t> first = std::nullopt);
  [[nodiscard]] bool empty() const { return cells.empty(); }
  /// Index drawn in proportion to the weights. @pre !empty()
  [[nodiscard]] std::size_t draw(Rng& rng) const;
  /// The candidate whose cell holds (x, y), or -1.
  [[nodiscard]] int find(double x_m, double y_m) const;

 private:
  std::vector<int> by_cell_;  ///< grid index -> candidate index or -1
};

/// CDOS weights: curiosity loss over F_v (F_g with `global`), sharpened so the largest
/// loss dominates, the cdos policy's goal first in `order`; the rapid weights where the losses are
/// all zero or there is no candidate (with F_v empty: the nearest F_g cell first, Algorithm 1).
[[nodiscard]] FrontierCandidates cdos_candidates(const ExplorationState& state,
                                                 const CuriosityOptions& options,
                                                 double max_velocity_mps = 2.0,
                                                 bool global = false);
/// Rapid weights: exp(-|v_max u(g) - v| / (0.25 v_max)) over F_v, the rapid policy's
/// goal first in `order`; where F_v is empty, exp(-path distance / 1 m) over F_g
/// (nearest first).
[[nodiscard]] FrontierCandidates rapid_candidates(const ExplorationState& state,
                                                  double max_velocity_mps);

class FrontierValidStateSampler : public ompl::base::ValidStateSampler {
 public:
  FrontierValidStateSampler(const ompl::base::SpaceInformation* si,
                            std::shared_ptr<const FrontierCandidates> candidates,
                            std::uint64_t seed,
                            std::shared_ptr<std::atomic<std::size_t>> counter = nullptr);
  /// A valid state at a frontier cell drawn by weight (uniform inside the cell, any
  /// heading); false after `attempts_` invalid draws.
  bool sample(ompl::base::State* state) override;
  /// A valid frontier state within `distance` of `near`, by weight among those cells.
  bool sampleNear(ompl::base::State* state, const ompl::base::State* near,
                  double distance) override;

 private:
  bool fill(ompl::base::State* state, std::size_t k);
  std::shared_ptr<const FrontierCandidates> candidates_;
  Rng rng_;
  std::shared_ptr<std::atomic<std::size_t>> counter_;
};

/// The allocator to register with SpaceInformation::setValidStateSamplerAllocator.
/// `counter` (optional) counts the states the samplers drew.
[[nodiscard]] ompl::base::ValidStateSamplerAllocator frontier_sampler_allocator(
    std::shared_ptr<const FrontierCandidates> candidates, std::uint64_t seed,
    std::shared_ptr<std::atomic<std::size_t>> counter = nullptr);

/// The goal of a frontier plan: any state on a candidate cell. Goals are offered
/// heaviest first (the k-th sample is the k-th best candidate), so a planner that
/// connects goals as they come, as PRM does, connects the best ones first. A goal is
/// valid for a path only within the tether's reach (`within_reach`, if set): the
/// planner asks path_within_reach() before it returns a path.
class FrontierGoal : public ompl::base::GoalSampleableRegion {
 public:
  using Reach = std::function<bool(Cell, const std::vector<Eigen::Vector2d>&)>;
  FrontierGoal(const ompl::base::SpaceInformationPtr& si,
               std::shared_ptr<const FrontierCandidates> candidates, Reach within_reach = {});
  double distanceGoal(const ompl::base::State* state) const override;
  void sampleGoal(ompl::base::State* state) const override;
  unsigned int maxSampleCount() const override;
  /// Whether the robot may drive `path_W` to its last point's candidate (the tether).
  [[nodiscard]] bool path_within_reach(const std::vector<Eigen::Vector2d>& path_W) const;

 private:
  std::shared_ptr<const FrontierCandidates> candidates_;
  Reach within_reach_;
  mutable std::size_t next_ = 0;
};

/// Where an OMPL frontier plan took the robot.
struct FrontierPlan {
  bool solved = false;
  std::vector<Eigen::Vector2d> path_W;  ///< from the robot to the frontier
  Cell goal;
  double planning_time_s = 0.0;
  std::size_t samples_drawn = 0;           ///< by the frontier sampler
  std::size_t out_of_reach = 0;            ///< connected goals refused for the tether's reach
  std::vector<Eigen::Vector2d> roadmap_W;  ///< every roadmap state (figures, tests)
};

/// The work one frontier plan may do. PRM runs in rounds: a grow batch (states from
/// the frontier sampler), the next goal state (best-weighted first) with, if
/// `seed_grid_paths`, the waypoints of G's shortest path to it (the grid's free-space
/// structure: corridors and doorways a sampler finds only by luck), optionally an
/// expand batch (random bounces from poorly connected roadmap states), and a solution
/// check after each: the best-weighted goal connected to the start whose path is within
/// the tether's reach. The plan ends on this budget, so it depends only on the seed;
/// the wall-time cap is a safety net a plan does not reach in normal use.
struct FrontierPlanBudget {
  std::size_t rounds = 12;
  std::size_t grow_milestones = 8;  ///< new roadmap states per grow batch...
  std::size_t grow_draws = 160;     ///< ...or this many sampler draws, whichever first
  std::size_t expand_bounces = 0;   ///< random-bounce expansions per round
  bool seed_grid_paths = true;      ///< add G's shortest path to each goal as it comes
  double safety_cap_s = 5.0;
};

/// Plans with PRM (which calls the frontier sampler) from the robot to a frontier
/// over G's known-free, clear cells (within `escape_radius_m` of the robot, known free
/// suffices, so a robot next to a wall can leave it). The goal is the best-weighted
/// candidate PRM connects whose path (shortened by line of sight) passes
/// state.within_reach. Single-threaded and seeded through and through (PRM's
/// generator, the SE2 sampler, the frontier sampler): the same state, candidates and
/// seed give the same plan in any thread.
[[nodiscard]] FrontierPlan plan_to_frontier(const ExplorationState& state,
                                            std::shared_ptr<const FrontierCandidates> candidates,
                                            const FrontierPlanBudget& budget, std::uint64_t seed,
                                            double escape_radius_m = 1.0);

}  // namespace ferret
