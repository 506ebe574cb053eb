// The miniUGV's trajectory in a tether simulation: samples interpolated in time,
// velocities and accelerations by differences, a scripted drive through waypoints, the
// motion a lagging, slipping robot really makes, and the default scenario.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "ferret/core/random.hpp"
#include "ferret/sim/tether_sim.hpp"

namespace ferret::sim {

TrajectorySample TetherScenario::at(double t_s) const {
  if (t_s <= samples.front().t_s) return samples.front();
  if (t_s >= samples.back().t_s) return samples.back();
  const auto it = std::upper_bound(samples.begin(), samples.end(), t_s,
                                   [](double t, const TrajectorySample& s) { return t < s.t_s; });
  const TrajectorySample& b = *it;
  const TrajectorySample& a = *(it - 1);
  const double f = (t_s - a.t_s) / (b.t_s - a.t_s);
  TrajectorySample out;
  out.t_s = t_s;
  out.p_WG = a.p_WG + f * (b.p_WG - a.p_WG);
  out.yaw_rad = a.yaw_rad + f * std::remainder(b.yaw_rad - a.yaw_rad, 2.0 * std::numbers::pi);
  out.v_WG = a.v_WG + f * (b.v_WG - a.v_WG);
  out.a_WG = a.a_WG + f * (b.a_WG - a.a_WG);
  return out;
}

void differentiate_trajectory(std::vector<TrajectorySample>& s) {
  const std::size_t n = s.size();
  if (n < 2) return;
  auto diff = [&](auto get, auto set) {
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t a = i == 0 ? 0 : i - 1, b = i + 1 == n ? n - 1 : i + 1;
      set(s[i], Eigen::Vector2d((get(s[b]) - get(s[a])) / (s[b].t_s - s[a].t_s)));
    }
  };
  diff([](const TrajectorySample& x) { return x.p_WG; },
       [](TrajectorySample& x, Eigen::Vector2d v) { x.v_WG = v; });
  diff([](const TrajectorySample& x) { return x.v_WG; },
       [](TrajectorySample& x, Eigen::Vector2d a) { x.a_WG = a; });
}

std::vector<TrajectorySample> scripted_trajectory(const std::vector<Eigen::Vector2d>& waypoints,
                                                  double cruise_mps, double accel_mps2,
                                                  double dwell_s, double dt_s) {
  if (waypoints.size() < 2 || !(cruise_mps > 0.0) || !(accel_mps2 > 0.0) || !(dt_s > 0.0) ||
      dwell_s < 0.0)
    throw std::invalid_argument(
        "scripted_trajectory: need >= 2 waypoints, positive speed, acceleration and dt");
  // Each segment: accelerate, cruise, decelerate (a triangle when too short), then dwell.
  struct Segment {
    Eigen::Vector2d from, dir;
    double t0, t_acc, t_cruise, v_peak, length, yaw;
  };
  std::vector<Segment> segments;
  double t = 0.0;
  double yaw = 0.0;
  for (std::size_t i = 0; i + 1 < waypoints.size(); ++i) {
    const Eigen::Vector2d d = waypoints[i + 1] - waypoints[i];
    const double length = d.norm();
    if (length < 1e-9) continue;
    yaw = std::atan2(d.y(), d.x());
    Segment s{waypoints[i], d / length, t, 0, 0, 0, length, yaw};
    if (length >= cruise_mps * cruise_mps / accel_mps2) {
      s.v_peak = cruise_mps;
      s.t_acc = cruise_mps / accel_mps2;
      s.t_cruise = (length - cruise_mps * s.t_acc) / cruise_mps;
    } else {
      s.v_peak = std::sqrt(length * accel_mps2);
      s.t_acc = s.v_peak / accel_mps2;
    }
    segments.push_back(s);
    t += 2.0 * s.t_acc + s.t_cruise + dwell_s;
  }
  if (segments.empty()) throw std::invalid_argument("scripted_trajectory: all waypoints coincide");
  const double total = t;
  std::vector<TrajectorySample> out;
  std::size_t k = 0;
  const auto count = static_cast<std::size_t>(std::floor(total / dt_s + 1e-9)) + 1;
  for (std::size_t i = 0; i < count; ++i) {
    const double ti = std::min(total, static_cast<double>(i) * dt_s);
    while (k + 1 < segments.size() && ti >= segments[k + 1].t0) ++k;
    const Segment& s = segments[k];
    const double tau = ti - s.t0, move = 2.0 * s.t_acc + s.t_cruise;
    double dist, speed, acc;
    if (tau < s.t_acc) {
      dist = 0.5 * accel_mps2 * tau * tau, speed = accel_mps2 * tau, acc = accel_mps2;
    } else if (tau < s.t_acc + s.t_cruise) {
      dist = 0.5 * s.v_peak * s.t_acc + s.v_peak * (tau - s.t_acc), speed = s.v_peak, acc = 0.0;
    } else if (tau < move) {
      const double rem = move - tau;
      dist = s.length - 0.5 * accel_mps2 * rem * rem, speed = accel_mps2 * rem, acc = -accel_mps2;
    } else {
      dist = s.length, speed = 0.0, acc = 0.0;
    }
    TrajectorySample smp;
    smp.t_s = ti;
    smp.p_WG = s.from + s.dir * dist;
    smp.yaw_rad = s.yaw;
    smp.v_WG = s.dir * speed;
    smp.a_WG = s.dir * acc;
    if (!out.empty() && ti <= out.back().t_s) break;
    out.push_back(smp);
  }
  return out;
}

