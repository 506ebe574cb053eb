#include "ferret/sim/invariant_monitor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

namespace ferret {
namespace {
constexpr std::array<std::string_view, kInvariantKinds> kNames{
    "tension_over_limit", "tether_over_length", "uav_collision",   "ugv_body_contact",
    "battery_empty",      "state_timeout",      "ugv_left_behind", "no_end"};
}  // namespace

std::string_view to_string(InvariantKind kind) {
  const auto i = static_cast<std::size_t>(kind);
  return i < kNames.size() ? kNames[i] : "?";
}

InvariantMonitor::InvariantMonitor(InvariantLimits limits) : limits_(std::move(limits)) {}

void InvariantMonitor::check(InvariantKind kind, bool violated, double value, double limit,
                             const InvariantSample& s, bool higher_is_worse,
                             const std::string& detail) {
  Episode& e = episodes_[{kind, detail}];
  if (!violated) {
    e.open.reset();
    return;
  }
  if (!e.open) {
    violations_.push_back({kind, s.t_s, s.t_s, s.uav_state, s.ugv_state, value, limit, detail});
    e.open = violations_.size() - 1;
    return;
  }
  InvariantViolation& v = violations_[*e.open];
  v.until_s = s.t_s;
  v.value = higher_is_worse ? std::max(v.value, value) : std::min(v.value, value);
}

void InvariantMonitor::check_timeout(const std::string& robot, const std::string& state,
                                     StateClock& clock, const InvariantSample& s) {
  if (!started_ || state != clock.state) clock = {state, s.t_s, false};
  if (state.empty() || clock.reported) return;
  const auto r = limits_.state_timeout_s.find(robot);
  if (r == limits_.state_timeout_s.end()) return;
  const auto limit = r->second.find(state);
  if (limit == r->second.end()) return;
  const double held_s = s.t_s - clock.entered_s;
  if (held_s <= limit->second) return;
  // One violation per visit of the state: the time it overstayed is what matters.
  clock.reported = true;
  violations_.push_back({InvariantKind::kStateTimeout, s.t_s, s.t_s, s.uav_state, s.ugv_state,
                         held_s, limit->second, robot + "." + state});
}

void InvariantMonitor::observe(const InvariantSample& s) {
  // NaN is a violation too: a tension nobody can read is not under the limit.
  const auto over = [](double v, double limit) { return !(v <= limit); };
  check(InvariantKind::kTensionOverLimit, over(s.tension_n, limits_.max_tension_n), s.tension_n,
        limits_.max_tension_n, s, true);
  check(InvariantKind::kTetherOverLength, over(s.released_m, limits_.tether_length_m), s.released_m,
        limits_.tether_length_m, s, true);
  check(InvariantKind::kUavCollision, s.uav_collision, 1.0, 0.0, s, true);
  check(InvariantKind::kUgvBodyContact,
        s.ugv_body_contact && !(s.ugv_contact_depth_m < limits_.contact_tolerance_m),
        s.ugv_contact_depth_m, limits_.contact_tolerance_m, s, true);
  check(InvariantKind::kBatteryEmpty, !(s.uav_battery > limits_.battery_floor), s.uav_battery,
        limits_.battery_floor, s, false, "uav");
  check(InvariantKind::kBatteryEmpty, s.ugv_battery && !(*s.ugv_battery > limits_.battery_floor),
        s.ugv_battery.value_or(1.0), limits_.battery_floor, s, false, "ugv");
  check_timeout("uav", s.uav_state, uav_clock_, s);
  check_timeout("ugv", s.ugv_state, ugv_clock_, s);
  started_ = true;
}

void InvariantMonitor::finish(const InvariantSample& last, bool ugv_left_in_space,
                              const std::string& reason, bool ended) {
  if (ugv_left_in_space && reason.empty())
    violations_.push_back({InvariantKind::kUgvLeftBehind, last.t_s, last.t_s, last.uav_state,
                           last.ugv_state, 1.0, 0.0, ""});
  if (!ended)
    violations_.push_back({InvariantKind::kNoEnd, last.t_s, last.t_s, last.uav_state,
                           last.ugv_state, last.t_s, last.t_s, ""});
}

int InvariantMonitor::count(InvariantKind kind) const {
  return static_cast<int>(std::count_if(violations_.begin(), violations_.end(),
                                        [kind](const auto& v) { return v.kind == kind; }));
}

}  // namespace ferret
