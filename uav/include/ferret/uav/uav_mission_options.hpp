#pragma once
// The UAV mission's plain types (uav_mission.hpp is the controller that runs them): its
// options, its states and outcomes with the words logs and report.json use, and what came
// of each hidden space it found. A simulation's settings and results hold these without
// the controller. The functions are defined beside the controller (uav_mission.cpp).

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/planning/mission_config.hpp"
#include "ferret/tether_model/taut_control_options.hpp"
#include "ferret/tether_model/tether_modes.hpp"
#include "ferret/tether_model/winch_controllers.hpp"
#include "ferret/uav/landing_zone.hpp"
#include "ferret/uav/marker_detector.hpp"
#include "ferret/uav/opening_locator.hpp"

namespace ferret {

enum class UavMissionState {
  kIdle,
  kTakeoff,
  kSearch,
  kApproach,
  kSurvey,
  kLand,
  kLower,
  kUgvOps,
  kRetract,
  kLiftoff,
  kDeliver,
  kDrop,
  kReturnHome,
  kLandHome,
  kDone
};
[[nodiscard]] std::string_view to_string(UavMissionState state);

enum class UavMissionOutcome {
  kNone,
  kSearchComplete,  ///< the whole pattern flown, landed at home
  kFlightBudget,    ///< the battery only covered the way home: returned early, landed
  kTakeoffFailed,   ///< never reached the search altitude
  kRetractFailed,   ///< the miniUGV could not be reeled in (the UAV stays landed)
  kDeliveryFailed,  ///< no flight (or none in time) to the drop zone with the object: landed at
                    ///< home with it
  kAborted,         ///< stop()
};
[[nodiscard]] std::string_view to_string(UavMissionOutcome outcome);

/// How the miniUGV goes down by a hidden space (uav.release).
enum class ReleaseMode {
  kLand,   ///< beside the opening, on a safe zone the depth frames show within l_0 of it
  kHover,  ///< always from a hover over the opening, no survey
};
/// "land", "hover": the YAML's words.
[[nodiscard]] std::string_view to_string(ReleaseMode release);

/// What the UAV does when no safe landing zone is within reach (uav.no_landing_zone).
enum class NoLandingZone {
  kHover,  ///< lower from a hover over the opening's standoff point
  kSkip,   ///< leave the hidden space and search on
};
/// "hover", "skip": the YAML's and --no-landing-zone's words.
[[nodiscard]] std::string_view to_string(NoLandingZone choice);
/// The choice `word` names. @throws InputError(source, field, "hover or skip", word).
[[nodiscard]] NoLandingZone parse_no_landing_zone(const std::string& word,
                                                  const std::string& source,
                                                  const std::string& field = {});

/// What came of a hidden space the UAV found.
enum class VisitState { kDetected, kSkipped, kServiced };
/// "detected", "skipped", "serviced": the words of report.json.
[[nodiscard]] std::string_view to_string(VisitState state);

struct UavMissionOptions {
  /// The area to search, [x0, y0, x1, y1] (m) in the world.
  Eigen::Vector4d search_area_m{-25.0, -25.0, 25.0, 25.0};
  double search_altitude_m = 4.0;
  double search_speed_mps = 3.0;
  double cruise_speed_mps = 5.0;
  /// Distance between the pattern's legs; 0: from the marker camera (twice the lateral
  /// reach, at half the range where a marker still spans min_marker_side_px).
  double leg_spacing_m = 0.0;
  int passes = 2;               ///< 1: legs along x; 2: then legs along y
  double frame_period_s = 0.5;  ///< marker frames while searching
  double waypoint_tolerance_m = 0.4;
  /// The deceleration the flight controller stops with (0.8 of the M100 URDF's 2 m/s^2):
  /// where a new path starts when one is planned in flight.
  double braking_accel_mps2 = 1.6;
  /// The markers the team placed: where each one's opening lies in its frame.
  std::vector<OpeningInMarker> openings;
  /// The markers' family, dictionary and size: the world's (its first hidden space's
  /// marker) unless the mission YAML sets `uav.marker`.
  MarkerDetectorOptions marker;
  bool marker_from_mission = false;  ///< `uav.marker` was set: the world's does not replace it
  /// Detections of the same marker needed before the UAV goes (a single frame can lie).
  int confirm_detections = 2;
  LandingZoneDetector::Options landing;
  double survey_height_m = 3.5;    ///< above the opening, for the depth frames
  double survey_standoff_m = 1.0;  ///< out from the opening, horizontally
  int survey_views = 3;            ///< survey points tried (round the opening) before giving up
  /// Depth frames the hover at a survey point takes and fuses before it judges the ground
  /// (fuse_depth_frames: the noise of a cell falls with their square root; 8 frames of a
  /// D415 at 30 Hz take 0.27 s).
  int survey_frames = 8;
  /// A hover that finds no safe zone in its frames looks longer before it tries the next
  /// view: twice the frames (all of them fused), again, up to this many
  /// (hover_frames_after_miss; at most survey_frames: never). What 8 frames' noise hides
  /// at 4 m, 16, 32 or 64 show: 64 frames of a D415 at 30 Hz take 2.1 s.
  int survey_frames_max = 64;
  /// How the miniUGV goes down: land (beside the opening, on a safe zone the depth
  /// frames show within l_0 of it; none: no_landing_zone decides) or hover (always from
  /// a hover over the opening, no survey: for ground the team knows is unsafe).
  ReleaseMode release = ReleaseMode::kLand;
  /// No safe landing zone within reach: hover over the opening or skip it.
  NoLandingZone no_landing_zone = NoLandingZone::kHover;
  double hover_standoff_m = 0.6;     ///< out from the opening
  double touchdown_height_m = 0.25;  ///< the winch above the ground when landed (Z_W)
  TetherParams tether;               ///< L and l_0
  tether::TouchdownGuard::Options touchdown;
  std::string winch_controller = "mpc";  ///< tether::tether_controller_names()
  /// The winch's control (its slack reference is raised to 10 cm by default: the
  /// miniUGV's tether model, from its own map's corners, differs from the real tether
  /// by a few centimetres, and a taut line has no room for that), and the reel-in guard
  /// on for a miniUGV held to 0.8 of the spool's speed (the mission sets its real limits).
  tether::TautControlOptions winch_control = default_winch_control();
  [[nodiscard]] static tether::TautControlOptions default_winch_control() {
    tether::TautControlOptions o;
    o.slack_reference_m = 0.10;
    o.reel_in_guard.ugv_speed_mps = 0.8 * o.limits.max_speed_mps;
    // The MPC's estimation of a miniUGV that does not do exactly what it says
    // (docs/tether.md): its velocity error and its response model, identified online.
    o.ugv_velocity_error = tether::UgvVelocityErrorOptions::estimated();
    o.ugv_response_identification = tether::UgvResponseIdentificationOptions::on();
    return o;
  }
  /// Each winch controller's own options (`uav.winch_control.mpc`, `.baseline` of the
  /// mission YAML); the MPC estimates the miniUGV as winch_control has it.
  tether::WinchControllerOptions winch_controllers =
      tether::WinchControllerOptions::following(default_winch_control());
  double retract_speed_mps = 0.4;
  /// How fast the UAV counts on the miniUGV coming back along its tether when it
  /// recalls it (hovering on a low battery): half its tethered speed, for the turns.
  double ugv_return_speed_mps = 0.2;
  Eigen::Vector2d drop_zone_W = Eigen::Vector2d::Zero();
  double drop_altitude_m = 3.0;
  double drop_time_s = 3.0;  ///< the EPM off and the object falling clear
  /// Flight endurance of a full battery (the M100 with its payload: about 20 min) and
  /// the reserve kept over what the way home costs at cruise speed.
  double flight_endurance_s = 20.0 * 60.0;
  double battery_reserve_fraction = 0.10;
  double takeoff_timeout_s = 40.0;
  double approach_timeout_s = 120.0;
  double survey_timeout_s = 60.0;
  double land_timeout_s = 60.0;
  double lower_timeout_s = 60.0;
  double ugv_ops_timeout_s = 25.0 * 60.0;
  double retract_timeout_s = 120.0;
  double deliver_timeout_s = 240.0;
  double return_timeout_s = 300.0;

