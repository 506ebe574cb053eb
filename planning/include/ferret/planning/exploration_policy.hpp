#pragma once
// Exploration policies of the object search: given the maps G and O, the frontier
// sets and the robot's state, choose the next goal. Every policy sees the same maps,
// sensors and motion; they differ only in the goal they choose. Built in:
//   cdos          curiosity-driven object search, the reading of ARCHITECTURE.md
//   cdos-literal  the paper's section IV read to the letter (for comparison)
//   cdos-fg       cdos scoring all of F_g instead of F_v
//   cdos-closest  cdos with d_{t+1} the closest approach on the straight drive to g
//   rapid         rapid frontier (Cieslewski et al. 2017), the paper's baseline
//   nearest       classic nearest reachable frontier (Yamauchi 1997)
//   oracle        knows the object; drives towards the nearest pose that sees it
//   bayes         Bayesian viewpoint search without evidence, CDOS with it
//                 (viewpoint_search.hpp)
// docs/object_search.md describes each. A new policy is one class plus one line in
// register_builtin_policies() (exploration_policy.cpp). The OMPL frontier planner
// (FrontierPlanner::kOmpl) runs cdos and rapid as the variants cdos+ompl and rapid+ompl.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/core/registry.hpp"
#include "ferret/mapping/frontier.hpp"
#include "ferret/mapping/ir_grid.hpp"
#include "ferret/mapping/object_map.hpp"
#include "ferret/planning/curiosity.hpp"
#include "ferret/planning/grid_path_planner.hpp"
#include "ferret/planning/mission_config.hpp"

namespace ferret {

/// How a policy's goals are chosen and reached: on the Dijkstra field over G, or by
/// PRM with the frontier valid-state sampler (frontier_sampler.hpp, docs/planning.md).
enum class FrontierPlanner { kGrid, kOmpl };

/// The rule that chose a goal (decision logs print to_string()).
enum class GoalRule {
  kNone,       ///< not said (viewing_goal() before its caller names it)
  kCuriosity,  ///< cdos: the largest curiosity loss
  kRapid,      ///< the least change of velocity
  kNearest,    ///< the nearest reachable frontier
  kOracle,     ///< towards the object the oracle knows
  kRevisit,    ///< the strongest evidence once exploration ended
  kEvidence,   ///< bayes: a view of the evidence
  kRecheck,    ///< bayes: the evidence again from another side
  kViewpoint,  ///< bayes: the viewpoint of most expected information
  kUnwind,     ///< the explore controller: back along the driven path to unwind the tether
};
/// "", "curiosity", "rapid", "nearest", "oracle", "revisit", "evidence", "recheck",
/// "viewpoint", "unwind".
[[nodiscard]] std::string_view to_string(GoalRule rule);

/// Why a goal was chosen: its rule and, for the OMPL frontier policies, how its path
/// was found (PRM: "+ompl"; the grid path where PRM found none: "+grid").
struct GoalReason {
  GoalReason() = default;
  GoalReason(GoalRule r,
             std::optional<FrontierPlanner> by = std::nullopt)  // NOLINT: a rule is a reason
      : rule(r), path_by(by) {}
  GoalRule rule = GoalRule::kNone;
  std::optional<FrontierPlanner> path_by;
  bool operator==(const GoalReason&) const = default;
};
/// "curiosity", "curiosity+ompl", "rapid+grid", ...
[[nodiscard]] std::string to_string(const GoalReason& reason);
/// For nlohmann::json (found by ADL): the reason as to_string() prints it.
template <class Json>
void to_json(Json& j, const GoalReason& reason) {
  j = to_string(reason);
}

struct ExplorationGoal {
  Cell cell;
  Eigen::Vector2d p_W = Eigen::Vector2d::Zero();
  std::optional<double> heading_rad;  ///< face this on arrival; none: any heading
  /// The path from the robot (world waypoints); empty: the caller plans it on the
  /// known-free field of ExplorationState::paths.
  std::vector<Eigen::Vector2d> path_W;
  double score = 0.0;  ///< the quantity the policy optimised (curiosity loss, velocity change, ...)
  GoalReason reason;
};

/// What a policy may look at when it decides.
struct ExplorationState {
  const IrGrid& grid;
  const ObjectMap& objects;
  const FrontierTracker& tracker;
  const FrontierSets& frontiers;
  const GridPathPlanner& paths;  ///< field from the robot over known-free cells
  Pose2 X_WG;                    ///< the robot (sensors are at its origin, facing its heading)
  Eigen::Vector2d v_W = Eigen::Vector2d::Zero();  ///< current velocity
  double ir_fov_rad = 0.5;
  double ir_range_m = 4.0;
  /// The object's true position: set by the simulator for policies that ask for it
  /// (needs_oracle()), and only for them.
  std::optional<Eigen::Vector2d> oracle_object_W;
  /// The tether's reach (empty: no tether): whether the robot may drive `path_W` (from
  /// where it is) to the goal `cell`. Policies that plan their own paths (the OMPL
  /// frontier policies) ask it of a goal before they choose it, as goal validity; the
  /// caller may remember a refusal (the explore controller blacklists the cell until
  /// the tether is unwound). The others leave the check to the caller.
  std::function<bool(Cell cell, const std::vector<Eigen::Vector2d>& path_W)> within_reach{};
  /// When set, fills `frontiers` the first time a policy asks for them (it must be
  /// harmless to call again): which frontier cells are reachable needs the whole path
  /// field, and a cycle that keeps its goal never asks (GridPathPlanner grows the field
  /// only as far as it is asked about).
  std::function<void()> fill_frontiers{};
  /// True while the robot has not yet moved the object map's min_move_m from where the
  /// search started (the explore controller knows; a caller that does not, leaves it
  /// false): the object map then holds the looks of that one pose only.
  bool at_entry = false;

