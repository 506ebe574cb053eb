#include "ferret/planning/plan_validation.hpp"

#include <fmt/format.h>
#include <octomap/OcTree.h>

#include <cmath>
#include <numbers>

#include "collision_contact.hpp"
#include "ferret/core/error.hpp"
#include "ferret/planning/uav_planner.hpp"
#include "ferret/planning/ugv_planner.hpp"

namespace ferret {
namespace {

// A relative tolerance: time stamps written with rounding are not violations.
constexpr double kRelTol = 1e-6;

bool over(double value, double limit) { return value > limit * (1 + kRelTol) + 1e-12; }

// The velocity of one timed segment (for accelerations).
struct TimedSegment {
  std::size_t from, to;
  double dt_s;
  Eigen::Vector3d v_mps;
};

bool unobserved(const octomap::OcTree* observed, const Eigen::Vector3d& p_W) {
  if (!observed) return false;
  octomap::OcTreeKey key;
  if (!observed->coordToKeyChecked(p_W.x(), p_W.y(), p_W.z(), key)) return true;
  return observed->search(key) == nullptr;
}

}  // namespace

const char* to_string(ViolationKind kind) {
  switch (kind) {
    case ViolationKind::kCollision:
      return "collision";
    case ViolationKind::kUnknownSpace:
      return "unknown_space";
    case ViolationKind::kGeofence:
      return "geofence";
    case ViolationKind::kTimeOrder:
      return "time_order";
    case ViolationKind::kSpeed:
      return "speed";
    case ViolationKind::kAcceleration:
      return "acceleration";
    case ViolationKind::kYawRate:
      return "yaw_rate";
    case ViolationKind::kTetherLength:
      return "tether_length";
  }
  return "?";
}

std::string Violation::describe() const {
  std::string where = from_index == to_index ? fmt::format("state {}", from_index)
                                             : fmt::format("segment {}-{}", from_index, to_index);
  std::string head = fmt::format("{} at t = {:.3f} s", where, t_s);
  if (from_index != to_index) head += fmt::format(" (s = {:.3f})", s);
  head += fmt::format(", position ({:.3f}, {:.3f}, {:.3f})", p_W.x(), p_W.y(), p_W.z());
  std::string what;
  switch (kind) {
    case ViolationKind::kCollision:
    case ViolationKind::kUnknownSpace: {
      // "collision of chassis_link with block (voxel at ...)", "... with unknown space (...)"
      what = "collision";
      if (!part.empty()) what += " of " + part;
      std::string with = kind == ViolationKind::kUnknownSpace  ? "unknown space"
                         : obstacle && !obstacle->name.empty() ? obstacle->name
                                                               : "";
      if (obstacle)
        with += fmt::format("{}(voxel at {:.3f}, {:.3f}, {:.3f})", with.empty() ? "" : " ",
                            obstacle->p_W.x(), obstacle->p_W.y(), obstacle->p_W.z());
      if (!with.empty()) what += " with " + with;
      break;
    }
    case ViolationKind::kGeofence:
      what = "outside the geofence";
      break;
    case ViolationKind::kTimeOrder:
      what = "time does not increase";
      break;
    case ViolationKind::kSpeed:
      what = fmt::format("too fast: {:.4g} m/s > {:.4g} m/s", value, limit);
      break;
    case ViolationKind::kAcceleration:
      what = fmt::format("acceleration too high: {:.4g} m/s^2 > {:.4g} m/s^2", value, limit);
      break;
    case ViolationKind::kYawRate:
      what = fmt::format("yaw rate too high: {:.4g} rad/s > {:.4g} rad/s", value, limit);
      break;
    case ViolationKind::kTetherLength:
      what = fmt::format("tether too long: taut length {:.4g} m > {:.4g} m", value, limit);
      break;
  }
  return head + ": " + what;
}

CheckResolution default_resolution(PlanRobot robot) {
  return robot == PlanRobot::kUgv ? UgvPlannerOptions{}.resolution : UavPlannerOptions{}.resolution;
}

void check_yaw_is_radians(const PlanFile& plan, const std::string& source) {
  // Rounding of pi in a file (3.1416) is not an error; anything further out is.
  constexpr double kTol = 1e-3;
  double largest = 0.0;
  for (const Waypoint& w : plan.states) largest = std::max(largest, std::abs(w.yaw_rad));
  for (std::size_t k = 0; k < plan.states.size(); ++k) {
    const Waypoint& w = plan.states[k];
    if (std::abs(w.yaw_rad) <= std::numbers::pi + kTol) continue;
    const std::string expected =
        largest <= 360.0 + kTol
            ? "a heading in radians within [-pi, pi] (the plan's headings reach " +
                  fmt::format("{:g}", largest) + ": degrees?)"
            : "a heading in radians within [-pi, pi]";
    throw InputError(source, fmt::format("states[{}].yaw_rad (t = {:g} s)", k, w.t_s), expected,
                     fmt::format("{:g}", w.yaw_rad));
  }
}

std::uint64_t plan_check_count(const std::vector<Waypoint>& states, const CheckResolution& res) {
  std::uint64_t n = states.empty() ? 0 : 1;
  for (std::size_t k = 1; k < states.size() && n <= kMaxPlanChecks; ++k)
    n += static_cast<std::uint64_t>(segment_steps(states[k - 1], states[k], res)) + 1;
  return n;
}

void check_plan_work(const PlanFile& plan, const CheckResolution& res, const std::string& source) {
  const std::uint64_t n = plan_check_count(plan.states, res);
  if (n > kMaxPlanChecks)
    throw InputError(
        source, "states",
        fmt::format("a plan of at most {} collision checks (one every {:g} m and {:g} rad)",
                    kMaxPlanChecks, res.step_m, res.step_rad),
        fmt::format("more than {} (plan too long to check)", kMaxPlanChecks));
}

ValidationReport validate_plan(const PlanFile& plan, CollisionChecker& exact,
                               const std::shared_ptr<const TetherCorners>& corners,
                               const ValidationOptions& options) {
  ValidationReport report;
  ValidationInputs& in = report.inputs;
  in.robot = plan.robot;
  in.states = plan.states.size();
  in.limits = options.limits;
  in.geofence = options.geofence;
  in.resolution = options.resolution;
  for (const ShapePart& p : exact.shape().parts) in.parts.push_back(p.name);
  ValidationMargins& m = report.margins;
  const auto& states = plan.states;
  if (states.empty()) throw InputError("plan", "states", "at least one state");
  check_plan_work(plan, options.resolution, "plan");
  const MotionLimits& lim = options.limits;

  auto at = [&](ViolationKind kind, std::size_t from, std::size_t to, double s, const Waypoint& w) {
    Violation v;
    v.kind = kind;
    v.from_index = from;
    v.to_index = to;
    v.s = s;
    v.t_s = w.t_s;
    v.p_W = w.position();
    v.yaw_rad = w.yaw_rad;
    return v;
  };
  auto add_collision = [&](std::size_t from, std::size_t to, double s, const Waypoint& w) {
    Violation v = at(ViolationKind::kCollision, from, to, s, w);
    if (const auto c = find_contact(*exact.map(), exact.shape(), w.pose())) {
      v.part = c->part;
      Obstacle o{c->voxel_W,
                 options.name_obstacle ? options.name_obstacle(c->voxel_W) : std::string()};
      if (unobserved(options.observed, c->voxel_W)) v.kind = ViolationKind::kUnknownSpace;
      v.obstacle = o;
    }
    report.violations.push_back(std::move(v));
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
      throw InputError("plan", "tether",
                       "a tether entry point (the plan has no tether section; pass --entry)");
    }
    if (options.tether_max_m) tether_max = *options.tether_max_m;
    // The tether as it lay at the start: bent at the recorded wrap points.
    tether.emplace(corners, entry,
                   plan.tether ? plan.tether->initial_wraps : std::vector<WrapPoint>{},
                   Eigen::Vector2d(states.front().x_m, states.front().y_m));
    m.tether_budget_m = tether_max;
    m.peak_tether_m = 0.0;
  }

