#include "ferret/planning/plan_overlay.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "ferret/tether_model/taut_tether.hpp"

namespace ferret {
namespace {

// The world rectangle the canvas's map area shows, widened by `margin_px` (from its
// affine world-to-pixel map, so any scale and flip).
struct WorldBox {
  Eigen::Vector2d lo, hi;
};
WorldBox visible_box(const MapCanvas& canvas, double margin_px) {
  const Eigen::Vector2d o = canvas.to_pixel({0.0, 0.0});
  Eigen::Matrix2d A;
  A.col(0) = canvas.to_pixel({1.0, 0.0}) - o;
  A.col(1) = canvas.to_pixel({0.0, 1.0}) - o;
  const PixelRect r = canvas.map_area();
  const Eigen::Matrix2d inv = A.inverse();
  const Eigen::Vector2d a = inv * (Eigen::Vector2d(r.x - margin_px, r.y - margin_px) - o);
  const Eigen::Vector2d b =
      inv * (Eigen::Vector2d(r.x + r.width + margin_px, r.y + r.height + margin_px) - o);
  return {a.cwiseMin(b), a.cwiseMax(b)};
}

// Liang-Barsky: the part of a -> b inside the box, if any.
std::optional<std::pair<Eigen::Vector2d, Eigen::Vector2d>> clip(const Eigen::Vector2d& a,
                                                                const Eigen::Vector2d& b,
                                                                const WorldBox& box) {
  double t0 = 0.0, t1 = 1.0;
  const Eigen::Vector2d d = b - a;
  for (int axis = 0; axis < 2; ++axis) {
    for (const double sign : {-1.0, 1.0}) {
      const double p = sign * d[axis];
      const double q = sign > 0 ? box.hi[axis] - a[axis] : a[axis] - box.lo[axis];
      if (p == 0.0) {
        if (q < 0.0) return std::nullopt;
        continue;
      }
      const double t = q / p;
      if (p < 0.0)
        t0 = std::max(t0, t);
      else
        t1 = std::min(t1, t);
      if (t0 > t1) return std::nullopt;
    }
  }
  return std::make_pair(Eigen::Vector2d(a + t0 * d), Eigen::Vector2d(a + t1 * d));
}

// A polyline drawn only where it can be seen: the drawing's work is bounded by the
// picture, not by how far off the map a plan's segment runs (a line's cost grows with
// its length in pixels).
void draw_visible_path(MapCanvas& canvas, const std::vector<Eigen::Vector2d>& points, Rgb color,
                       int thickness_px) {
  if (points.size() < 2) {
    if (!points.empty() && canvas.contains(points[0]))
      canvas.draw_path(points, color, thickness_px);
    return;
  }
  const WorldBox box = visible_box(canvas, 4.0 * thickness_px + 8.0);
  std::vector<Eigen::Vector2d> run;  // consecutive visible segments, drawn as one path
  const auto flush = [&] {
    if (run.size() >= 2) canvas.draw_path(run, color, thickness_px);
    run.clear();
  };
  for (std::size_t k = 1; k < points.size(); ++k) {
    const auto part = clip(points[k - 1], points[k], box);
    if (!part) {
      flush();
      continue;
    }
    if (run.empty() || part->first != run.back()) {
      flush();
      run.push_back(part->first);
    }
    run.push_back(part->second);
    if (part->second != points[k]) flush();  // it left the picture
  }
  flush();
}

}  // namespace

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
    draw_visible_path(canvas, tether.polyline(), style.tether, 2);
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

  draw_visible_path(canvas, path, style.path, 3);
  // Heading ticks at states at least tick_spacing_px apart along the path (and at both ends).
  const double px_per_m = canvas.to_pixel({1.0, 0.0}).x() - canvas.to_pixel({0.0, 0.0}).x();
  const double tick_m = 2.0 * style.tick_spacing_px / px_per_m;
  double since_m = 0.0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    if (k > 0) since_m += (path[k] - path[k - 1]).norm();
    if (k != 0 && k + 1 != path.size() && since_m * px_per_m < style.tick_spacing_px) continue;
    since_m = 0.0;
    if (!canvas.contains(path[k], tick_m)) continue;  // a tick off the map is not seen
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
