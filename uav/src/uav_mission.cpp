#include "ferret/uav/uav_mission.hpp"

#include <algorithm>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"

namespace ferret {

std::string_view to_string(UavMissionState state) {
  switch (state) {
    case UavMissionState::kIdle:
      return "idle";
    case UavMissionState::kTakeoff:
      return "takeoff";
    case UavMissionState::kSearch:
      return "search";
    case UavMissionState::kApproach:
      return "approach";
    case UavMissionState::kSurvey:
      return "survey";
    case UavMissionState::kLand:
      return "land";
    case UavMissionState::kLower:
      return "lower";
    case UavMissionState::kUgvOps:
      return "ugv_ops";
    case UavMissionState::kRetract:
      return "retract";
    case UavMissionState::kLiftoff:
      return "liftoff";
    case UavMissionState::kDeliver:
      return "deliver";
    case UavMissionState::kDrop:
      return "drop";
    case UavMissionState::kReturnHome:
      return "return_home";
    case UavMissionState::kLandHome:
      return "land_home";
    case UavMissionState::kDone:
      return "done";
  }
  return "?";
}

std::string_view to_string(UavMissionOutcome outcome) {
  switch (outcome) {
    case UavMissionOutcome::kNone:
      return "none";
    case UavMissionOutcome::kSearchComplete:
      return "search_complete";
    case UavMissionOutcome::kFlightBudget:
      return "flight_budget";
    case UavMissionOutcome::kTakeoffFailed:
      return "takeoff_failed";
    case UavMissionOutcome::kRetractFailed:
      return "retract_failed";
    case UavMissionOutcome::kDeliveryFailed:
      return "delivery_failed";
    case UavMissionOutcome::kAborted:
      return "aborted";
  }
  return "?";
}

std::string_view to_string(ReleaseMode release) {
  switch (release) {
    case ReleaseMode::kLand:
      return "land";
    case ReleaseMode::kHover:
      return "hover";
  }
  return "?";
}

std::string_view to_string(NoLandingZone choice) {
  return choice == NoLandingZone::kSkip ? "skip" : "hover";
}

NoLandingZone parse_no_landing_zone(const std::string& word, const std::string& source,
                                    const std::string& field) {
  for (const NoLandingZone c : {NoLandingZone::kHover, NoLandingZone::kSkip})
    if (word == to_string(c)) return c;
  throw InputError(source, field, "hover or skip", word);
}

std::string_view to_string(VisitState state) {
  switch (state) {
    case VisitState::kDetected:
      return "detected";
    case VisitState::kSkipped:
      return "skipped";
    case VisitState::kServiced:
      return "serviced";
  }
  return "?";
}

std::optional<double> UavMissionOptions::state_timeout_s(UavMissionState state) const {
  using S = UavMissionState;
  switch (state) {
    case S::kTakeoff:
    case S::kLiftoff:
      return takeoff_timeout_s;
    case S::kApproach:
      return approach_timeout_s;
    case S::kSurvey:
      return survey_timeout_s;
    case S::kLand:
    case S::kLandHome:
      return land_timeout_s;
    case S::kLower:
      return lower_timeout_s;
    case S::kUgvOps:
      return ugv_ops_timeout_s;
    case S::kRetract:
      return retract_timeout_s;
    case S::kDeliver:
      return deliver_timeout_s;
    case S::kDrop:
      return drop_time_s;
    case S::kReturnHome:
      return return_timeout_s;
    case S::kIdle:
    case S::kSearch:
    case S::kDone:
      return std::nullopt;
  }
  return std::nullopt;
}

void UavMissionOptions::validate(const std::string& source) const {
  const auto positive = [&](double v, const char* field, std::string_view unit, double hi = 1e6) {
    check_number(v, NumberRange::positive(hi, unit), source, field);
  };
  for (int i = 0; i < 4; ++i)
    check_number(search_area_m[i], NumberRange::closed(-1e5, 1e5, "m"), source,
                 "uav.search_area_m");
  if (!(search_area_m[2] > search_area_m[0] && search_area_m[3] > search_area_m[1]))
    throw InputError(source, "uav.search_area_m", "[x0, y0, x1, y1] with x1 > x0 and y1 > y0");
  positive(search_altitude_m, "uav.search_altitude_m", "m", 500.0);
  positive(search_speed_mps, "uav.search_speed_mps", "m/s", 50.0);
  positive(cruise_speed_mps, "uav.cruise_speed_mps", "m/s", 50.0);
  check_number(leg_spacing_m, NumberRange::non_negative(1e4, "m"), source, "uav.leg_spacing_m");
  if (passes < 1 || passes > 2)
    throw InputError(source, "uav.passes", "1 or 2", std::to_string(passes));
  positive(frame_period_s, "uav.frame_period_s", "s", 60.0);
  positive(waypoint_tolerance_m, "uav.waypoint_tolerance_m", "m", 10.0);
  positive(braking_accel_mps2, "uav.braking_accel_mps2", "m/s^2", 50.0);
  if (confirm_detections < 1 || confirm_detections > 100)
    throw InputError(source, "uav.confirm_detections", "an integer in [1, 100]",
                     std::to_string(confirm_detections));
  positive(survey_height_m, "uav.survey_height_m", "m", 10.0);
  check_number(survey_standoff_m, NumberRange::non_negative(10.0, "m"), source,
               "uav.survey_standoff_m");
  if (survey_views < 1 || survey_views > 8)
    throw InputError(source, "uav.survey_views", "an integer in [1, 8]",
                     std::to_string(survey_views));
  if (survey_frames < 1 || survey_frames > kMaxHoverFrames)
    throw InputError(source, "uav.survey_frames",
                     "an integer in [1, " + std::to_string(kMaxHoverFrames) + "]",
                     std::to_string(survey_frames));
  if (survey_frames_max < 1 || survey_frames_max > kMaxHoverFrames)
    throw InputError(source, "uav.survey_frames_max",
                     "an integer in [1, " + std::to_string(kMaxHoverFrames) + "]",
                     std::to_string(survey_frames_max));
  positive(hover_standoff_m, "uav.hover_standoff_m", "m", 10.0);
  positive(touchdown_height_m, "uav.touchdown_height_m", "m", 5.0);
  positive(tether.total_length_m, "tether.total_length_m", "m", 1000.0);
  positive(tether.entry_offset_m, "tether.entry_offset_m", "m", 1000.0);
  if (tether.entry_offset_m >= tether.total_length_m)
    throw InputError(source, "tether.entry_offset_m", "less than tether.total_length_m");
  if (hover_standoff_m >= tether.entry_offset_m)
    throw InputError(source, "uav.hover_standoff_m", "less than tether.entry_offset_m (l_0)");
  if (const auto names = tether::tether_controller_names();
      std::find(names.begin(), names.end(), winch_controller) == names.end()) {
    std::string list;
    for (const std::string& n : names) list += (list.empty() ? "" : " or ") + n;
    throw InputError(source, "uav.winch_controller", list, winch_controller);
  }
  positive(retract_speed_mps, "uav.retract_speed_mps", "m/s", 10.0);
  positive(ugv_return_speed_mps, "uav.ugv_return_speed_mps", "m/s", 10.0);
  for (int i = 0; i < 2; ++i)
    check_number(drop_zone_W[i], NumberRange::closed(-1e5, 1e5, "m"), source, "uav.drop_zone_m");
  positive(drop_altitude_m, "uav.drop_altitude_m", "m", 500.0);
  check_number(drop_time_s, NumberRange::non_negative(600.0, "s"), source, "uav.drop_time_s");
  positive(flight_endurance_s, "uav.flight_endurance_s", "s", 1e5);
  check_number(battery_reserve_fraction, NumberRange::closed(0.0, 0.9), source,
               "uav.battery_reserve_fraction");
  for (const auto& [v, field] : {std::pair{takeoff_timeout_s, "uav.takeoff_timeout_s"},
                                 {approach_timeout_s, "uav.approach_timeout_s"},
                                 {survey_timeout_s, "uav.survey_timeout_s"},
                                 {land_timeout_s, "uav.land_timeout_s"},
                                 {lower_timeout_s, "uav.lower_timeout_s"},
                                 {ugv_ops_timeout_s, "uav.ugv_ops_timeout_s"},
                                 {retract_timeout_s, "uav.retract_timeout_s"},
                                 {deliver_timeout_s, "uav.deliver_timeout_s"},
                                 {return_timeout_s, "uav.return_timeout_s"}})
    positive(v, field, "s", 1e5);
  marker.check(source);
  landing.check(source);
}

UavMission::UavMission(Hardware hardware, const Clock& clock, FlightPlanner planner,
                       CameraModel marker_camera, CameraModel depth_camera,
                       UavMissionOptions options, TransitionLog* log)
    : hw_(hardware),
      clock_(clock),
      marker_camera_(std::move(marker_camera)),
      depth_camera_(std::move(depth_camera)),
      options_(std::move(options)),
      path_(hw_.flight, std::move(planner),
            {options_.braking_accel_mps2, options_.waypoint_tolerance_m}),
      budget_({options_.cruise_speed_mps, options_.flight_endurance_s,
               options_.battery_reserve_fraction, options_.retract_speed_mps,
               options_.ugv_return_speed_mps}),
      log_(log),
      landing_(options_.landing),
      modes_(tether::TetherModeSwitcher::Options::from_mission(options_.tether,
                                                               options_.touchdown_height_m)),
      survey_frames_(depth_camera_) {
  options_.validate("uav mission options");
  detector_ = make_marker_detector(options_.marker);
  options_.winch_control.limits.total_length_m = options_.tether.total_length_m;
  winch_.emplace(hw_.winch,
                 WinchSupervision::Options{options_.tether.entry_offset_m, options_.touchdown,
                                           options_.winch_controller, options_.winch_control,
                                           options_.winch_controllers, options_.retract_speed_mps});

  pattern_ = CoveragePattern(options_.search_area_m, options_.search_altitude_m, options_.passes,
                             options_.leg_spacing_m <= 0.0 ? CoveragePattern::camera_leg_spacing_m(
                                                                 options_.marker, marker_camera_)
                                                           : options_.leg_spacing_m);
}

UavMission::~UavMission() = default;

void UavMission::enter(UavMissionState next, const std::string& reason) {
  if (log_)
    log_->add({clock_.now_s(), "uav", std::string(to_string(state_)), std::string(to_string(next)),
               reason});
  state_ = next;
  state_since_s_ = clock_.now_s();
  settled_since_s_ = -1.0;
  survey_frames_.clear();  // a survey's frames are one hover's
  survey_frames_needed_ = options_.survey_frames;
}

void UavMission::finish(UavMissionOutcome outcome, const std::string& reason) {
  outcome_ = outcome;
  winch_->idle();
  enter(UavMissionState::kDone, std::string(to_string(outcome)) + ": " + reason);
}

void UavMission::start() {
  if (state_ != UavMissionState::kIdle) return;
  const FlightState s = hw_.flight.state();
  budget_.set_home(s.p_W);
  last_tick_s_ = clock_.now_s();
  winch_->switch_on();
  hw_.flight.command_takeoff(home_W().z() + options_.search_altitude_m);
  enter(UavMissionState::kTakeoff, "mission started");
}

void UavMission::stop(const std::string& reason) {
  if (done()) return;
  if (state_ == UavMissionState::kUgvOps) hw_.ugv.abort(reason);
  const FlightState s = hw_.flight.state();
  if (!s.on_ground) hw_.flight.command_position(s.p_W, s.yaw_rad, 0.0);
  finish(UavMissionOutcome::kAborted, reason);
}

void UavMission::go_home(const std::string& reason) {
  const Eigen::Vector3d above = home_W() + Eigen::Vector3d(0, 0, options_.search_altitude_m);
  if (!path_.fly_to(above, options_.cruise_speed_mps, carrying_))
    path_.fly_straight(above, options_.cruise_speed_mps);  // the way it came is clear
  enter(UavMissionState::kReturnHome, reason);
}

void UavMission::resume_search(const std::string& reason) {
  path_.clear();
  sightings_.clear();
  current_ = -1;
  enter(UavMissionState::kSearch, reason);
}

void UavMission::tick() {
  if (state_ == UavMissionState::kIdle || done()) return;
  const double now = clock_.now_s();
  time_in_[std::string(to_string(state_))] += now - last_tick_s_;
  last_tick_s_ = now;
  const Tick t{now, now - state_since_s_, hw_.flight.state(), hw_.winch.read_state()};
  modes_.update(now, t.winch.released_m);
  budget_.observe(now, t.uav.battery_fraction);
  switch (state_) {
    case UavMissionState::kTakeoff:
      return on_takeoff(t);
    case UavMissionState::kSearch:
      return on_search(t);
    case UavMissionState::kApproach:
      return on_approach(t);
    case UavMissionState::kSurvey:
      return on_survey(t);
    case UavMissionState::kLand:
      return on_land(t);
    case UavMissionState::kLower:
      return on_lower(t);
    case UavMissionState::kUgvOps:
      return on_ugv_ops(t);
    case UavMissionState::kRetract:
      return on_retract(t);
    case UavMissionState::kLiftoff:
      return on_liftoff(t);
    case UavMissionState::kDeliver:
      return on_deliver(t);
    case UavMissionState::kDrop:
      return on_drop(t);
    case UavMissionState::kReturnHome:
      return on_return_home(t);
    case UavMissionState::kLandHome:
      return on_land_home(t);
    case UavMissionState::kIdle:
    case UavMissionState::kDone:
      return;
  }
}

bool UavMission::settled(bool there, const Tick& t) {
  if (!there || t.uav.v_W.norm() > 0.15) {
    settled_since_s_ = -1.0;
    return false;
  }
  if (settled_since_s_ < 0) settled_since_s_ = t.now_s;
  return t.now_s - settled_since_s_ >= 1.0;
}

}  // namespace ferret
