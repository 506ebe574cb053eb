#include "ferret/tether_model/line_catch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ferret::tether {

double LineCatchLimit::stretch_m(double line_m) const {
  // The same floor as TensionModel::stiffness_npm: a few cm of line is not a rigid rod.
  return pull_budget_n * std::max(line_m, 0.1) / axial_stiffness_n;
}

double LineCatchLimit::speed_mps(double line_m) const {
  if (!on()) return std::numeric_limits<double>::infinity();
  const double a = spool_acceleration_mps2, t = reaction_s;
  // r^2 / (2 a) + r t = stretch, the positive root.
  return a * (std::sqrt(t * t + 2.0 * stretch_m(line_m) / a) - t);
}

}  // namespace ferret::tether
