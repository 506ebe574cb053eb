#include "ferret/ugv/ugv_link_endpoint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "ferret/tether_model/taut_control_options.hpp"
#include "ferret/ugv/mini_ugv_mission.hpp"
#include "ferret/ugv/ugv_base.hpp"

namespace ferret {
namespace {

// The link mirrors the mission's enums value for value (link/messages.hpp).
static_assert(static_cast<int>(UgvMissionState::kDone) == static_cast<int>(link::UgvMode::kDone));
static_assert(static_cast<int>(UgvMissionOutcome::kRecalled) ==
              static_cast<int>(link::UgvOutcome::kRecalled));

link::UgvMode mode_of(UgvMissionState s) { return static_cast<link::UgvMode>(static_cast<int>(s)); }
link::UgvOutcome outcome_of(UgvMissionOutcome o) {
  return static_cast<link::UgvOutcome>(static_cast<int>(o));
}

// The wire's ranges (docs/link.md): a value past them is the sender's bug, so it is
// held inside them here rather than thrown at the robot's control loop.
float clamped(double v, double limit) { return static_cast<float>(std::clamp(v, -limit, limit)); }

// How fast a robot at `p` moving at `v` lengthens a taut line fixed at `anchor` (m/s;
// negative: it shortens it). On the anchor every direction lengthens it.
double line_speed_mps(const Eigen::Vector2d& p, const Eigen::Vector2d& v,
                      const Eigen::Vector2d& anchor) {
  const Eigen::Vector2d d = p - anchor;
  return d.norm() < 1e-3 ? v.norm() : v.dot(d.normalized());
}

// What the default winch catches up by the pull it feels, with half of the pull
// budget: a winch following a moving robot over a lossy link already holds the line at
// up to half the way from its guard to the tension limit (3-6 N measured), and the
// catch may only use the rest.
tether::LineCatchLimit link_catch_limit() {
  tether::LineCatchLimit c = tether::LineCatchLimit::for_winch(tether::TautControlOptions{});
  c.pull_budget_n *= 0.5;
  return c;
}

}  // namespace

UgvLinkEndpoint::UgvLinkEndpoint(const Clock& clock, StartSearch start_search,
                                 UgvLinkEndpointOptions options)
    : clock_(clock),
      start_search_(std::move(start_search)),
      options_(options),
      session_(clock, options.link),
      line_catch_(options.line_catch.value_or(link_catch_limit())) {
  if (!(std::isfinite(options_.telemetry_period_s) && options_.telemetry_period_s > 0.0))
    throw std::invalid_argument("UgvLinkEndpoint: telemetry_period_s must be > 0");
  if (!start_search_) throw std::invalid_argument("UgvLinkEndpoint: no start_search");
  if (options_.winch_view_limit &&
      !(options_.winch_follow_s >= 0.0 && options_.braking_mps2 > 0.0 &&
        options_.turn_per_tick_rad >= 0.0 && line_catch_.on()))
    throw std::invalid_argument("UgvLinkEndpoint: bad winch view limit options");
}

void UgvLinkEndpoint::set_attitude(double roll_rad, double pitch_rad) {
  roll_rad_ = roll_rad;
  pitch_rad_ = pitch_rad;
}

void UgvLinkEndpoint::act_on(const link::UavRequest& r) {
  using Kind = link::UavRequest::Kind;
  last_request_id_ = r.request_id;
  if (r.kind ==
      Kind::kReleaseObject) {  // under the UAV: the magnet is the robot's, not the mission's
    if (base_)
      base_->set_epm(false);
    else
      ++without_mission_;
    return;
  }
  if (r.kind == Kind::kStartSearch) {
    if (mission_ && !mission_->done()) mission_->stop("a new search was asked for");
    const Deployment d = start_search_(r);
    mission_ = d.mission;
    if (d.base) base_ = d.base;
    if (!mission_) {
      ++without_mission_;
      return;
    }
    if (mission_->state() == UgvMissionState::kIdle) mission_->start();
    return;
  }
  if (!mission_) {
    ++without_mission_;
    return;
  }
  MiniUgvMission& m = *mission_;
  switch (r.kind) {
    case Kind::kRecall:
      m.recall(r.reason);
      return;
    case Kind::kRetracted:
      if (m.wants_retraction()) m.retracted();
      if (!m.done()) m.stop("lifted out");
      mission_ = nullptr;  // aboard: the next search is another mission
      return;
    case Kind::kAbort:
      if (!m.done()) m.stop(r.reason.empty() ? "the UAV aborted" : r.reason);
      return;
    case Kind::kStartSearch:
    case Kind::kReleaseObject:
      return;
  }
}

bool UgvLinkEndpoint::handle_requests() {
  while (const auto request = session_.next_request()) act_on(*request);
  const bool under_way =
      mission_ && !mission_->done() && mission_->state() != UgvMissionState::kIdle;
  const bool hold = under_way && session_.peer_silent();
  if (hold && !holding_) ++holds_;
  holding_ = hold;
  if (holding_ && base_) base_->command_velocity(0.0, 0.0);
  if (mission_) mission_->set_link_speed_limit_mps(winch_view_speed_limit_mps());
  return holding_;
}

double UgvLinkEndpoint::winch_view_age_s() const {
  const auto& heartbeat = session_.heartbeat();
  if (!heartbeat || !(heartbeat->ugv_telemetry_t_s > 0.0))
    return std::numeric_limits<double>::infinity();
  return std::max(0.0, clock_.now_s() - heartbeat->ugv_telemetry_t_s);
}

double UgvLinkEndpoint::winch_known_line_speed_mps() const {
  const auto& heartbeat = session_.heartbeat();
  if (!heartbeat) return 0.0;
  const double echoed_s = heartbeat->ugv_telemetry_t_s;
  // The echo is the very number sent; a record without it has forgotten it.
  const auto from = std::find_if(reported_.begin(), reported_.end(),
                                 [&](const auto& r) { return r.first == echoed_s; });
  if (from == reported_.end()) return 0.0;
  double known_mps = std::numeric_limits<double>::infinity();
  for (auto r = from; r != reported_.end(); ++r) known_mps = std::min(known_mps, r->second);
  return std::max(0.0, known_mps);
}

double winch_view_line_speed_mps(const UgvLinkEndpointOptions& o, double age_s, double known_mps,
                                 double catch_mps) {
  if (!o.winch_view_limit) return std::numeric_limits<double>::infinity();
  // The winch holds no earlier than winch_follow_s after the echoed telemetry (it heard
  // it no earlier than it was sent); till then it pays out at least the known speed.
  // The robot keeps within the line catch of that, and brakes so that it is within the
  // line catch of a holding winch by then: what the winch feels, it pays out.
  const double follow_left_s = o.winch_follow_s - age_s;
  const double follow_mps = follow_left_s > 0.0
                                ? std::min(std::max(known_mps, 0.0), o.braking_mps2 * follow_left_s)
                                : 0.0;
  return catch_mps + follow_mps;
}

double UgvLinkEndpoint::winch_view_line_speed_mps() const {
  if (!options_.winch_view_limit) return std::numeric_limits<double>::infinity();
  const double line_m = mission_ ? mission_->line_length_m() : 0.0;
  return ferret::winch_view_line_speed_mps(
      options_, winch_view_age_s(), winch_known_line_speed_mps(), line_catch_.speed_mps(line_m));
}

double UgvLinkEndpoint::winch_view_speed_limit_mps() const {
  const double line_mps = winch_view_line_speed_mps();
  if (!std::isfinite(line_mps) || !base_) return line_mps;
  const Pose2 pose = base_->odometry();
  Eigen::Vector2d anchor_W = mission_ ? mission_->entry_W() : pose.position();
  if (mission_)
    if (const auto a = mission_->explore_controller().tether_anchor()) anchor_W = a->first;
  const Eigen::Vector2d d = pose.position() - anchor_W;
  if (d.norm() < 1e-3) return line_mps;
  // The share of the speed along the line, at the heading the robot may turn to by the
  // next tick, in the direction it drives (either while it nearly stands).
  const double speed_mps = base_->speed_mps();
  double share = 0.0;
  for (const double sign : {1.0, -1.0}) {
    if (sign * speed_mps < -0.02) continue;
    const double along_rad = std::acos(std::clamp(
        sign * (std::cos(pose.yaw_rad) * d.x() + std::sin(pose.yaw_rad) * d.y()) / d.norm(), -1.0,
        1.0));
    share = std::max(share, std::cos(std::max(0.0, along_rad - options_.turn_per_tick_rad)));
  }
  return share > 0.0 ? line_mps / share : std::numeric_limits<double>::infinity();
}

void UgvLinkEndpoint::report() {
  const double now = clock_.now_s();
  if (now + 1e-9 < next_telemetry_s_) return;
  const link::UgvTelemetry t = telemetry();
  session_.send_telemetry(t);
  reported_.emplace_back(t.t_s, line_speed_mps({t.x_m, t.y_m}, {t.vx_mps, t.vy_mps},
                                               {t.tether_anchor_x_m, t.tether_anchor_y_m}));
  // An echo older than winch_follow_s gives the winch's view nothing to follow.
  while (!reported_.empty() && reported_.front().first < t.t_s - options_.winch_follow_s - 1.0)
    reported_.pop_front();
  next_telemetry_s_ = now + options_.telemetry_period_s;
}

link::UgvTelemetry UgvLinkEndpoint::telemetry() const {
  link::UgvTelemetry t;
  t.t_s = std::clamp(clock_.now_s(), 0.0, 1e9);
  t.last_request_id = last_request_id_;
  t.roll_rad = clamped(roll_rad_, 3.14159);
  t.pitch_rad = clamped(pitch_rad_, 3.14159);
  if (base_) {
    const UgvStatus st = base_->status();
    t.battery_fraction = static_cast<float>(std::clamp(st.battery_fraction, 0.0, 1.0));
    t.epm_on = st.epm_on;
    t.object_held = st.epm_on && st.contact;
    const Pose2 p = base_->odometry();
    t.x_m = std::clamp(p.x_m, -1e5, 1e5);
    t.y_m = std::clamp(p.y_m, -1e5, 1e5);
    t.yaw_rad = std::remainder(p.yaw_rad, 2.0 * M_PI);
    const double v = base_->speed_mps();
    t.vx_mps = clamped(v * std::cos(p.yaw_rad), 100.0);
    t.vy_mps = clamped(v * std::sin(p.yaw_rad), 100.0);
    t.tether_anchor_x_m = t.x_m;
    t.tether_anchor_y_m = t.y_m;
  }
  if (!mission_) return t;
  const MiniUgvMission& m = *mission_;
  t.mode = mode_of(m.state());
  t.wants_retraction = m.wants_retraction();
  if (m.done()) t.outcome = outcome_of(m.outcome());
  if (m.wants_retraction()) t.outcome = outcome_of(m.return_outcome());
  if (const auto a = m.explore_controller().tether_anchor()) {
    t.tether_anchor_x_m = std::clamp(a->first.x(), -1e5, 1e5);
    t.tether_anchor_y_m = std::clamp(a->first.y(), -1e5, 1e5);
    t.tether_to_anchor_m = std::clamp(a->second, 0.0, 1e4);
    t.tether_uncertainty_m = static_cast<float>(std::clamp(
        m.explore_controller().reach_length_m() - m.explore_controller().tether_length_m(), 0.0,
        1e4));
  } else {
    t.tether_anchor_x_m = m.entry_W().x();
    t.tether_anchor_y_m = m.entry_W().y();
  }
  return t;
}

}  // namespace ferret