  /// The frontier sets; policies read them through this, never `frontiers` directly.
  [[nodiscard]] const FrontierSets& frontier_sets() const {
    if (fill_frontiers) fill_frontiers();
    return frontiers;
  }
};

struct PolicyOptions {
  CuriosityOptions curiosity;
  double max_velocity_mps = 2.0;
  /// CDOS option: score F_g instead of F_v.
  bool cdos_candidates_global = false;
  /// Oracle and "revisit the evidence": a pose this close sees the object with
  /// conf = eta / d > lambda2 (0.9 eta / lambda2 by default).
  double view_distance_m = 0.95;
  /// The object camera's horizontal field of view (bayes: what a viewpoint sees).
  double camera_fov_rad = 1.5707963267948966;
  /// The robot's turn rate (bayes: the time a viewpoint's turns cost).
  double max_yaw_rate_radps = 2.0;
  /// The run's seed, for policies that draw random numbers (the OMPL frontier policies).
  std::uint64_t seed = 0;

  [[nodiscard]] static PolicyOptions from(const MissionConfig& mission, double camera_range_m,
                                          double max_velocity_mps);
};

class ExplorationPolicy {
 public:
  virtual ~ExplorationPolicy() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  /// The next goal, or none when nothing is left to explore.
  [[nodiscard]] virtual std::optional<ExplorationGoal> choose(const ExplorationState& state) = 0;
  /// True for the oracle: the simulator fills ExplorationState::oracle_object_W.
  [[nodiscard]] virtual bool needs_oracle() const { return false; }
  /// The last goal chosen was reached (or given up: unreachable, stuck). Policies that
  /// commit to a goal until then (Algorithm 1's "goto g*") release it here.
  virtual void goal_done() {}
  /// True if choose() would return the goal it returned last, judged from the maps
  /// alone (no path field): the caller may then skip the decision cycle. The default
  /// (false) asks for a full decision every cycle.
  [[nodiscard]] virtual bool keeps_goal(const ObjectMap& objects,
                                        const FrontierTracker& tracker) const {
    (void)objects;
    (void)tracker;
    return false;
  }
};

using ExplorationPolicyRegistry = Registry<ExplorationPolicy, PolicyOptions>;
using ExplorationPolicyFactory = ExplorationPolicyRegistry::Factory;

/// "grid", "ompl".
[[nodiscard]] std::string_view to_string(FrontierPlanner planner);
/// "grid" or "ompl". @throws InputError(source, field, "grid or ompl", text) otherwise.
[[nodiscard]] FrontierPlanner parse_frontier_planner(std::string_view text,
                                                     const std::string& source,
                                                     const std::string& field = {});

/// The exploration policies by name, and which of them runs a method with a frontier
/// planner other than the grid. A method's own policy is its grid policy (name ==
/// method); a variant is a policy of its own name (what runs.csv and the logs print)
/// that runs `method` with `planner`.
class ExplorationPolicies {
 public:
  /// A method: its policy runs on the grid.
  void add(std::string name, std::string description, ExplorationPolicyFactory factory);
  /// A policy `name` that runs `method` (added before) with `planner`.
  void add_variant(const std::string& method, FrontierPlanner planner, std::string name,
                   std::string description, ExplorationPolicyFactory factory);

