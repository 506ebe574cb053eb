#pragma once
// The miniUGV mission's plain types (mini_ugv_mission.hpp is the controller that runs
// them): its options, its states and outcomes with the words logs and report.json use.
// A simulation's settings and results hold these without the controller. The functions
// are defined beside the controller (mini_ugv_mission.cpp).

#include <optional>
#include <string>
#include <string_view>

#include "ferret/tether_model/line_catch.hpp"
#include "ferret/ugv/explore_options.hpp"

namespace ferret {

enum class UgvMissionState {
  kIdle,
  kExplore,
  kTrack,
  kTurn,
  kGrasp,
  kReturn,
  kAwaitRetract,
  kDone
};
[[nodiscard]] std::string_view to_string(UgvMissionState state);

enum class UgvMissionOutcome {
  kNone,             ///< not done yet
  kObjectRetrieved,  ///< at the entry with the object on the magnet, lifted out
  kNoObject,         ///< explored everything reachable, no object: a result, not a failure
  kGraspFailed,      ///< no contact after every attempt
  kTrackLost,        ///< the object out of sight too long while servoing
  kBatteryLow,       ///< returned because the battery would not cover more search
  kSearchTimeout,    ///< the search's time limit
  kReturnFailed,     ///< no way back to the entry within the return's timeout
  kRetractTimeout,   ///< at the entry, but nobody lifted it out
  kAborted,          ///< stop() (the UAV or the operator)
  kRecalled,         ///< recall(): the UAV called it back before the search ended
};
[[nodiscard]] std::string_view to_string(UgvMissionOutcome outcome);

struct UgvMissionOptions {
  ExploreOptions explore;
  /// Hold the search within the tether's reach: unless `explore.tether_budget_m` is
  /// set, the budget is the mission's L - l_0 (tether.total_length_m - entry_offset_m).
  bool tether_aware = true;
  double standoff_m = 0.3;  ///< d_min: the servo stops this far (centre to object)
  double servo_max_speed_mps = 0.3;
  double servo_gain_per_s = 1.0;      ///< v = gain (d - d_min)
  double servo_yaw_gain_per_s = 3.0;  ///< w = gain * bearing
  double track_lost_s = 3.0;          ///< no detection this long: lost
  double track_timeout_s = 30.0;
  double turn_timeout_s = 10.0;
  double rear_offset_m = 0.065;  ///< centre to the EPM face (half of 130 mm)
  double grasp_speed_mps = 0.1;
  double grasp_overshoot_m = 0.05;  ///< back up this much past the expected contact
  int grasp_attempts = 3;
  double grasp_timeout_s = 15.0;  ///< per attempt
  double explore_timeout_s = 600.0;
  double entry_tolerance_m = 0.2;  ///< "at the entry"
  double return_timeout_min_s =
      30.0;  ///< and 4x the planned path's time at full speed, plus a half turn a corner
  double retract_timeout_s = 120.0;
  /// Driving time of a full battery at full speed, s (the real one: about 18 min); the
  /// return estimate divides the way back by half the top speed.
  double battery_endurance_s = 18.0 * 60.0;
  double battery_reserve_fraction = 0.05;
  /// A bump: told to drive forwards, the base has not moved for this long (the mission
  /// YAML's ugv.base.stall_time_s). Longer than the base takes to move from rest on its
  /// odometry, or every start is a bump.
  double bump_time_s = 0.3;
  /// On its tether, the robot's top speed is what the winch can follow should the line
  /// catch on a corner no map holds (docs/mission.md, "The line's speed"); off by
  /// default, the mission fills it from the winch.
  tether::LineCatchLimit line_catch;

  /// Checks every value (finite, positive where it must be). Throws InputError naming
  /// the field with `source` as the file.
  void validate(const std::string& source) const;
  /// The longest the controller stays in `state` before its timeout moves it on (none:
  /// idle and done; return, whose timeout the controller sets from the path it plans).
  /// The simulation's invariants check it (docs/safety.md).
  [[nodiscard]] std::optional<double> state_timeout_s(UgvMissionState state) const;
};

}  // namespace ferret
