#pragma once
// The slack from geometry, overruled by the tension when the line is caught (a snag).

#include "ferret/tether_model/tension_model.hpp"

namespace ferret::tether {

/// Slack the controllers act on: geometric slack l_t - l_req from the (latency-
/// compensated) miniUGV position, but never more than the tension implies. A tension
/// above `guard_n` with geometric slack means the tether is caught somewhere (a snag):
/// the measured stretch wins, so the winch stops reeling in against it.
struct SlackEstimator {
  TensionModel tension;
  double guard_n = 1.5;  ///< tension (above the hanging weight) that overrides geometry

  [[nodiscard]] double estimate_m(double released_m, double required_m,
                                  double winch_tension_n) const;
};

}  // namespace ferret::tether
