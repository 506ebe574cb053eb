#include "ferret/planning/plan_validation.hpp"

#include <cmath>
#include <sstream>

#include "ferret/planning/ugv_planner.hpp"
#include "ferret/planning/uav_planner.hpp"

namespace ferret {
namespace {
std::string fmt_number(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}
}  // namespace

CheckResolution default_resolution(PlanRobot robot) {
  return robot == PlanRobot::kUgv ? UgvPlannerOptions{}.resolution : UavPlannerOptions{}.resolution;
}

std::optional<Violation> validate_plan(const PlanFile& plan, CollisionChecker& exact,
                                       const std::shared_ptr<const TetherCorners>& corners,
                                       const ValidationOptions& options) {
  const auto& states = plan.states;
  auto violation = [&](std::size_t k, const Waypoint& w, std::string reason) {
    return Violation{k, w.t_s, w.position(), std::move(reason)};
  };
  // Tether: replayed along the plan from its initial wrap points.
  std::optional<TautTether> tether;
  double tether_max = std::numeric_limits<double>::infinity();
  if (plan.robot == PlanRobot::kUgv) {
    Eigen::Vector2d entry;
    if (plan.tether) {
      entry = plan.tether->p_WE;
      tether_max = plan.tether->total_length_m - plan.tether->entry_offset_m;
    } else if (options.p_WE) {
      entry = *options.p_WE;
    } else {
      return violation(0, states.front(), "no tether entry point (the plan has no tether section; pass --entry)");
    }
    if (options.tether_max_m) tether_max = *options.tether_max_m;
    // The tether as it lay at the start: bent at the recorded wrap points.
    tether.emplace(corners, entry, plan.tether ? plan.tether->initial_wraps : std::vector<WrapPoint>{},
                   Eigen::Vector2d(states.front().x_m, states.front().y_m));
  }
  for (std::size_t k = 0; k < states.size(); ++k) {
    const Waypoint& w = states[k];
    if (options.geofence && !options.geofence->contains(w.position()))
      return violation(k, w, "outside the geofence");
    if (k > 0) {
      const Waypoint& p = states[k - 1];
      const double dt = w.t_s - p.t_s;
      const double dp = (w.position() - p.position()).norm();
      const double dyaw = std::abs(wrap_angle_rad(w.yaw_rad - p.yaw_rad));
      const bool moves = dp > 1e-12 || dyaw > 1e-12;
      if (dt < 0 || (moves && dt <= 0)) return violation(k, w, "time does not increase");
      if (moves) {
        // A relative tolerance: time stamps written with rounding are not violations.
        if (dp / dt > options.max_velocity_mps * (1 + 1e-6))
          return violation(k, w, "too fast: " + fmt_number(dp / dt) + " m/s > " +
                                     fmt_number(options.max_velocity_mps) + " m/s");
        if (dyaw / dt > options.max_yaw_rate_radps * (1 + 1e-6))
          return violation(k, w, "yaw rate too high: " + fmt_number(dyaw / dt) + " rad/s > " +
                                     fmt_number(options.max_yaw_rate_radps) + " rad/s");
      }
      if (const auto s = first_collision(exact, p, w, options.resolution, /*exact=*/true))
        return violation(k, interpolate(p, w, *s), "collision");
    } else if (exact.in_collision_fcl(w.pose())) {
      return violation(0, w, "collision");
    }
    if (tether) {
      tether->move_to({w.x_m, w.y_m});
      // The taut length is convex along a straight drive: checking states suffices.
      if (tether->length_m() > tether_max + 1e-9)
        return violation(k, w, "tether too long: taut length " + fmt_number(tether->length_m()) + " m > " +
                                   fmt_number(tether_max) + " m");
    }
  }
  return std::nullopt;
}

}  // namespace ferret
