#include "ferret/uav/winch_supervision.hpp"

#include <algorithm>
#include <utility>

#include "ferret/tether_model/required_length.hpp"

namespace ferret {

// The tether length the miniUGV's last report asks for at a position: l_0, the taut
// tether from the entry to its last fixed point, and straight on from there. The
// winch controllers predict the miniUGV's motion between reports with it.
class ReportedTetherLength final : public tether::RequiredLengthModel {
 public:
  explicit ReportedTetherLength(double entry_offset_m) : l0_m_(entry_offset_m) {}
  void update(const UgvReport& r) {
    anchor_W_ = r.tether_anchor_W;
    to_anchor_m_ = r.tether_to_anchor_m;
  }
  [[nodiscard]] double required_length_m(const Eigen::Vector2d& p_WG) const override {
    return l0_m_ + to_anchor_m_ + (p_WG - anchor_W_).norm();
  }

 private:
  double l0_m_;
  Eigen::Vector2d anchor_W_ = Eigen::Vector2d::Zero();
  double to_anchor_m_ = 0.0;
};

WinchSupervision::WinchSupervision(tether::Winch& winch, Options options)
    : winch_(winch), options_(std::move(options)) {
  required_ = std::make_shared<ReportedTetherLength>(options_.entry_offset_m);
  controller_ = tether::tether_controllers().make(
      options_.controller, {options_.control, options_.controllers, required_},
      "uav mission options", "uav.winch_controller");
}

WinchSupervision::~WinchSupervision() = default;

void WinchSupervision::switch_on() {
  winch_.set_torque_enabled(true);
  idle();
}

void WinchSupervision::idle() { winch_.command_velocity_mps(0.0); }

void WinchSupervision::arm_touchdown_guard() {
  guard_ = std::make_unique<tether::TouchdownGuard>(options_.touchdown);
}

void WinchSupervision::keep_touchdown_guard() {
  if (!guard_) guard_ = std::make_unique<tether::TouchdownGuard>(options_.touchdown);
}

double WinchSupervision::release_length_m() const {
  // The miniUGV starts with the winch's slack reference paid out beyond l_0: a
  // metre of line is stiff (1.5 kN/m), so a line ending exactly taut at the entry
  // pulls tens of newtons the moment the robot moves.
  return options_.entry_offset_m + options_.control.slack_reference_m;
}

bool WinchSupervision::ugv_at_entry(const tether::WinchState& w) const {
  return w.released_m >= release_length_m() - 0.01;
}

void WinchSupervision::lower(double now_s, const UgvReport& r, const tether::WinchState& w) {
  // The touchdown check matters near the floor; above it the miniUGV hangs level.
  const auto action = guard_->update(now_s, r.roll_rad, r.pitch_rad, w.released_m);
  (void)action;
  winch_.command_velocity_mps(
      std::min(guard_->spool_velocity_mps(), release_length_m() - w.released_m + 0.05));
}

void WinchSupervision::start_taut_control() {
  idle();
  guard_.reset();
  controller_->reset();
}

void WinchSupervision::follow_ugv(double now_s, const UgvReport& r, const tether::WinchState& w) {
  // Over the robot link the miniUGV answers its search request a moment later:
  // until it has started (or while it is not heard) the winch cannot know where the
  // line must go, and holds its length. In one process it has started at once.
  const bool heard = r.link_ok && (r.running || r.done || r.wants_retraction);
  if (heard) required_->update(r);
  tether::TetherObservation obs;
  obs.t_s = now_s;
  obs.released_m = w.released_m;
  obs.spool_speed_mps = w.speed_mps;
  obs.winch_tension_n = w.tension_n;
  obs.ugv.p_WG = r.p_WG;
  obs.ugv.v_WG = r.v_WG;
  obs.slack_margin_m = r.tether_uncertainty_m;
  // Without word from the miniUGV the winch holds its length (the miniUGV holds too,
  // docs/link.md "Watchdogs"), but never against the line: a miniUGV still driving on a
  // stale link pulls it, and the winch measures that pull itself.
  winch_.command_velocity_mps(heard ? controller_->step(obs) : yield_to_tension_mps(w));
}

double WinchSupervision::yield_to_tension_mps(const tether::WinchState& w) const {
  // Pay out in proportion to the pull above the guard, all the spool can at the limit:
  // a metre of line is stiff (1.5 kN/m), so a few centimetres held against a moving
  // robot are tens of newtons.
  const tether::SlackEstimator& e = options_.control.slack_estimator;
  const double pull_n = w.tension_n - e.tension.hanging_weight_n - e.guard_n;
  if (!(pull_n > 0.0)) return 0.0;
  const double span_n =
      std::max(e.tension.max_tension_n - e.tension.hanging_weight_n - e.guard_n, 1e-3);
  return options_.control.limits.max_speed_mps * std::min(1.0, pull_n / span_n);
}

void WinchSupervision::reel_in() { winch_.command_velocity_mps(-options_.retract_speed_mps); }

}  // namespace ferret
