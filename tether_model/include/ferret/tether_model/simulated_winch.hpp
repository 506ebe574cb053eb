#pragma once
// Simulated winch: a spool with inertia and friction driven by a servo in velocity
// mode (a profile generator limits the acceleration of the target, a PI velocity loop
// with a force limit tracks it). The tether's tension pulls line off
// the spool. Time advances only through advance(), so runs are deterministic.

#include "ferret/tether_model/winch.hpp"

namespace ferret::tether {

class SimulatedWinch final : public Winch {
 public:
  struct Options {
    double max_speed_mps = 0.6;             ///< servo speed limit at the spool surface
    double max_acceleration_mps2 = 2.0;     ///< profile acceleration
    double effective_mass_kg = 0.4;         ///< spool + rotor inertia seen at the line, J / r^2
    double max_force_n = 40.0;              ///< stall torque / spool radius
    double velocity_gain_n_per_mps = 16.0;  ///< m / K = 0.025 s velocity-loop time constant
    /// The velocity loop's I term: holds the line against the tether's pull (a load F
    /// gives F / Ki of line before it is held); 640 with the P gain is 40 rad/s, damping 0.5.
    double velocity_integral_gain_n_per_m = 640.0;
    double coulomb_friction_n = 0.3;
    double viscous_friction_n_per_mps = 0.5;
    double total_length_m = 15.0;  ///< L: the line ends here (a hard stop)
    double initial_released_m = 0.0;
  };

  explicit SimulatedWinch(Options options);

  void set_torque_enabled(bool enabled) override { torque_enabled_ = enabled; }
  void command_velocity_mps(double speed_mps) override;
  [[nodiscard]] WinchState read_state() override;

  /// Integrates the spool over dt_s with the tether pulling `tension_n` on the line.
  void advance(double dt_s, double tension_n);

  [[nodiscard]] double released_m() const { return released_m_; }
  [[nodiscard]] double speed_mps() const { return speed_mps_; }
  [[nodiscard]] double profile_target_mps() const { return target_mps_; }
  [[nodiscard]] double motor_force_n() const { return motor_force_n_; }
  [[nodiscard]] const Options& options() const { return options_; }

 private:
  Options options_;
  bool torque_enabled_ = true;
  double command_mps_ = 0.0;
  double target_mps_ = 0.0;  ///< profile generator output
  double released_m_ = 0.0;
  double speed_mps_ = 0.0;
  double motor_force_n_ = 0.0;
  double integral_n_ = 0.0;  ///< I-term force of the velocity loop
  double tension_n_ = 0.0;
};

}  // namespace ferret::tether
