#pragma once
// How fast the miniUGV may drive on its line. Where the line catches on a corner no map
// holds (the robot's tether model is short of the real line), the line grows at the
// robot's speed until the winch notices the pull and speeds its spool up to match;
// meanwhile the line stretches, and a short line is stiff. Feedback alone cannot keep
// that under the tension limit at any speed, so the speed is held to what it can.

namespace ferret::tether {

struct TautControlOptions;

struct LineCatchLimit {
  /// The pull the stretch may add before the winch has caught up (N); 0: no limit.
  double pull_budget_n = 0.0;
  double axial_stiffness_n = 1500.0;     ///< EA of the line (N)
  double reaction_s = 0.065;             ///< from the catch to the spool speeding up
  double spool_acceleration_mps2 = 1.8;  ///< how fast the spool then speeds up

  /// The winch's: the pull from the hanging weight up to the tension limit less the
  /// guard's threshold (what the slack estimator calls a snag), noticed after two
  /// control periods and the servo's lag, the spool then speeding up at the reel-in
  /// guard's share of its acceleration.
  [[nodiscard]] static LineCatchLimit for_winch(const TautControlOptions& winch);

  [[nodiscard]] bool on() const { return pull_budget_n > 0.0; }
  /// The stretch that pulls the budget on `line_m` of line: a line that may be at most
  /// this much longer than the robot's model of it cannot pull more, at any speed.
  [[nodiscard]] double stretch_m(double line_m) const;
  /// The top speed on `line_m` of line (winch to robot): the line growing at r
  /// stretches by r t + r^2 / (2 a) before the spool pays out at r, and `line_m` of
  /// line stretched by x pulls EA x / line_m. Infinite when off.
  [[nodiscard]] double speed_mps(double line_m) const;
};

}  // namespace ferret::tether
