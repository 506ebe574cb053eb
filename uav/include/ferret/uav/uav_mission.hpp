#pragma once
// The UAV's mission controller (paper sect. III):
//   takeoff      climb to the search altitude
//   search       a coverage pattern over the area (legs spaced by what the marker
//                camera resolves, a second pass across the first), each leg a planned
//                flight; marker frames at a fixed period; a marker of a hidden space not
//                yet visited -> approach
//   approach     fly to the survey point out from the opening the marker gives
//   survey       depth frames from there: the best safe landing zone within reach of
//                the opening (unknown is not free); none -> hover or skip (an option)
//   land         over the zone, then down (or hold the hover)
//   lower        release the miniUGV: l_t from 0 to l_0 with the IMU touchdown check
//   ugv_ops      the miniUGV's mission; the winch's taut-tether control keeps l_t on the
//                length the miniUGV's pose asks for
//   retract      reel the miniUGV in
//   liftoff      back to the search altitude
//   deliver      fly the object to the drop zone (planned with the miniUGV hanging)
//   drop         release it there, then search on
//   return_home  the pattern done, or the battery only covers the way home
//   land_home    down at home -> done
// Every state has a timeout and a defined exit; every transition goes to the
// TransitionLog with the clock's time and the reason. Each state is one handler
// (on_<state>, in uav_mission_<phase>.cpp); the parts they share are classes of their
// own: CoveragePattern, FlightPathFollower, FlightBudget, WinchSupervision. The controller sees the
// interfaces of flight_controller.hpp, a tether::Winch, a Clock and a flight planner,
// never the simulator's truth.

#include <Eigen/Core>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/core/clock.hpp"
#include "ferret/core/transition_log.hpp"
#include "ferret/tether_model/tether_controller.hpp"
#include "ferret/tether_model/tether_modes.hpp"
#include "ferret/tether_model/winch.hpp"
#include "ferret/tether_model/winch_controllers.hpp"
#include "ferret/uav/coverage_pattern.hpp"
#include "ferret/uav/flight_budget.hpp"
#include "ferret/uav/flight_controller.hpp"
#include "ferret/uav/flight_path_follower.hpp"
#include "ferret/uav/landing_zone.hpp"
#include "ferret/uav/marker_detector.hpp"
#include "ferret/uav/opening_locator.hpp"
#include "ferret/uav/winch_supervision.hpp"

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

/// A survey hover's depth frames, gathered one a control cycle and fused as they come
/// (DepthFrameFusion), to be judged together. A dropped frame (0 x 0, the adapter's "no
/// frame this time") is not counted: the hover waits for the next, within the survey's
/// timeout.
class SurveyFrames {
 public:
  explicit SurveyFrames(const CameraModel& depth_camera) : fusion_(depth_camera) {}
  /// Adds the frame unless it is a dropped one; true once `needed` frames are in. Throws
  /// InputError for a frame of another size than the camera's.
  bool add(const CameraShot<DepthImageMm>& shot, int needed) {
    if (shot.image.width_px > 0 && shot.image.height_px > 0) fusion_.add(shot.image, shot.X_WC);
    return static_cast<int>(fusion_.frames()) >= needed;
  }
  /// The frames taken, fused, for LandingZoneDetector::detect.
  [[nodiscard]] const DepthFrameFusion& fused() const { return fusion_; }
  [[nodiscard]] std::size_t size() const { return fusion_.frames(); }
  void clear() { fusion_.clear(); }

 private:
  DepthFrameFusion fusion_;
};

class UavMission {
 public:
  struct Hardware {
    FlightController& flight;
    UavCameras& cameras;
    tether::Winch& winch;
    UgvLink& ugv;
  };
  /// configure: `marker_camera`, `depth_camera` are the cameras' models; `log` may be null.
  UavMission(Hardware hardware, const Clock& clock, FlightPlanner planner,
             CameraModel marker_camera, CameraModel depth_camera, UavMissionOptions options,
             TransitionLog* log);
  ~UavMission();
  UavMission(const UavMission&) = delete;
  UavMission& operator=(const UavMission&) = delete;

  /// On the ground at home: idle -> takeoff.
  void start();
  /// One control step (every control_period_s of the winch control).
  void tick();
  /// Ends the mission (the vehicle holds where it is).
  void stop(const std::string& reason);

