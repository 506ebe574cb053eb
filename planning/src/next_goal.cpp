#include "ferret/planning/next_goal.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "ferret/core/error.hpp"
#include "ferret/mapping/frontier.hpp"
#include "ferret/mapping/ir_grid.hpp"
#include "ferret/mapping/object_map.hpp"
#include "ferret/planning/grid_path_planner.hpp"

namespace ferret {
namespace {
constexpr const char* kSource = "NextGoalRequest";
}  // namespace

std::optional<ExplorationGoal> next_exploration_goal(const NextGoalRequest& r) {
  const GridGeometry& g = r.geometry;
  if (!(std::isfinite(g.resolution_m) && g.resolution_m >= 0.005 && g.resolution_m <= 10.0))
    throw InputError(kSource, "resolution_m", "metres in [0.005, 10]",
                     fmt::format("{}", g.resolution_m));
  if (g.width < 1 || g.height < 1 || g.width > 4096 || g.height > 4096)
    throw InputError(kSource, "width", "a grid of 1 to 4096 cells a side",
                     fmt::format("{} x {}", g.width, g.height));
  if (!(std::isfinite(g.origin_x_m) && std::isfinite(g.origin_y_m) &&
        std::abs(g.origin_x_m) < 1e6 && std::abs(g.origin_y_m) < 1e6))
    throw InputError(kSource, "origin", "a finite origin within 1000 km");
  if (r.occupancy.size() != g.size())
    throw InputError(kSource, "occupancy", fmt::format("{} cells (width x height)", g.size()),
                     std::to_string(r.occupancy.size()));
  if (!r.object_probability.empty() && r.object_probability.size() != g.size())
    throw InputError(kSource, "object_probability", fmt::format("{} cells, or none", g.size()),
                     std::to_string(r.object_probability.size()));
  if (!r.object_confidence.empty() && r.object_confidence.size() != g.size())
    throw InputError(kSource, "object_confidence", fmt::format("{} cells, or none", g.size()),
                     std::to_string(r.object_confidence.size()));
  if (!(std::isfinite(r.pose.x_m) && std::isfinite(r.pose.y_m) && std::isfinite(r.pose.yaw_rad)))
    throw InputError(kSource, "pose", "a finite pose x, y, yaw");
  const Cell robot = g.cell_at(r.pose.x_m, r.pose.y_m);
  if (!g.contains(robot)) throw InputError(kSource, "pose", "a pose inside the grid");
  if (!r.velocity_W.allFinite()) throw InputError(kSource, "velocity", "a finite velocity");
  if (!has_exploration_policy(r.method))
    throw InputError(kSource, "method",
                     fmt::format("one of {}", fmt::join(exploration_policy_names(), ", ")),
                     r.method);

  PolicyOptions popt =
      PolicyOptions::from(r.mission, r.camera_range_m, r.mission.ugv_limits.max_velocity_mps);
  popt.seed = r.seed;
  auto policy = make_exploration_policy(r.method, popt);
  if (policy->needs_oracle())
    throw InputError(kSource, "method", "a policy that does not need to know the object", r.method);

  IrGrid::Options gopt;
  gopt.clearance_m = r.clearance_m;
  IrGrid grid(g, gopt);
  ObjectMap objects(g, ObjectMap::Options::from(r.mission.object_search, r.camera_range_m));
  for (std::size_t k = 0; k < g.size(); ++k) {
    const float p = r.occupancy[k];
    if (!(std::isfinite(p) && p <= 1.0f))
      throw InputError(kSource, fmt::format("occupancy[{}]", k),
                       "a probability in [0, 1], or < 0 for unknown", fmt::format("{}", p));
    if (p >= 0.0f) grid.set_probability(g.cell_of_index(k), p);
    if (!r.object_probability.empty()) {
      const float q = r.object_probability[k];
      if (!(std::isfinite(q) && q >= 0.0f && q <= 1.0f))
        throw InputError(kSource, fmt::format("object_probability[{}]", k),
                         "a probability in [0, 1]", fmt::format("{}", q));
      // One detection of confidence q from the prior 0.5 gives q (paper eq. (p_o_update)).
      double conf = q > 0.5f ? std::min<double>(q, objects.options().conf_cap) : 0.0;
      if (!r.object_confidence.empty()) {
        const float c = r.object_confidence[k];
        if (!(std::isfinite(c) && c >= 0.0f && c <= 1.0f))
          throw InputError(kSource, fmt::format("object_confidence[{}]", k),
                           "a confidence in [0, 1]", fmt::format("{}", c));
        conf = c;
      }
      if (q != 0.5f || conf > 0.0) objects.set_cell(g.cell_of_index(k), q, conf);
    }
  }
  (void)grid.take_changed_cells();
  FrontierTracker tracker(g);
  tracker.rebuild(grid);
  GridPathPlanner paths(g);
  // Cells near the robot may be crossed though close to a wall (as the search loop does).
  paths.compute(grid, robot, GridPathPlanner::Traversal::kKnownFree,
                r.clearance_m + 2 * g.resolution_m);
  const FrontierSets sets =
      tracker.extract(paths.distances_m(), r.pose, r.ir_fov_rad, r.ir_range_m);
  const ExplorationState state{grid,   objects,      tracker,      sets,         paths,
                               r.pose, r.velocity_W, r.ir_fov_rad, r.ir_range_m, std::nullopt};
  std::optional<ExplorationGoal> goal = policy->choose(state);
  if (goal && goal->path_W.empty()) goal->path_W = paths.path_to(goal->cell);
  return goal;
}

}  // namespace ferret