  /// Every policy, methods and variants.
  [[nodiscard]] const ExplorationPolicyRegistry& registry() const { return registry_; }
  /// The methods (what --method and an experiment's `methods:` name), in the order added.
  [[nodiscard]] std::vector<std::string> methods() const;
  /// The policy that runs `method` with `planner`: the method itself on the grid (and
  /// a variant's name as given), else its variant for `planner`.
  /// @throws InputError("--method", ...) listing the methods for an unknown one, and
  /// InputError("--planner", ...) naming the methods the planner serves when `method`
  /// has no variant for it ("ompl: ...; nearest has none").
  [[nodiscard]] std::string policy_for(std::string_view method, FrontierPlanner planner) const;

 private:
  struct Variant {
    std::string method;
    FrontierPlanner planner;
    std::string policy;
  };
  ExplorationPolicyRegistry registry_;
  std::vector<Variant> variants_;
};

/// The built-in policies (exploration_policy.cpp): cdos, cdos-literal, ..., bayes.
void register_builtin_policies(ExplorationPolicies& policies);
/// The OMPL frontier policies (ompl_frontier_policy.cpp): cdos+ompl and rapid+ompl,
/// the variants of cdos and rapid with FrontierPlanner::kOmpl.
void register_ompl_frontier_policies(ExplorationPolicies& policies);

/// The policies of the search, filled on first use by the two calls above.
[[nodiscard]] const ExplorationPolicies& exploration_policies();

/// Adds a method under `name` to exploration_policies() (for tests and extensions;
/// before any search runs). @throws std::logic_error when the name is taken.
void register_exploration_policy(std::string name, ExplorationPolicyFactory factory);
/// The methods of exploration_policies(), in the order they were registered.
[[nodiscard]] std::vector<std::string> exploration_policy_names();
/// True for a registered policy, a method or a variant (cdos+ompl).
[[nodiscard]] bool has_exploration_policy(std::string_view name);
/// A new policy (a method or a variant by its name). @throws InputError("--method")
/// listing the methods for an unknown name.
[[nodiscard]] std::unique_ptr<ExplorationPolicy> make_exploration_policy(
    std::string_view name, const PolicyOptions& options);

/// exploration_policies().policy_for(method, planner): the one place that decides
/// which policy runs a method with a frontier planner (explore, experiment, the
/// mission's miniUGV).
[[nodiscard]] std::string exploration_policy_for(std::string_view method, FrontierPlanner planner);

/// A goal from which the camera sees `target_W`: the reachable cell within
/// `view_distance_m` of it (with a line of sight through non-occupied cells of G) of
/// least path distance in `paths`, facing the target. Used by the oracle and to
/// revisit evidence when exploration ends. None if no such cell is reachable.
[[nodiscard]] std::optional<ExplorationGoal> viewing_goal(const IrGrid& grid,
                                                          const FrontierTracker& tracker,
                                                          const GridPathPlanner& paths,
                                                          const Eigen::Vector2d& target_W,
                                                          double view_distance_m);

}  // namespace ferret
