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
#include "ferret/uav/uav_mission_options.hpp"
#include "ferret/uav/winch_supervision.hpp"

namespace ferret {

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
