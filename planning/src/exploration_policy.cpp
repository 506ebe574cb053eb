#include "ferret/planning/exploration_policy.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>

#include "ferret/core/error.hpp"
#include "ferret/planning/policies.hpp"
#include "ferret/planning/viewpoint_search.hpp"

namespace ferret {

void register_builtin_policies(ExplorationPolicies& p) {
  p.add("cdos", "curiosity-driven object search",
        [](const PolicyOptions& o) { return std::make_unique<CdosPolicy>(o, false); });
  p.add("cdos-literal", "the paper's section IV read to the letter",
        [](const PolicyOptions& o) { return std::make_unique<CdosPolicy>(o, true); });
  p.add("cdos-fg", "cdos scoring all of F_g", [](PolicyOptions o) {
    o.cdos_candidates_global = true;
    return std::make_unique<CdosPolicy>(o, false, "cdos-fg");
  });
  p.add("cdos-closest", "cdos with d_{t+1} at the closest approach", [](PolicyOptions o) {
    o.curiosity.closest_approach = true;
    return std::make_unique<CdosPolicy>(o, false, "cdos-closest");
  });
  p.add("rapid", "rapid frontier (Cieslewski et al. 2017)",
        [](const PolicyOptions& o) { return std::make_unique<RapidFrontierPolicy>(o); });
  p.add("nearest", "nearest reachable frontier (Yamauchi 1997)",
        [](const PolicyOptions& o) { return std::make_unique<NearestFrontierPolicy>(o); });
  p.add("oracle", "knows the object, drives to the nearest pose that sees it",
        [](const PolicyOptions& o) { return std::make_unique<OraclePolicy>(o); });
  p.add("bayes", "Bayesian viewpoint search",
        [](const PolicyOptions& o) { return std::make_unique<ViewpointSearchPolicy>(o); });
}

namespace {

// The registry a process uses: filled by the registration calls the first time it is
// asked for (explicit calls: a static build keeps them), then only read, but for
// register_exploration_policy (tests) under the mutex.
struct Global {
  std::mutex mutex;
  ExplorationPolicies policies;
};

Global& global() {
  static Global* g = [] {
    auto* r = new Global;
    register_builtin_policies(r->policies);
    register_ompl_frontier_policies(r->policies);
    return r;
  }();
  return *g;
}

}  // namespace

std::string_view to_string(FrontierPlanner planner) {
  switch (planner) {
    case FrontierPlanner::kGrid:
      return "grid";
    case FrontierPlanner::kOmpl:
      return "ompl";
  }
  return "grid";
}

std::string_view to_string(GoalRule rule) {
  switch (rule) {
    case GoalRule::kNone:
      return "";
    case GoalRule::kCuriosity:
      return "curiosity";
    case GoalRule::kRapid:
      return "rapid";
    case GoalRule::kNearest:
      return "nearest";
    case GoalRule::kOracle:
      return "oracle";
    case GoalRule::kRevisit:
      return "revisit";
    case GoalRule::kEvidence:
      return "evidence";
    case GoalRule::kRecheck:
      return "recheck";
    case GoalRule::kViewpoint:
      return "viewpoint";
    case GoalRule::kUnwind:
      return "unwind";
  }
  return "";
}

std::string to_string(const GoalReason& reason) {
  std::string text(to_string(reason.rule));
  if (reason.path_by) {
    text.push_back('+');
    text.append(to_string(*reason.path_by));
  }
  return text;
}

FrontierPlanner parse_frontier_planner(std::string_view text, const std::string& source,
                                       const std::string& field) {
  for (const auto p : {FrontierPlanner::kGrid, FrontierPlanner::kOmpl})
    if (text == to_string(p)) return p;
  throw InputError(source, field, "grid or ompl", std::string(text));
}

void ExplorationPolicies::add(std::string name, std::string description,
                              ExplorationPolicyFactory factory) {
  registry_.add(std::move(name), std::move(description), std::move(factory));
}

void ExplorationPolicies::add_variant(const std::string& method, FrontierPlanner planner,
                                      std::string name, std::string description,
                                      ExplorationPolicyFactory factory) {
  if (!registry_.contains(method) || planner == FrontierPlanner::kGrid)
    throw std::logic_error("exploration policy " + name + ": a variant of an unknown method " +
                           method);
  variants_.push_back({method, planner, name});
  registry_.add(std::move(name), std::move(description), std::move(factory));
}

std::vector<std::string> ExplorationPolicies::methods() const {
  std::vector<std::string> names;
  for (const auto& e : registry_.entries())
    if (std::none_of(variants_.begin(), variants_.end(),
                     [&](const Variant& v) { return v.policy == e.name; }))
      names.push_back(e.name);
  return names;
}

std::string ExplorationPolicies::policy_for(std::string_view method,
                                            FrontierPlanner planner) const {
  if (!registry_.contains(method))
    throw InputError("--method", "", fmt::format("one of {}", fmt::join(methods(), ", ")),
                     std::string(method));
  // A variant named as it is runs as it is: its name fixes its planner.
  for (const auto& v : variants_)
    if (v.policy == method) return v.policy;
  if (planner == FrontierPlanner::kGrid) return std::string(method);
  std::vector<std::string> served;
  for (const auto& v : variants_) {
    if (v.planner != planner) continue;
    if (v.method == method) return v.policy;
    served.push_back(v.method);
  }
  throw InputError(
      "--planner", "",
      fmt::format("grid, or {} with a method its frontier sampler serves ({}); {} has none",
                  to_string(planner), fmt::join(served, ", "), method),
      std::string(to_string(planner)));
}

PolicyOptions PolicyOptions::from(const MissionConfig& mission, double camera_range_m,
                                  double max_velocity_mps) {
  PolicyOptions o;
  o.curiosity = CuriosityOptions::from(mission, camera_range_m);
  o.max_velocity_mps = max_velocity_mps;
  o.view_distance_m = 0.9 * mission.object_search.eta_m / mission.object_search.lambda2;
  return o;
}

const ExplorationPolicies& exploration_policies() { return global().policies; }

void register_exploration_policy(std::string name, ExplorationPolicyFactory factory) {
  auto& g = global();
  std::lock_guard lock(g.mutex);
  g.policies.add(std::move(name), "", std::move(factory));
}

std::vector<std::string> exploration_policy_names() {
  auto& g = global();
  std::lock_guard lock(g.mutex);
  return g.policies.methods();
}

bool has_exploration_policy(std::string_view name) {
  auto& g = global();
  std::lock_guard lock(g.mutex);
  return g.policies.registry().contains(name);
}

std::string exploration_policy_for(std::string_view method, FrontierPlanner planner) {
  auto& g = global();
  std::lock_guard lock(g.mutex);
  return g.policies.policy_for(method, planner);
}

std::unique_ptr<ExplorationPolicy> make_exploration_policy(std::string_view name,
                                                           const PolicyOptions& options) {
  ExplorationPolicyFactory factory;
  {
    auto& g = global();
    std::lock_guard lock(g.mutex);
    const auto* entry = g.policies.registry().find(name);
    if (entry == nullptr)
      throw InputError("--method", "",
                       fmt::format("one of {}", fmt::join(g.policies.methods(), ", ")),
                       std::string(name));
    factory = entry->factory;
  }
  return factory(options);
}

std::optional<ExplorationGoal> viewing_goal(const IrGrid& grid, const FrontierTracker& tracker,
                                            const GridPathPlanner& paths,
                                            const Eigen::Vector2d& target_W,
                                            double view_distance_m) {
  const GridGeometry& g = grid.geometry();
  const Cell t = g.cell_at(target_W.x(), target_W.y());
  const int r = static_cast<int>(std::ceil(view_distance_m / g.resolution_m));
  std::optional<Cell> best;
  float best_d = kUnreachable;
  for (int dj = -r; dj <= r; ++dj)
    for (int di = -r; di <= r; ++di) {
      const Cell c{t.i + di, t.j + dj};
      if (!g.contains(c) || tracker.blacklisted(c)) continue;
      const Eigen::Vector2d p = g.center(c);
      if ((p - target_W).norm() > view_distance_m) continue;
      const float d = paths.distance_m(c);
      if (!(d < best_d)) continue;
      bool sight = true;
      trace_ray(g, p, target_W, [&](Cell k, double) {
        sight = grid.label(k) != GridLabel::kOccupied;
        return sight;
      });
      if (!sight) continue;
      best = c;
      best_d = d;
    }
  if (!best) return std::nullopt;
  ExplorationGoal goal;
  goal.cell = *best;
  goal.p_W = g.center(*best);
  const Eigen::Vector2d to_target = target_W - goal.p_W;
  if (to_target.norm() > 1e-6) goal.heading_rad = std::atan2(to_target.y(), to_target.x());
  goal.score = best_d;
  return goal;
}

}  // namespace ferret
