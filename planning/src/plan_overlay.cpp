#include "ferret/planning/plan_overlay.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "ferret/tether_model/taut_tether.hpp"

namespace ferret {

std::string PlanOverlaySummary::describe() const {
  std::string s = fmt::format("{} state{}, {:.1f} m", states, states == 1 ? "" : "s", length_m);
  if (tether_taut_m > 0)
    s += fmt::format(", tether {:.2f} m taut at the goal, {} wrap point{} ({} on the way)",
                     tether_taut_m, goal_wraps, goal_wraps == 1 ? "" : "s", wraps);
  if (outside) s += fmt::format("; {} of {} states outside the map", outside, states);
  return s;
}

PlanOverlaySummary draw_plan(MapCanvas& canvas, const PlanFile& plan,
                             const OccupancyMap2D& obstacles, const PlanOverlayStyle& style) {
  PlanOverlaySummary out;
  const auto inside = [&](const Eigen::Vector2d& p) { return canvas.contains(p); };
  std::vector<Eigen::Vector2d> path;
  path.reserve(plan.states.size());
  for (const Waypoint& w : plan.states) {
    path.emplace_back(w.x_m, w.y_m);
    out.outside += !inside(path.back());
    if (path.size() > 1) out.length_m += (path.back() - path[path.size() - 2]).norm();
  }
  out.states = path.size();
  if (path.empty()) return out;

  // The tether first, so that the path lies on top of it.
  if (plan.robot == PlanRobot::kUgv && plan.tether) {
    TautTether tether(TetherCorners::from_map(obstacles, false), plan.tether->p_WE,
                      plan.tether->initial_wraps, path.front());
    std::vector<Eigen::Vector2d> wraps;
    const auto note = [&] {
      for (const WrapPoint& w : tether.wrap_points())
        if (std::none_of(wraps.begin(), wraps.end(),
                         [&](const Eigen::Vector2d& q) { return (q - w.p_W).norm() < 1e-9; }))
          wraps.push_back(w.p_W);
    };
    note();
    for (const Eigen::Vector2d& p : path) {
      tether.move_to(p);
      note();
    }
    canvas.draw_path(tether.polyline(), style.tether, 2);
    for (const Eigen::Vector2d& w : wraps) canvas.draw_marker(w, style.wrap, LegendMark::kRing, 6);
    canvas.draw_marker(plan.tether->p_WE, style.entry, LegendMark::kDiamond, 8);
    out.wraps = wraps.size();
    out.goal_wraps = tether.wrap_points().size();
    out.tether_taut_m = tether.length_m();
    if (inside(plan.tether->p_WE))
      canvas.add_legend("tether entry E", style.entry, LegendMark::kDiamond);
    canvas.add_legend(fmt::format("tether at the goal ({:.2f} m taut)", tether.length_m()),
                      style.tether, LegendMark::kLine);
    if (!wraps.empty())
      canvas.add_legend(fmt::format("wrap points on the way ({})", wraps.size()), style.wrap,
                        LegendMark::kRing);
  }

  canvas.draw_path(path, style.path, 3);
  // Heading ticks at states at least tick_spacing_px apart along the path (and at both ends).
  const double px_per_m = canvas.to_pixel({1.0, 0.0}).x() - canvas.to_pixel({0.0, 0.0}).x();
  const double tick_m = 2.0 * style.tick_spacing_px / px_per_m;
  double since_m = 0.0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    if (k > 0) since_m += (path[k] - path[k - 1]).norm();
    if (k != 0 && k + 1 != path.size() && since_m * px_per_m < style.tick_spacing_px) continue;
    since_m = 0.0;
    const double yaw = plan.states[k].yaw_rad;
    canvas.draw_path(
        {path[k], path[k] + 0.6 * tick_m * Eigen::Vector2d(std::cos(yaw), std::sin(yaw))},
        style.path, 2);
  }
  canvas.draw_marker(path.front(), style.start, LegendMark::kDot, 7);
  canvas.draw_marker(path.back(), style.goal, LegendMark::kSquare, 6);
  canvas.add_legend("plan path (ticks: heading)", style.path, LegendMark::kLine);
  canvas.add_legend("start", style.start, LegendMark::kDot);
  canvas.add_legend("goal", style.goal, LegendMark::kSquare);
  return out;
}

}  // namespace ferret
