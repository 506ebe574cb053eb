#pragma once
// A reel-in command limited so that a miniUGV driving off cannot take the line taut.

#include "ferret/tether_model/winch_limits.hpp"

namespace ferret::tether {

/// The miniUGV can drive off without warning (a decision cycle that ends a stop): while
/// the spool reels in, the slack left must cover what the miniUGV takes before the
/// spool has turned round and caught up with it. With the miniUGV starting from its
/// present required-length rate at `ugv_acceleration_mps2` up to `ugv_speed_mps`, and
/// the spool answering `reaction_s` later at `spool_acceleration_fraction` of its
/// limit, the guard raises a command whose worst-case loss would leave less than
/// `min_slack_m`. Off (ugv_speed_mps 0) by default: the tether study's controllers as
/// published; the mission turns it on.
struct ReelInGuard {
  double ugv_speed_mps = 0.0;  ///< the fastest the tethered miniUGV drives; 0: off
  double ugv_acceleration_mps2 = 2.0;
  double reaction_s = 0.06;  ///< a control period, the servo's lag and the link's age
  double spool_acceleration_fraction = 0.9;
  double min_slack_m = 0.02;

  [[nodiscard]] bool on() const { return ugv_speed_mps > 0.0; }
  /// Line the miniUGV takes beyond the spool, starting now, if the spool turns at `u_mps`
  /// and the required length grows at `rate_mps` (both positive out).
  [[nodiscard]] double worst_loss_m(double u_mps, double rate_mps, const WinchLimits& limits) const;
  /// `command` raised (never lowered) so the worst loss stays within `slack_m` less
  /// min_slack_m, within [lo, hi] (the command's rate and speed limits).
  [[nodiscard]] double limit(double command, double slack_m, double rate_mps,
                             const WinchLimits& limits, double lo, double hi) const;
};

}  // namespace ferret::tether
