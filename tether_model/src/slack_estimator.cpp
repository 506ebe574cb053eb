#include "ferret/tether_model/slack_estimator.hpp"

#include <algorithm>

namespace ferret::tether {

double SlackEstimator::estimate_m(double released_m, double required_m,
                                  double winch_tension_n) const {
  const double geometric = released_m - required_m;
  const double pull = winch_tension_n - tension.hanging_weight_n;
  if (pull <= guard_n) return geometric;
  return std::min(geometric, -pull / tension.stiffness_npm(released_m));
}

}  // namespace ferret::tether
