#include "ferret/tether_model/tether_modes.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ferret::tether {

std::string_view to_string(TetherMode mode) {
  switch (mode) {
    case TetherMode::kAerial:
      return "aerial";
    case TetherMode::kLowering:
      return "lowering";
    case TetherMode::kHiddenSpace:
      return "hidden-space";
  }
  return "?";
}

std::string_view to_string(LoweringAction action) {
  switch (action) {
    case LoweringAction::kLower:
      return "lower";
    case LoweringAction::kPause:
      return "pause";
    case LoweringAction::kRelift:
      return "relift";
  }
  return "?";
}

TetherModeSwitcher::TetherModeSwitcher(Options options, TetherMode initial)
    : options_(options), mode_(initial) {
  if (!(options_.total_length_m > 0.0) || !(options_.entry_offset_m > 0.0) ||
      options_.entry_offset_m > options_.total_length_m)
    throw std::invalid_argument("TetherModeSwitcher: need 0 < l_0 <= L");
  if (!(options_.uav_height_m > 0.0) || !(options_.hysteresis_m >= 0.0) ||
      !(options_.aerial_tolerance_m >= 0.0))
    throw std::invalid_argument(
        "TetherModeSwitcher: Z_W must be > 0, hysteresis and tolerance >= 0");
  if (options_.aerial_tolerance_m + 2.0 * options_.hysteresis_m >=
      options_.entry_offset_m - options_.hysteresis_m)
    throw std::invalid_argument(
        "TetherModeSwitcher: hysteresis bands overlap (l_0 too small for the hysteresis)");
}

TetherMode TetherModeSwitcher::update(double t_s, double released_m) {
  const auto& o = options_;
  const double aerial_exit = o.aerial_tolerance_m + o.hysteresis_m;
  const double hidden_enter = o.entry_offset_m + o.hysteresis_m;
  const double hidden_exit = o.entry_offset_m - o.hysteresis_m;
  TetherMode next = mode_;
  switch (mode_) {
    case TetherMode::kAerial:
      if (released_m >= hidden_enter)
        next = TetherMode::kHiddenSpace;
      else if (released_m > aerial_exit)
        next = TetherMode::kLowering;
      break;
    case TetherMode::kLowering:
      if (released_m <= o.aerial_tolerance_m)
        next = TetherMode::kAerial;
      else if (released_m >= hidden_enter)
        next = TetherMode::kHiddenSpace;
      break;
    case TetherMode::kHiddenSpace:
      if (released_m <= o.aerial_tolerance_m)
        next = TetherMode::kAerial;
      else if (released_m < hidden_exit)
        next = TetherMode::kLowering;
      break;
  }
  if (next != mode_) {
    spdlog::info("tether mode: {} -> {} at t = {:.3f} s, l_t = {:.3f} m", to_string(mode_),
                 to_string(next), t_s, released_m);
    transitions_.push_back({t_s, mode_, next, released_m});
    mode_ = next;
  }
  if (released_m > o.total_length_m)
    spdlog::warn("tether: l_t = {:.3f} m exceeds L = {:.3f} m", released_m, o.total_length_m);
  return mode_;
}

TouchdownGuard::TouchdownGuard(Options options) : options_(options) {
  if (!(options_.pause_tilt_rad > 0.0) || !(options_.relift_tilt_rad > options_.pause_tilt_rad))
    throw std::invalid_argument("TouchdownGuard: need 0 < pause tilt < relift tilt");
  velocity_mps_ = options_.lowering_speed_mps;
}

double TouchdownGuard::tilt_rad(double roll_rad, double pitch_rad) {
  // Body z in the world for R = Rz * Ry(pitch) * Rx(roll): its z component is cos(roll) cos(pitch).
  return std::acos(std::clamp(std::cos(roll_rad) * std::cos(pitch_rad), -1.0, 1.0));
}

LoweringAction TouchdownGuard::update(double t_s, double roll_rad, double pitch_rad,
                                      double released_m) {
  const double tilt = tilt_rad(roll_rad, pitch_rad);
  const LoweringAction before = action_;
  if (tilt < options_.relift_tilt_rad) relift_armed_ = true;
  if (action_ == LoweringAction::kRelift && released_m > relift_target_m_) {
    // Finish the re-lift before judging the attitude again.
    calm_since_s_ = -1.0;
  } else if (tilt >= options_.relift_tilt_rad && relift_armed_) {
    // A bad angle: lift by relift_distance_m from here. Lift once per bad spell: a
    // robot still hanging at a bad angle afterwards is held, not lifted further.
    relift_target_m_ = std::max(0.0, released_m - options_.relift_distance_m);
    relift_armed_ = false;
    action_ = LoweringAction::kRelift;
    calm_since_s_ = -1.0;
  } else if (tilt >= options_.pause_tilt_rad) {
    action_ = LoweringAction::kPause;
    calm_since_s_ = -1.0;
  } else {
    if (action_ != LoweringAction::kLower) {
      if (calm_since_s_ < 0.0) calm_since_s_ = t_s;
      if (t_s - calm_since_s_ >= options_.settle_time_s)
        action_ = LoweringAction::kLower;
      else
        action_ = LoweringAction::kPause;
    }
  }
  velocity_mps_ = action_ == LoweringAction::kLower    ? options_.lowering_speed_mps
                  : action_ == LoweringAction::kRelift ? -options_.relift_speed_mps
                                                       : 0.0;
  if (action_ != before)
    spdlog::info("tether lowering: {} -> {} at t = {:.3f} s (tilt {:.1f} deg, l_t = {:.3f} m)",
                 to_string(before), to_string(action_), t_s, tilt * 180.0 / std::numbers::pi,
                 released_m);
  return action_;
}

}  // namespace ferret::tether
