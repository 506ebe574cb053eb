#include "ferret/tether_model/line_catch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ferret/tether_model/taut_control_options.hpp"

namespace ferret::tether {

LineCatchLimit LineCatchLimit::for_winch(const TautControlOptions& w) {
  const TensionModel& line = w.slack_estimator.tension;
  LineCatchLimit c;
  c.pull_budget_n =
      std::max(0.0, line.max_tension_n - line.hanging_weight_n - w.slack_estimator.guard_n);
  c.axial_stiffness_n = line.axial_stiffness_n;
  c.reaction_s = 2.0 * w.control_period_s + w.limits.velocity_time_constant_s;
  c.spool_acceleration_mps2 =
      w.reel_in_guard.spool_acceleration_fraction * w.limits.max_acceleration_mps2;
  return c;
}

double LineCatchLimit::stretch_m(double line_m) const {
  TensionModel line;  // its spring rate, with its floor for a few cm of line
  line.axial_stiffness_n = axial_stiffness_n;
  return pull_budget_n / line.stiffness_npm(line_m);
}

double LineCatchLimit::speed_mps(double line_m) const {
  if (!on()) return std::numeric_limits<double>::infinity();
  const double a = spool_acceleration_mps2, t = reaction_s;
  // r^2 / (2 a) + r t = stretch, the positive root.
  return a * (std::sqrt(t * t + 2.0 * stretch_m(line_m) / a) - t);
}

}  // namespace ferret::tether
