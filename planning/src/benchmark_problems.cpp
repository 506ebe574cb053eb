#include "ferret/planning/benchmark_problems.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"

namespace ferret {
namespace {
// Rejection sampling gives up after this many draws: a world with (almost) no free
// space must end in an error, not in a loop.
constexpr int kMaxDraws = 100000;
}  // namespace

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
    int draws = 0;
    do {
      if (++draws > kMaxDraws)
        throw InputError(world.name, "bounds", "free space for the UAV inside the geofence",
                         fmt::format("no free pose in {} draws", kMaxDraws));
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
  // A space smaller than the distance asked for gets problems across half its diagonal.
  const double distance_m = std::min(min_distance_m, 0.5 * (f.hi_m - f.lo_m).head<2>().norm());
  int draws = 0;
  auto draw = [&] {
    for (;;) {
      if (++draws > kMaxDraws)
        throw InputError("hidden space", "interior",
                         fmt::format("{} start/goal pairs of free miniUGV poses {:.2f} m apart",
                                     count, distance_m),
                         fmt::format("none found in {} draws", kMaxDraws));
      const Pose2 p{rng.uniform(f.lo_m.x(), f.hi_m.x()), rng.uniform(f.lo_m.y(), f.hi_m.y()),
                    rng.uniform(-3.14159, 3.14159)};
      if (!planner.checker().in_collision(planner.waypoint(p).pose())) return planner.waypoint(p);
    }
  };
  std::vector<PlanningProblem> out;
  while (static_cast<int>(out.size()) < count) {
    const Waypoint a = draw(), b = draw();
    if (std::hypot(a.x_m - b.x_m, a.y_m - b.y_m) >= distance_m) out.push_back({a, b});
  }
  return out;
}

}  // namespace ferret
