#pragma once
// A link watchdog: how long since the peer was last heard, on the controller's clock
// (simulated or steady, never the wall clock), and whether that is past a timeout. The
// miniUGV stops and holds when the UAV falls silent; the winch holds its length when
// the miniUGV does (docs/link.md, "Watchdogs"). This is the mechanism only; the
// controllers decide what holding means.

#include "ferret/core/clock.hpp"

namespace ferret::link {

class Watchdog {
 public:
  /// @throws std::invalid_argument unless timeout_s is finite and > 0
  /// The clock must outlive the watchdog.
  Watchdog(const Clock& clock, double timeout_s);

  /// The peer was heard now (an accepted message; never a rejected one).
  void heard();
  /// Forgets the peer: expired() until it is heard again.
  void reset();

  /// True when the peer was never heard, or not for more than timeout_s. A peer that
  /// never spoke counts as silent: a robot does not move on a link that never came up.
  [[nodiscard]] bool expired() const;
  /// Seconds since heard(); +infinity before the first.
  [[nodiscard]] double since_heard_s() const;
  [[nodiscard]] bool ever_heard() const { return ever_heard_; }
  [[nodiscard]] double timeout_s() const { return timeout_s_; }

 private:
  const Clock* clock_;
  double timeout_s_;
  bool ever_heard_ = false;
  double heard_at_s_ = 0.0;
};

}  // namespace ferret::link