  /// Throws InputError(source, field, ...) for a value out of range.
  void validate(const std::string& source) const;
  /// The longest the controller stays in `state` before its timeout moves it on (none:
  /// the state has no timeout of its own: idle, search, bounded by the flight budget,
  /// and done). The simulation's invariants check it (docs/safety.md).
  [[nodiscard]] std::optional<double> state_timeout_s(UavMissionState state) const;
};

/// One hidden space the UAV found, and what came of it.
struct HiddenSpaceVisit {
  int marker_id = -1;
  OpeningEstimate opening;         ///< from the nearest frame of its marker
  double marker_distance_m = 1e9;  ///< camera to marker in that frame
  double detected_s = 0.0;
  std::size_t pattern_index = 0;  ///< the pattern waypoint the UAV was flying to then
  VisitState state = VisitState::kDetected;
  std::string note;     ///< why skipped, or why the object was not delivered
  bool landed = false;  ///< landed beside it (false: hovered)
  std::optional<LandingZone> landing_zone;
  double deployed_s = -1.0;
  double retracted_s = -1.0;
  std::string ugv_outcome;
  bool object_retrieved = false;  ///< the miniUGV came out with it
  bool object_dropped = false;    ///< released in the drop zone
  double max_released_m = 0.0;    ///< longest l_t while the miniUGV worked
};

}  // namespace ferret
