#pragma once
// The winch's taut-tether control loop: a narrow interface with two named
// implementations, "mpc" (TautTetherMpc) and "baseline" (FeedForwardPid). Both see
// the same observation: the winch encoder, the winch's tension estimate, and the
// miniUGV's pose, desired velocity and desired acceleration as received over the
// link (with its age). Both output a spool velocity command (positive pays out).
// The controllers are built by name from tether_controllers() (winch_controllers.hpp).

#include <string_view>

#include "ferret/tether_model/tether_observation.hpp"

namespace ferret::tether {

class TetherController {
 public:
  virtual ~TetherController() = default;
  [[nodiscard]] virtual std::string_view name() const = 0;
  /// Forget integrators and the previous command.
  virtual void reset() = 0;
  /// One control cycle; returns the spool velocity command in m/s (positive pays out).
  [[nodiscard]] virtual double step(const TetherObservation& obs) = 0;
};

}  // namespace ferret::tether