  [[nodiscard]] UavMissionState state() const { return state_; }
  [[nodiscard]] UavMissionOutcome outcome() const { return outcome_; }
  [[nodiscard]] bool done() const { return state_ == UavMissionState::kDone; }
  [[nodiscard]] const std::vector<HiddenSpaceVisit>& visits() const { return visits_; }
  /// The coverage pattern's waypoints (at the search altitude) and how far it got.
  [[nodiscard]] const std::vector<Eigen::Vector3d>& pattern() const { return pattern_.waypoints(); }
  [[nodiscard]] std::size_t pattern_done() const { return pattern_.next_index(); }
  [[nodiscard]] double leg_spacing_m() const { return pattern_.leg_spacing_m(); }
  /// Waypoints of the first pass (legs along x); the second pass follows.
  [[nodiscard]] std::size_t first_pass_waypoints() const { return pattern_.first_pass_waypoints(); }
  /// Seconds spent in each state.
  [[nodiscard]] const std::map<std::string, double>& time_in_state() const { return time_in_; }
  [[nodiscard]] tether::TetherMode tether_mode() const { return modes_.mode(); }
  [[nodiscard]] const tether::TautControlOptions& winch_control() const {
    return options_.winch_control;
  }
  [[nodiscard]] int frames_processed() const { return frames_; }
  [[nodiscard]] int plans_failed() const { return path_.plans_failed(); }

 private:
  /// What one control step sees: the clock, the time in the state so far, the vehicle
  /// and the winch.
  struct Tick {
    double now_s;
    double in_state_s;
    FlightState uav;
    tether::WinchState winch;
  };
  // One handler a state; tick() dispatches on the state. Each returns after at most one
  // transition.
  // uav_mission_search.cpp: the climb, the coverage pattern, the approach to an opening.
  void on_takeoff(const Tick& t);
  void on_search(const Tick& t);
  void on_approach(const Tick& t);
  // uav_mission_survey.cpp: the landing zone survey, the landing or the hover.
  void on_survey(const Tick& t);
  void on_land(const Tick& t);
  // uav_mission_ugv.cpp: the miniUGV lowered, at work, reeled in.
  void on_lower(const Tick& t);
  void on_ugv_ops(const Tick& t);
  void on_retract(const Tick& t);
  // uav_mission_return.cpp: the climb back, the delivery, the way home.
  void on_liftoff(const Tick& t);
  void on_deliver(const Tick& t);
  void on_drop(const Tick& t);
  void on_return_home(const Tick& t);
  void on_land_home(const Tick& t);
  /// Whether the UAV has held still (`there`, and slower than 0.15 m/s) for a second;
  /// the second starts again when it is not.
  bool settled(bool there, const Tick& t);

  void enter(UavMissionState next, const std::string& reason);
  void finish(UavMissionOutcome outcome, const std::string& reason);
  struct MarkerFrame {
    Pose3 X_WC;
    std::vector<MarkerDetection> detections;
  };
  /// A marker frame's detections when one is due (every frame_period_s).
  [[nodiscard]] std::optional<MarkerFrame> marker_frame_due();
  /// The opening relation of one of the team's markers, or null.
  [[nodiscard]] const OpeningInMarker* opening_of(int marker_id) const;
  void look_for_markers();
  void refine_opening();
  void go_home(const std::string& reason);
  void start_survey_view();
  void choose_release(const std::string& why_no_zone);
  void hover_over_opening(const std::string& why);
  void resume_search(const std::string& reason);
  /// While the miniUGV is out: the hover over the release point held.
  void hold_over_release();
  [[nodiscard]] HiddenSpaceVisit& current() {
    return visits_.at(static_cast<std::size_t>(current_));
  }
  [[nodiscard]] Eigen::Vector3d survey_point(int view) const;
  [[nodiscard]] const Eigen::Vector3d& home_W() const { return budget_.home_W(); }

  Hardware hw_;
  const Clock& clock_;
  CameraModel marker_camera_, depth_camera_;
  UavMissionOptions options_;
  FlightPathFollower path_;  ///< the planned legs the UAV flies
  FlightBudget budget_;      ///< the battery against the way home
  TransitionLog* log_;
  std::unique_ptr<MarkerDetector> detector_;
  LandingZoneDetector landing_;
  tether::TetherModeSwitcher modes_;
  /// The winch while the miniUGV is out (built once the options are checked).
  std::optional<WinchSupervision> winch_;

  UavMissionState state_ = UavMissionState::kIdle;
  UavMissionOutcome outcome_ = UavMissionOutcome::kNone;
  double state_since_s_ = 0.0;
  double last_tick_s_ = 0.0;
  std::map<std::string, double> time_in_;
  CoveragePattern pattern_;
  double next_frame_s_ = 0.0;
  std::map<int, int> sightings_;  ///< marker id -> detections not yet acted on
  std::vector<HiddenSpaceVisit> visits_;
  int current_ = -1;
  int survey_view_ = 0;
  /// The depth frames taken so far at this survey point, and how many it judges next
  /// (survey_frames, more after a miss: survey_frames_max).
  SurveyFrames survey_frames_;
  int survey_frames_needed_ = 0;
  double settled_since_s_ = -1.0;
  Eigen::Vector3d release_W_ = Eigen::Vector3d::Zero();
  bool carrying_ = false;
  int frames_ = 0;
};

}  // namespace ferret
