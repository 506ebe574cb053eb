#pragma once
// The tether as an elastic line: its tension from its length and slack.

namespace ferret::tether {

/// Elastic tether: tension = EA / l * stretch (stretch = -slack when negative).
struct TensionModel {
  double axial_stiffness_n = 1500.0;  ///< EA of a 1 mm nylon line
  double hanging_weight_n =
      0.5;  ///< weight of the hanging part (winch to entry): the winch always feels it
  double max_tension_n = 10.0;  ///< above this the tether drags the miniUGV: an over-tension event

  /// Spring rate of `length_m` of tether (N/m).
  [[nodiscard]] double stiffness_npm(double length_m) const;
  /// Tension of `length_m` of tether with slack `slack_m` (0 when slack).
  [[nodiscard]] double tension_n(double length_m, double slack_m) const;
};

}  // namespace ferret::tether
