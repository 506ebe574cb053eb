#pragma once
// Seeded planning problems for the benchmarks (bench/planning_bench.cpp) and
// `ferret bench-plan`: UAV approaches to hover poses by hidden-space openings, and
// miniUGV start/goal pairs inside a hidden space. Both only draw collision-free
// endpoints, so every problem is posed fairly; solvability is the planner's job.

#include <cstdint>
#include <utility>
#include <vector>

#include "ferret/mapping/world_spec.hpp"
#include "ferret/planning/collision_checker.hpp"
#include "ferret/planning/motion_check.hpp"
#include "ferret/planning/planning_world.hpp"  // approach_hover_pose
#include "ferret/planning/ugv_planner.hpp"

namespace ferret {

struct PlanningProblem {
  Waypoint start;
  Waypoint goal;
};

/// `count` UAV approaches: random free starts inside `fence` (at its altitudes),
/// goals cycling over the world's hidden spaces. Goals in collision are moved out
/// along the opening's normal until free.
[[nodiscard]] std::vector<PlanningProblem> uav_approach_problems(const WorldSpec& world,
                                                                 CollisionChecker& checker,
                                                                 const Aabb3& fence, int count,
                                                                 std::uint64_t seed);

/// `count` miniUGV start/goal pairs, free and at least `min_distance_m` apart (half the
/// space's diagonal in a smaller space). InputError when rejection sampling finds none.
[[nodiscard]] std::vector<PlanningProblem> ugv_problems(UgvPlanner& planner, int count,
                                                        std::uint64_t seed,
                                                        double min_distance_m = 3.0);

}  // namespace ferret