  // The velocity profile: one constant velocity a timed segment (segments of no
  // duration and no motion are repeated states, not stops, and carry none).
  std::vector<TimedSegment> timed;
  for (std::size_t k = 1; k < states.size(); ++k) {
    const double dt = states[k].t_s - states[k - 1].t_s;
    if (dt > 0)
      timed.push_back({k - 1, k, dt, (states[k].position() - states[k - 1].position()) / dt});
  }
  std::size_t next_timed = 0;  // the first timed segment that ends at or after state k

  const auto stop_if_cancelled = [&] {
    if (options.cancelled && options.cancelled()) throw ValidationCancelled();
  };
  for (std::size_t k = 0; k < states.size(); ++k) {
    stop_if_cancelled();
    const Waypoint& w = states[k];
    if (k > 0) {
      const Waypoint& p = states[k - 1];
      const double dt = w.t_s - p.t_s;
      const double dp = (w.position() - p.position()).norm();
      const double dyaw = std::abs(wrap_angle_rad(w.yaw_rad - p.yaw_rad));
      const bool moves = dp > 1e-12 || dyaw > 1e-12;
      if (dt < 0 || (moves && dt <= 0)) {
        report.violations.push_back(at(ViolationKind::kTimeOrder, k - 1, k, 1.0, w));
      } else if (dt > 0) {
        const double speed = dp / dt, yaw_rate = dyaw / dt;
        m.peak_speed_mps = std::max(m.peak_speed_mps, speed);
        m.peak_yaw_rate_radps = std::max(m.peak_yaw_rate_radps, yaw_rate);
        // A segment's speed is the same all along it: reported at its start.
        if (over(speed, lim.max_velocity_mps)) {
          Violation v = at(ViolationKind::kSpeed, k - 1, k, 0.0, p);
          v.value = speed;
          v.limit = lim.max_velocity_mps;
          report.violations.push_back(v);
        }
        if (over(yaw_rate, lim.max_yaw_rate_radps)) {
          Violation v = at(ViolationKind::kYawRate, k - 1, k, 0.0, p);
          v.value = yaw_rate;
          v.limit = lim.max_yaw_rate_radps;
          report.violations.push_back(v);
        }
      }
      if (const auto s =
              first_collision(exact, p, w, options.resolution, /*exact=*/true, options.cancelled))
        add_collision(k - 1, k, *s, interpolate(p, w, *s));
      stop_if_cancelled();  // a check cut short found nothing: it must not pass as clear
      // The clearance at the poses the collision check visits.
      const int n = segment_steps(p, w, options.resolution);
      for (int i = 1; i <= n; ++i) {
        if (i % 64 == 0) stop_if_cancelled();
        m.min_clearance_m = std::min(
            m.min_clearance_m,
            exact.clearance_lower_bound_m(interpolate(p, w, static_cast<double>(i) / n).pose()));
      }
    } else {
      if (exact.in_collision_fcl(w.pose())) add_collision(0, 0, 0.0, w);
      m.min_clearance_m = std::min(m.min_clearance_m, exact.clearance_lower_bound_m(w.pose()));
    }
    // Acceleration at state k: the change between the timed segments meeting there,
    // over the mean of their durations (the time the robot has to make it).
    while (next_timed < timed.size() && timed[next_timed].to < k) ++next_timed;
    if (next_timed + 1 < timed.size() && timed[next_timed].to == k &&
        states[timed[next_timed + 1].from].t_s == w.t_s &&
        states[timed[next_timed + 1].from].position() == w.position()) {  // only repeats between
      const TimedSegment& a = timed[next_timed];
      const TimedSegment& b = timed[next_timed + 1];
      const double accel = (b.v_mps - a.v_mps).norm() / (0.5 * (a.dt_s + b.dt_s));
      m.peak_acceleration_mps2 = std::max(m.peak_acceleration_mps2, accel);
      if (over(accel, lim.max_acceleration_mps2)) {
        const double span = states[b.to].t_s - states[a.from].t_s;
        Violation v =
            at(ViolationKind::kAcceleration, a.from, b.to, (w.t_s - states[a.from].t_s) / span, w);
        v.value = accel;
        v.limit = lim.max_acceleration_mps2;
        report.violations.push_back(v);
      }
    }
    if (options.geofence && !options.geofence->contains(w.position()))
      report.violations.push_back(at(ViolationKind::kGeofence, k, k, 0.0, w));
    if (tether) {
      tether->move_to({w.x_m, w.y_m});
      // The taut length is convex along a straight drive: checking states suffices.
      m.peak_tether_m = std::max(*m.peak_tether_m, tether->length_m());
      if (tether->length_m() > tether_max + 1e-9) {
        Violation v = at(ViolationKind::kTetherLength, k, k, 0.0, w);
        v.value = tether->length_m();
        v.limit = tether_max;
        report.violations.push_back(v);
      }
    }
  }
  return report;
}

}  // namespace ferret
