#include "ferret/tether_model/simulated_winch.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ferret::tether {

SimulatedWinch::SimulatedWinch(Options options)
    : options_(options), released_m_(options.initial_released_m) {
  if (!(options_.max_speed_mps > 0.0) || !(options_.max_acceleration_mps2 > 0.0) ||
      !(options_.effective_mass_kg > 0.0) || !(options_.max_force_n > 0.0) ||
      !(options_.velocity_gain_n_per_mps > 0.0))
    throw std::invalid_argument("SimulatedWinch: limits, mass and gain must be > 0");
  if (options_.initial_released_m < 0.0 || options_.initial_released_m > options_.total_length_m)
    throw std::invalid_argument("SimulatedWinch: initial l_t outside [0, L]");
}

void SimulatedWinch::command_velocity_mps(double speed_mps) {
  command_mps_ = std::clamp(speed_mps, -options_.max_speed_mps, options_.max_speed_mps);
}

WinchState SimulatedWinch::read_state() { return {released_m_, speed_mps_, tension_n_}; }

void SimulatedWinch::advance(double dt_s, double tension_n) {
  if (!(dt_s > 0.0)) return;
  tension_n_ = tension_n;
  const double step = options_.max_acceleration_mps2 * dt_s;
  target_mps_ =
      torque_enabled_ ? std::clamp(command_mps_, target_mps_ - step, target_mps_ + step) : 0.0;
  if (torque_enabled_) {
    const double error = target_mps_ - speed_mps_;
    integral_n_ = std::clamp(integral_n_ + options_.velocity_integral_gain_n_per_m * error * dt_s,
                             -options_.max_force_n, options_.max_force_n);
    motor_force_n_ = std::clamp(options_.velocity_gain_n_per_mps * error + integral_n_,
                                -options_.max_force_n, options_.max_force_n);
  } else {
    integral_n_ = 0.0;
    motor_force_n_ = 0.0;
  }
  // Friction opposes motion; at rest, static friction holds up to the Coulomb level.
  const double drive =
      motor_force_n_ + tension_n - options_.viscous_friction_n_per_mps * speed_mps_;
  double next_speed;
  if (std::abs(speed_mps_) < 1e-9 && std::abs(drive) <= options_.coulomb_friction_n) {
    next_speed = 0.0;
  } else {
    const double friction = speed_mps_ != 0.0
                                ? std::copysign(options_.coulomb_friction_n, speed_mps_)
                                : std::copysign(options_.coulomb_friction_n, drive);
    next_speed = speed_mps_ + (drive - friction) / options_.effective_mass_kg * dt_s;
    // Coulomb friction stops the spool rather than reversing it within a step.
    if (speed_mps_ != 0.0 && next_speed * speed_mps_ < 0.0 &&
        std::abs(drive) <= options_.coulomb_friction_n)
      next_speed = 0.0;
  }
  released_m_ += 0.5 * (speed_mps_ + next_speed) * dt_s;
  speed_mps_ = next_speed;
  // The line is fastened to the spool at both ends of its travel.
  if (released_m_ <= 0.0 && speed_mps_ < 0.0) {
    released_m_ = 0.0;
    speed_mps_ = 0.0;
  }
  if (released_m_ >= options_.total_length_m && speed_mps_ > 0.0) {
    released_m_ = options_.total_length_m;
    speed_mps_ = 0.0;
  }
}

}  // namespace ferret::tether
