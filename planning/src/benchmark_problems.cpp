#include "ferret/planning/benchmark_problems.hpp"

#include <cmath>

#include "ferret/core/random.hpp"

namespace ferret {

std::vector<PlanningProblem> uav_approach_problems(const WorldSpec& world,
                                                   CollisionChecker& checker, const Aabb3& fence,
                                                   int count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Waypoint> goals;
  for (const HiddenSpace& h : world.hidden_spaces) {
    for (double standoff = 1.0; standoff < 10.0; standoff += 0.25) {
      const Waypoint g = approach_hover_pose(h, standoff);
      if (fence.contains(g.position()) && !checker.in_collision(g.pose())) {
        goals.push_back(g);
        break;
      }
    }
  }
  std::vector<PlanningProblem> out;
  if (goals.empty()) return out;
  for (int k = 0; k < count; ++k) {
    Waypoint s;
    do {
      s.x_m = rng.uniform(fence.lo.x(), fence.hi.x());
      s.y_m = rng.uniform(fence.lo.y(), fence.hi.y());
      s.z_m = rng.uniform(fence.lo.z(), fence.hi.z());
      s.yaw_rad = rng.uniform(-3.14159, 3.14159);
    } while (checker.in_collision(s.pose()));
    out.push_back({s, goals[static_cast<std::size_t>(k) % goals.size()]});
  }
  return out;
}

std::vector<PlanningProblem> ugv_problems(UgvPlanner& planner, int count, std::uint64_t seed,
                                          double min_distance_m) {
  Rng rng(seed);
  const HiddenSpaceFrame& f = planner.space();
  auto draw = [&] {
    for (;;) {
      const Pose2 p{rng.uniform(f.lo_m.x(), f.hi_m.x()), rng.uniform(f.lo_m.y(), f.hi_m.y()),
                    rng.uniform(-3.14159, 3.14159)};
      if (!planner.checker().in_collision(planner.waypoint(p).pose())) return planner.waypoint(p);
    }
  };
  std::vector<PlanningProblem> out;
  while (static_cast<int>(out.size()) < count) {
    const Waypoint a = draw(), b = draw();
    if (std::hypot(a.x_m - b.x_m, a.y_m - b.y_m) >= min_distance_m) out.push_back({a, b});
  }
  return out;
}

}  // namespace ferret
