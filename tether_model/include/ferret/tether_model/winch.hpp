#pragma once
// The winch as the controllers see it: a narrow hardware interface with a simulated
// backend (SimulatedWinch, "sim") and the Dynamixel servo (DynamixelWinch, "hw").

namespace ferret::tether {

struct WinchState {
  double released_m = 0.0;  ///< l_t, from the spool encoder
  double speed_mps = 0.0;   ///< spool surface speed, positive pays out
  double tension_n = 0.0;   ///< tether tension estimated from the motor current
};

class Winch {
 public:
  virtual ~Winch() = default;
  /// Powers the motor (velocity control) or lets it go limp.
  virtual void set_torque_enabled(bool enabled) = 0;
  /// Spool surface speed command in m/s (positive pays out); the backend clamps to its limit.
  virtual void command_velocity_mps(double speed_mps) = 0;
  [[nodiscard]] virtual WinchState read_state() = 0;
};

}  // namespace ferret::tether