namespace {

// The default scenario: a block x in [1, 3.5], y in [0.5, 2] beside the entry; the
// tether wraps its two right-hand corners when the miniUGV drives up and behind it.
std::vector<tether::WrapPoint> default_wraps() { return {{{3.5, 0.5}, +1}, {{3.5, 2.0}, +1}}; }
std::vector<Eigen::Vector2d> default_waypoints() {
  return {{0.3, 0.0}, {4.2, 0.0}, {4.2, 3.0}, {1.5, 3.0}, {4.2, 3.0}, {4.2, 0.0}, {0.3, 0.0}};
}

}  // namespace

std::vector<TrajectorySample> actual_ugv_motion(const TetherScenario& scn, const UgvObedience& ugv,
                                                double dt_s, std::uint64_t seed) {
  if (!(dt_s > 0.0) || ugv.velocity_lag_s < 0.0 || ugv.slip_mps < 0.0 || !(ugv.slip_time_s > 0.0) ||
      ugv.tracking_time_s < 0.0)
    throw std::invalid_argument("actual_ugv_motion: need dt > 0, times and slip >= 0");
  Rng rng(seed);
  const auto count =
      static_cast<std::size_t>(std::floor((scn.end_s() - scn.start_s()) / dt_s + 1e-9)) + 1;
  // Exact discretisation of the lag v' = (v_cmd - v) / lag and of the slip process.
  const double follow = ugv.velocity_lag_s > 0.0 ? 1.0 - std::exp(-dt_s / ugv.velocity_lag_s) : 1.0;
  const double keep = std::exp(-dt_s / ugv.slip_time_s);
  const double kick = ugv.slip_mps * std::sqrt(1.0 - keep * keep);
  const double steer = ugv.tracking_time_s > 0.0 ? 1.0 / ugv.tracking_time_s : 0.0;
  std::vector<TrajectorySample> out;
  out.reserve(count);
  // The position is the desired one plus the integrated velocity error, so an
  // obedient robot reproduces its trajectory exactly.
  TrajectorySample desired = scn.at(scn.start_s());
  Eigen::Vector2d v = desired.v_WG, slip = Eigen::Vector2d::Zero(), offset = slip;
  out.push_back(desired);
  for (std::size_t i = 1; i < count; ++i) {
    const Eigen::Vector2d error_before = v + slip - desired.v_WG;
    desired = scn.at(scn.start_s() + static_cast<double>(i) * dt_s);
    v += follow * (desired.v_WG - steer * offset - v);
    if (ugv.slip_mps > 0.0)
      slip = keep * slip + kick * Eigen::Vector2d(rng.normal(0.0, 1.0), rng.normal(0.0, 1.0));
    offset += 0.5 * (error_before + v + slip - desired.v_WG) * dt_s;
    TrajectorySample row = desired;
    row.p_WG += offset;
    row.v_WG = v + slip;
    out.push_back(row);
  }
  return out;
}

TetherScenario default_tether_scenario() {
  TetherScenario scn;
  scn.name = "default";
  scn.wrap_points = default_wraps();
  scn.samples = scripted_trajectory(default_waypoints(), 0.4, 1.0, 1.0);
  return scn;
}

}  // namespace ferret::sim
