#include "ferret/planning/exploration_policy.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>

#include "ferret/planning/policies.hpp"
#include "ferret/planning/viewpoint_search.hpp"

namespace ferret {
namespace {
struct Registry {
  std::mutex mutex;
  std::map<std::string, ExplorationPolicyFactory, std::less<>> factories;
};

Registry& registry() {
  static Registry* r = [] {
    auto* reg = new Registry;
    // The built-in table: one line a policy.
    reg->factories["cdos"] = [](const PolicyOptions& o) {
      return std::make_unique<CdosPolicy>(o, false);
    };
    reg->factories["cdos-literal"] = [](const PolicyOptions& o) {
      return std::make_unique<CdosPolicy>(o, true);
    };
    reg->factories["cdos-fg"] = [](PolicyOptions o) {  // CDOS scoring all of F_g
      o.cdos_candidates_global = true;
      return std::make_unique<CdosPolicy>(o, false, "cdos-fg");
    };
    reg->factories["cdos-closest"] = [](PolicyOptions o) {  // d_{t+1} at the closest approach
      o.curiosity.closest_approach = true;
      return std::make_unique<CdosPolicy>(o, false, "cdos-closest");
    };
    reg->factories["rapid"] = [](const PolicyOptions& o) {
      return std::make_unique<RapidFrontierPolicy>(o);
    };
    reg->factories["nearest"] = [](const PolicyOptions& o) {
      return std::make_unique<NearestFrontierPolicy>(o);
    };
    reg->factories["oracle"] = [](const PolicyOptions& o) {
      return std::make_unique<OraclePolicy>(o);
    };
    reg->factories["bayes"] = [](const PolicyOptions& o) {
      return std::make_unique<ViewpointSearchPolicy>(o);
    };
    return reg;
  }();
  return *r;
}
}  // namespace

PolicyOptions PolicyOptions::from(const MissionConfig& mission, double camera_range_m,
                                  double max_velocity_mps) {
  PolicyOptions o;
  o.curiosity = CuriosityOptions::from(mission, camera_range_m);
  o.max_velocity_mps = max_velocity_mps;
  o.view_distance_m = 0.9 * mission.object_search.eta_m / mission.object_search.lambda2;
  return o;
}

void register_exploration_policy(std::string name, ExplorationPolicyFactory factory) {
  auto& r = registry();
  std::lock_guard lock(r.mutex);
  r.factories[std::move(name)] = std::move(factory);
}

std::vector<std::string> exploration_policy_names() {
  auto& r = registry();
  std::lock_guard lock(r.mutex);
  std::vector<std::string> names;
  for (const auto& [name, factory] : r.factories) names.push_back(name);
  return names;
}

bool has_exploration_policy(std::string_view name) {
  auto& r = registry();
  std::lock_guard lock(r.mutex);
  return r.factories.find(name) != r.factories.end();
}

std::string policy_for_planner(std::string_view method, std::string_view planner) {
  if (planner == "grid") return std::string(method);
  if (planner != "ompl")
    throw std::invalid_argument("unknown planner: " + std::string(planner) + " (grid or ompl)");
  std::string ompl = std::string(method) + "+ompl";
  return has_exploration_policy(ompl) ? ompl : std::string(method);
}

std::unique_ptr<ExplorationPolicy> make_exploration_policy(std::string_view name,
                                                           const PolicyOptions& options) {
  ExplorationPolicyFactory factory;
  {
    auto& r = registry();
    std::lock_guard lock(r.mutex);
    const auto it = r.factories.find(name);
    if (it == r.factories.end())
      throw std::out_of_range("unknown exploration policy: " + std::string(name));
    factory = it->second;
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
