#pragma once
// Operating modes from the released tether length l_t (paper sect. III-A): aerial
// (l_t = 0), lowering (0 < l_t <= Z_W) and hidden-space operations (l_0 <= l_t <= L),
// with hysteresis so that encoder noise at a boundary does not toggle the mission,
// and the IMU touchdown-angle check that pauses or re-lifts a lowering.

#include <string_view>
#include <vector>

#include "ferret/tether_model/tether_params.hpp"

namespace ferret::tether {

enum class TetherMode { kAerial, kLowering, kHiddenSpace };

[[nodiscard]] std::string_view to_string(TetherMode mode);

struct ModeTransition {
  double t_s = 0.0;
  TetherMode from = TetherMode::kAerial;
  TetherMode to = TetherMode::kAerial;
  double released_m = 0.0;  ///< l_t at the switch
};

/// Classifies l_t into a mode with hysteresis. Boundaries: aerial while l_t <=
/// aerial_tolerance_m; lowering above aerial_tolerance_m + hysteresis_m; hidden-space
/// operations from l_0 + hysteresis_m up, back to lowering below l_0 - hysteresis_m.
/// The paper assumes l_0 - Z_W ~ 0; a gap Z_W < l_t < l_0 counts as lowering (the
/// miniUGV is still on its way to the entry).
class TetherModeSwitcher {
 public:
  struct Options {
    double total_length_m = 15.0;       ///< L
    double entry_offset_m = 1.0;        ///< l_0
    double uav_height_m = 1.0;          ///< Z_W (height of the UAV's COM above the ground)
    double hysteresis_m = 0.02;         ///< half-width of the band around each boundary
    double aerial_tolerance_m = 0.005;  ///< l_t at or below this counts as fully retracted

    /// L and l_0 from the mission (MissionConfig::tether), Z_W from the flight.
    [[nodiscard]] static Options from_mission(const TetherParams& tether, double uav_height_m) {
      Options o;
      o.total_length_m = tether.total_length_m;
      o.entry_offset_m = tether.entry_offset_m;
      o.uav_height_m = uav_height_m;
      return o;
    }
  };

  /// Throws std::invalid_argument for inconsistent options (l_0 > L, negative values).
  explicit TetherModeSwitcher(Options options, TetherMode initial = TetherMode::kAerial);

  /// Feeds one l_t reading; logs and records a transition when the mode changes.
  TetherMode update(double t_s, double released_m);

  [[nodiscard]] TetherMode mode() const { return mode_; }
  [[nodiscard]] const std::vector<ModeTransition>& transitions() const { return transitions_; }
  [[nodiscard]] const Options& options() const { return options_; }

 private:
  Options options_;
  TetherMode mode_;
  std::vector<ModeTransition> transitions_;
};

/// What the winch does during lowering, from the miniUGV's IMU attitude.
enum class LoweringAction { kLower, kPause, kRelift };

[[nodiscard]] std::string_view to_string(LoweringAction action);

/// Touchdown-angle check (paper sect. III, tether attachment): the miniUGV must
/// touch down close to level. Tilt below pause_tilt_rad: keep lowering; between
/// pause and relift: hold; above relift_tilt_rad: lift by relift_distance_m (once
/// per bad spell), then hold until the tilt has been back under the pause limit for
/// settle_time_s.
class TouchdownGuard {
 public:
  struct Options {
    double pause_tilt_rad = 0.35;   ///< ~20 deg
    double relift_tilt_rad = 0.61;  ///< ~35 deg
    double relift_distance_m = 0.10;
    double settle_time_s = 0.5;
    double lowering_speed_mps = 0.2;
    double relift_speed_mps = 0.2;
  };

  explicit TouchdownGuard(Options options);

  /// @param roll_rad, pitch_rad miniUGV attitude from its IMU
  /// @param released_m current l_t
  /// @return the action and sets the spool velocity to command (positive pays out)
  LoweringAction update(double t_s, double roll_rad, double pitch_rad, double released_m);

  [[nodiscard]] double spool_velocity_mps() const { return velocity_mps_; }
  [[nodiscard]] LoweringAction action() const { return action_; }

  /// Tilt of the body z axis from vertical for a roll/pitch attitude.
  [[nodiscard]] static double tilt_rad(double roll_rad, double pitch_rad);

 private:
  Options options_;
  LoweringAction action_ = LoweringAction::kLower;
  double velocity_mps_ = 0.0;
  double relift_target_m_ = 0.0;
  double calm_since_s_ = -1.0;
  bool relift_armed_ = true;  ///< re-armed once the tilt drops below the relift limit
};

}  // namespace ferret::tether
