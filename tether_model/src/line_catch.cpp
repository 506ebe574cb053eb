#include "ferret/tether_model/line_catch.hpp"

#include <cmath>
#include <limits>

#include "ferret/tether_model/tether_controller.hpp"

namespace ferret::tether {

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
