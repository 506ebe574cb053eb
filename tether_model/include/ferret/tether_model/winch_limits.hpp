#pragma once
// The winch's and the tether's limits (the controllers' and the simulation's).

namespace ferret::tether {

/// Winch and tether limits shared by the controllers and the simulation.
struct WinchLimits {
  double total_length_m = 15.0;             ///< L: l_t never exceeds it
  double max_speed_mps = 0.6;               ///< spool surface speed (MX-64: 63 rpm on a 9 cm spool)
  double max_acceleration_mps2 = 2.0;       ///< profile acceleration
  double velocity_time_constant_s = 0.025;  ///< first-order lag of the servo's velocity loop
};

}  // namespace ferret::tether
