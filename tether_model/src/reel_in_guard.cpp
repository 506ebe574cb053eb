#include "ferret/tether_model/reel_in_guard.hpp"

#include <algorithm>
#include <cmath>

namespace ferret::tether {

double ReelInGuard::worst_loss_m(double u_mps, double rate_mps, const WinchLimits& limits) const {
  // Stepped: the two speed profiles are piecewise linear with a delay and saturation,
  // and the loss is the area where the miniUGV's runs ahead of the spool's.
  constexpr double kDt = 0.005;
  const double a_spool = spool_acceleration_fraction * limits.max_acceleration_mps2;
  // Beyond the spool's own speed no slack protects the line: that is the tension guard's.
  const double top = std::min(std::max(rate_mps, ugv_speed_mps), limits.max_speed_mps);
  double u = u_mps, r = rate_mps, loss = 0.0;
  for (double t = 0.0; t < 10.0; t += kDt) {
    if (r >= top && u >= r) break;  // caught up with a miniUGV at full speed
    loss += std::max(0.0, r - u) * kDt;
    r = std::min(top, r + ugv_acceleration_mps2 * kDt);
    if (t >= reaction_s) u = std::min(limits.max_speed_mps, u + a_spool * kDt);
  }
  return loss;
}

double ReelInGuard::limit(double command, double slack_m, double rate_mps,
                          const WinchLimits& limits, double lo, double hi) const {
  if (!on() || !std::isfinite(slack_m) || !std::isfinite(rate_mps)) return command;
  const double budget = slack_m - min_slack_m;
  if (command >= hi || worst_loss_m(command, rate_mps, limits) <= budget) return command;
  if (worst_loss_m(hi, rate_mps, limits) > budget) return std::max(command, hi);
  double a = std::max(command, lo), b = hi;  // the loss falls as the command rises
  for (int i = 0; i < 30; ++i) {
    const double m = 0.5 * (a + b);
    (worst_loss_m(m, rate_mps, limits) <= budget ? b : a) = m;
  }
  return std::max(command, b);
}

}  // namespace ferret::tether
