#include "ferret/uav/uav_mission.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"

namespace ferret {

std::string_view to_string(UavMissionState state) {
  switch (state) {
    case UavMissionState::kIdle: return "idle";
    case UavMissionState::kTakeoff: return "takeoff";
    case UavMissionState::kSearch: return "search";
    case UavMissionState::kApproach: return "approach";
    case UavMissionState::kSurvey: return "survey";
    case UavMissionState::kLand: return "land";
    case UavMissionState::kLower: return "lower";
    case UavMissionState::kUgvOps: return "ugv_ops";
    case UavMissionState::kRetract: return "retract";
    case UavMissionState::kLiftoff: return "liftoff";
    case UavMissionState::kDeliver: return "deliver";
    case UavMissionState::kDrop: return "drop";
    case UavMissionState::kReturnHome: return "return_home";
    case UavMissionState::kLandHome: return "land_home";
    case UavMissionState::kDone: return "done";
  }
  return "?";
}

std::string_view to_string(UavMissionOutcome outcome) {
  switch (outcome) {
    case UavMissionOutcome::kNone: return "none";
    case UavMissionOutcome::kSearchComplete: return "search_complete";
    case UavMissionOutcome::kFlightBudget: return "flight_budget";
    case UavMissionOutcome::kTakeoffFailed: return "takeoff_failed";
    case UavMissionOutcome::kRetractFailed: return "retract_failed";
    case UavMissionOutcome::kDeliveryFailed: return "delivery_failed";
    case UavMissionOutcome::kAborted: return "aborted";
  }
  return "?";
}

std::string_view to_string(ReleaseMode release) {
  switch (release) {
    case ReleaseMode::kLand: return "land";
    case ReleaseMode::kHover: return "hover";
  }
  return "?";
}

std::string_view to_string(VisitState state) {
  switch (state) {
    case VisitState::kDetected: return "detected";
    case VisitState::kSkipped: return "skipped";
    case VisitState::kServiced: return "serviced";
  }
  return "?";
}

void UavMissionOptions::validate(const std::string& source) const {
  const auto positive = [&](double v, const char* field, std::string_view unit, double hi = 1e6) {
    check_number(v, NumberRange::positive(hi, unit), source, field);
  };
  for (int i = 0; i < 4; ++i) check_number(search_area_m[i], NumberRange::closed(-1e5, 1e5, "m"), source, "uav.search_area_m");
  if (!(search_area_m[2] > search_area_m[0] && search_area_m[3] > search_area_m[1]))
    throw InputError(source, "uav.search_area_m", "[x0, y0, x1, y1] with x1 > x0 and y1 > y0");
  positive(search_altitude_m, "uav.search_altitude_m", "m", 500.0);
  positive(search_speed_mps, "uav.search_speed_mps", "m/s", 50.0);
  positive(cruise_speed_mps, "uav.cruise_speed_mps", "m/s", 50.0);
  check_number(leg_spacing_m, NumberRange::non_negative(1e4, "m"), source, "uav.leg_spacing_m");
  if (passes < 1 || passes > 2) throw InputError(source, "uav.passes", "1 or 2", std::to_string(passes));
  positive(frame_period_s, "uav.frame_period_s", "s", 60.0);
  positive(waypoint_tolerance_m, "uav.waypoint_tolerance_m", "m", 10.0);
  positive(braking_accel_mps2, "uav.braking_accel_mps2", "m/s^2", 50.0);
  if (confirm_detections < 1 || confirm_detections > 100)
    throw InputError(source, "uav.confirm_detections", "an integer in [1, 100]", std::to_string(confirm_detections));
  positive(survey_height_m, "uav.survey_height_m", "m", 10.0);
  check_number(survey_standoff_m, NumberRange::non_negative(10.0, "m"), source, "uav.survey_standoff_m");
  if (survey_views < 1 || survey_views > 8)
    throw InputError(source, "uav.survey_views", "an integer in [1, 8]", std::to_string(survey_views));
  if (survey_frames < 1 || survey_frames > kMaxHoverFrames)
    throw InputError(source, "uav.survey_frames", "an integer in [1, " + std::to_string(kMaxHoverFrames) + "]",
                     std::to_string(survey_frames));
  if (survey_frames_max < 1 || survey_frames_max > kMaxHoverFrames)
    throw InputError(source, "uav.survey_frames_max", "an integer in [1, " + std::to_string(kMaxHoverFrames) + "]",
                     std::to_string(survey_frames_max));
  if (no_landing_zone != "hover" && no_landing_zone != "skip")
    throw InputError(source, "uav.no_landing_zone", "hover or skip", no_landing_zone);
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
  for (int i = 0; i < 2; ++i) check_number(drop_zone_W[i], NumberRange::closed(-1e5, 1e5, "m"), source, "uav.drop_zone_m");
  positive(drop_altitude_m, "uav.drop_altitude_m", "m", 500.0);
  check_number(drop_time_s, NumberRange::non_negative(600.0, "s"), source, "uav.drop_time_s");
  positive(flight_endurance_s, "uav.flight_endurance_s", "s", 1e5);
  check_number(battery_reserve_fraction, NumberRange::closed(0.0, 0.9), source, "uav.battery_reserve_fraction");
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
      path_(hw_.flight, std::move(planner), {options_.braking_accel_mps2, options_.waypoint_tolerance_m}),
      budget_({options_.cruise_speed_mps, options_.flight_endurance_s, options_.battery_reserve_fraction,
               options_.retract_speed_mps, options_.ugv_return_speed_mps}),
      log_(log),
      landing_(options_.landing),
      modes_(tether::TetherModeSwitcher::Options::from_mission(options_.tether,
                                                               options_.touchdown_height_m)),
      survey_frames_(depth_camera_) {
  options_.validate("uav mission options");
  detector_ = make_marker_detector(options_.marker);
  options_.winch_control.limits.total_length_m = options_.tether.total_length_m;
  winch_.emplace(hw_.winch, WinchSupervision::Options{options_.tether.entry_offset_m, options_.touchdown,
                                                     options_.winch_controller, options_.winch_control,
                                                     options_.retract_speed_mps});

  pattern_ = CoveragePattern(options_.search_area_m, options_.search_altitude_m, options_.passes,
                             options_.leg_spacing_m <= 0.0
                                 ? CoveragePattern::camera_leg_spacing_m(options_.marker, marker_camera_)
                                 : options_.leg_spacing_m);
}

UavMission::~UavMission() = default;

void UavMission::enter(UavMissionState next, const std::string& reason) {
  if (log_)
    log_->add({clock_.now_s(), "uav", std::string(to_string(state_)), std::string(to_string(next)), reason});
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

const OpeningInMarker* UavMission::opening_of(int marker_id) const {
  const auto o = std::find_if(options_.openings.begin(), options_.openings.end(),
                              [&](const OpeningInMarker& x) { return x.marker_id == marker_id; });
  return o == options_.openings.end() ? nullptr : &*o;
}

std::optional<UavMission::MarkerFrame> UavMission::marker_frame_due() {
  if (clock_.now_s() < next_frame_s_) return std::nullopt;
  next_frame_s_ = clock_.now_s() + options_.frame_period_s;
  const CameraShot<GrayImage> shot = hw_.cameras.marker_frame();
  ++frames_;
  if (shot.image.empty()) return MarkerFrame{shot.X_WC, {}};  // dropped: nothing to look at
  return MarkerFrame{shot.X_WC, detector_->detect(shot.image, marker_camera_)};
}

void UavMission::look_for_markers() {
  const auto frame = marker_frame_due();
  if (!frame) return;
  for (const MarkerDetection& d : frame->detections) {
    const OpeningInMarker* known = opening_of(d.id);
    if (!known) continue;
    if (std::any_of(visits_.begin(), visits_.end(), [&](const HiddenSpaceVisit& v) { return v.marker_id == d.id; }))
      continue;
    if (++sightings_[d.id] < options_.confirm_detections) continue;
    HiddenSpaceVisit visit;
    visit.marker_id = d.id;
    visit.opening = locate_opening(d, frame->X_WC, *known);
    visit.marker_distance_m = d.X_CM.translation().norm();
    visit.detected_s = clock_.now_s();
    visit.pattern_index = pattern_.next_index();
    visits_.push_back(visit);
    current_ = static_cast<int>(visits_.size()) - 1;
    survey_view_ = 0;
    const Eigen::Vector3d& e = visit.opening.p_WE;
    enter(UavMissionState::kApproach,
          "marker " + std::to_string(d.id) + ": opening at (" + std::to_string(e.x()).substr(0, 6) + ", " +
              std::to_string(e.y()).substr(0, 6) + ")");
    start_survey_view();
    return;
  }
}

void UavMission::refine_opening() {
  // Nearer frames of the same marker give a better pose: keep the nearest one's estimate.
  const auto frame = marker_frame_due();
  if (!frame) return;
  HiddenSpaceVisit& v = current();
  const OpeningInMarker* known = opening_of(v.marker_id);
  for (const MarkerDetection& d : frame->detections) {
    if (d.id != v.marker_id || !known) continue;
    const double distance_m = d.X_CM.translation().norm();
    if (distance_m >= v.marker_distance_m) continue;
    v.marker_distance_m = distance_m;
    v.opening = locate_opening(d, frame->X_WC, *known);
  }
}

Eigen::Vector3d UavMission::survey_point(int view) const {
  const OpeningEstimate& o = visits_.at(static_cast<std::size_t>(current_)).opening;
  // Views: straight out from the opening, then swung 50 degrees either way.
  const double swing = (view == 0) ? 0.0 : ((view % 2) ? 1.0 : -1.0) * ((view + 1) / 2) * 50.0 * std::numbers::pi / 180.0;
  const double out = o.entry_yaw_rad + std::numbers::pi + swing;
  return {o.p_WE.x() + options_.survey_standoff_m * std::cos(out),
          o.p_WE.y() + options_.survey_standoff_m * std::sin(out), o.p_WE.z() + options_.survey_height_m};
}

void UavMission::start_survey_view() {
  const Eigen::Vector3d p = survey_point(survey_view_);
  const double face = current().opening.entry_yaw_rad;  // look along the way into the opening
  if (!path_.fly_to(p, options_.cruise_speed_mps, false, face)) {
    if (++survey_view_ < options_.survey_views) return start_survey_view();
    choose_release("no flight to any survey point");
  }
}

void UavMission::choose_release(const std::string& why_no_zone) {
  HiddenSpaceVisit& v = current();
  if (options_.no_landing_zone == "skip") {
    v.state = VisitState::kSkipped;
    v.note = why_no_zone;
    return resume_search("skipped marker " + std::to_string(v.marker_id) + ": " + why_no_zone);
  }
  hover_over_opening(why_no_zone);
}

void UavMission::hover_over_opening(const std::string& why) {
  HiddenSpaceVisit& v = current();
  // Hover where the winch is l_0 from the entry: out by hover_standoff, up by the rest.
  const OpeningEstimate& o = v.opening;
  const double out = o.entry_yaw_rad + std::numbers::pi;
  const double l0 = options_.tether.entry_offset_m, s = options_.hover_standoff_m;
  release_W_ = {o.p_WE.x() + s * std::cos(out), o.p_WE.y() + s * std::sin(out),
                o.p_WE.z() + std::sqrt(l0 * l0 - s * s) + options_.touchdown_height_m};
  v.landed = false;
  v.note = why + "; hovering";
  if (!path_.fly_to(release_W_, 1.0, false, o.entry_yaw_rad)) {
    v.state = VisitState::kSkipped;
    v.note = why + "; no flight to the hover point";
    return resume_search("skipped marker " + std::to_string(v.marker_id) + ": " + v.note);
  }
  enter(UavMissionState::kLand, why + ": hovering over the opening");
}

void UavMission::tick() {
  if (state_ == UavMissionState::kIdle || done()) return;
  const double now = clock_.now_s();
  time_in_[std::string(to_string(state_))] += now - last_tick_s_;
  last_tick_s_ = now;
  const double in_state_s = now - state_since_s_;
  const FlightState s = hw_.flight.state();
  const tether::WinchState w = hw_.winch.read_state();
  modes_.update(now, w.released_m);
  const auto settled = [&](bool there) {
    if (!there || s.v_W.norm() > 0.15) {
      settled_since_s_ = -1.0;
      return false;
    }
    if (settled_since_s_ < 0) settled_since_s_ = now;
    return now - settled_since_s_ >= 1.0;
  };

  switch (state_) {
    case UavMissionState::kTakeoff:
      if (s.p_W.z() >= home_W().z() + options_.search_altitude_m - 0.2)
        return enter(UavMissionState::kSearch, "at the search altitude");
      if (in_state_s > options_.takeoff_timeout_s)
        return finish(UavMissionOutcome::kTakeoffFailed, "not at the search altitude in time");
      return;

    case UavMissionState::kSearch: {
      if (budget_.calls_home(s)) return go_home("the battery covers the way home only");
      look_for_markers();
      if (state_ != UavMissionState::kSearch) return;
      if (pattern_.done()) return go_home("search pattern flown");
      if (path_.empty() && !path_.fly_to(pattern_.next_waypoint(), options_.search_speed_mps, false)) {
        pattern_.advance();  // an unreachable waypoint: on to the next
        return;
      }
      if (path_.follow(s)) {
        pattern_.advance();
        path_.clear();
      }
      return;
    }

    case UavMissionState::kApproach:
      if (budget_.calls_home(s)) return go_home("the battery covers the way home only");
      refine_opening();
      if (in_state_s > options_.approach_timeout_s) {
        current().state = VisitState::kSkipped;
        current().note = "approach timed out";
        return resume_search("approach timed out");
      }
      // The survey frame is taken level and facing the opening, as planned for.
      if (path_.follow(s) && settled(std::abs(std::remainder(s.yaw_rad - path_.final_yaw_rad().value_or(s.yaw_rad),
                                                       2 * std::numbers::pi)) < 0.05)) {
        // Near the opening, facing it, with the nearest frames' estimate of it: a hover
        // release needs no landing zone, so no survey.
        if (options_.release == ReleaseMode::kHover) return hover_over_opening("uav.release is hover");
        enter(UavMissionState::kSurvey, "over the survey point");
      }
      return;

    case UavMissionState::kSurvey: {
      if (in_state_s > options_.survey_timeout_s) return choose_release("survey timed out");
      // The hover's frames, one a cycle, fused before the ground is judged.
      if (!survey_frames_.add(hw_.cameras.depth_frame(), survey_frames_needed_)) return;
      LandingZoneDetector::Options lo = options_.landing;
      lo.p_WE = current().opening.p_WE;
      lo.reach_m = options_.tether.entry_offset_m;
      const LandingResult zones = LandingZoneDetector(lo).detect(survey_frames_.fused());
      const int taken = static_cast<int>(survey_frames_.size());
      const int longer = hover_frames_after_miss(taken, options_.survey_frames_max);
      if (zones.zones.empty() && longer > taken) {
        // Nothing safe in these frames: keep them and look longer before the next view.
        survey_frames_needed_ = longer;
        return;
      }
      survey_frames_.clear();
      if (!zones.zones.empty()) {
        HiddenSpaceVisit& v = current();
        v.landing_zone = zones.zones.front();
        v.landed = true;
        const Eigen::Vector3d& c = v.landing_zone->center_m;
        release_W_ = c + Eigen::Vector3d(0, 0, 1.5);
        if (path_.fly_to(release_W_, 1.0, false, v.opening.entry_yaw_rad))
          return enter(UavMissionState::kLand, "landing zone " + std::to_string(c.x()).substr(0, 6) + ", " +
                                                   std::to_string(c.y()).substr(0, 6) + " (slope " +
                                                   std::to_string(v.landing_zone->slope_deg).substr(0, 4) + " deg, " +
                                                   std::to_string(taken) + " frames)");
      }
      if (++survey_view_ < options_.survey_views) {
        start_survey_view();
        return enter(UavMissionState::kApproach, "no safe landing zone in view (" + zones.reason + ") in " +
                                                     std::to_string(taken) + " frames, next view");
      }
      return choose_release("no safe landing zone within reach of the opening (" + std::to_string(taken) +
                            " frames a view)");
    }

    case UavMissionState::kLand: {
      if (in_state_s > options_.land_timeout_s) {
        current().state = VisitState::kSkipped;
        current().note = "landing timed out";
        path_.clear();
        hw_.flight.command_takeoff(home_W().z() + options_.search_altitude_m);
        return resume_search("landing timed out");
      }
      if (!current().landed) {  // hover release: lower once the hover is steady
        if (path_.follow(s) && settled(true)) enter(UavMissionState::kLower, "hovering over the opening");
        return;
      }
      if (!path_.empty()) {
        if (path_.follow(s) && settled(true)) {
          path_.clear();
          hw_.flight.command_land();
        }
        return;
      }
      if (s.on_ground) {
        winch_->arm_touchdown_guard();
        return enter(UavMissionState::kLower, "landed beside the opening");
      }
      return;
    }

    case UavMissionState::kLower: {
      winch_->keep_touchdown_guard();
      if (!current().landed) hw_.flight.command_position(release_W_, current().opening.entry_yaw_rad, 0.5);
      const UgvReport r = hw_.ugv.report();
      if (winch_->ugv_at_entry(w)) {
        winch_->start_taut_control();
        budget_.miniugv_released();
        hw_.ugv.deploy(current().opening.p_WE, current().opening.entry_yaw_rad);
        current().deployed_s = now;
        return enter(UavMissionState::kUgvOps, "miniUGV at the entry (l_t " + std::to_string(w.released_m).substr(0, 4) + " m)");
      }
      if (in_state_s > options_.lower_timeout_s) {
        current().note = "lowering timed out (touchdown angle)";
        return enter(UavMissionState::kRetract, "lowering timed out");
      }
      winch_->lower(now, r, w);
      return;
    }

    case UavMissionState::kUgvOps: {
      if (!current().landed) hw_.flight.command_position(release_W_, current().opening.entry_yaw_rad, 0.5);
      const UgvReport r = hw_.ugv.report();
      current().max_released_m = std::max(current().max_released_m, w.released_m);
      winch_->follow_ugv(now, r, w);
      if (r.done || r.wants_retraction) {
        current().ugv_outcome = r.outcome.empty() ? "at the entry" : r.outcome;
        return enter(UavMissionState::kRetract, "miniUGV asks to be lifted out (" + current().ugv_outcome + ")");
      }
      if (in_state_s > options_.ugv_ops_timeout_s) {
        hw_.ugv.abort("the UAV's time for the hidden space ran out");
        current().ugv_outcome = "aborted";
        return enter(UavMissionState::kRetract, "hidden-space time ran out");
      }
      // Hovering burns the flight budget while the miniUGV works.
      if (!current().landed) {
        switch (budget_.while_hovering(s, r, w.released_m)) {
          case FlightBudget::HoverCall::kLiftOut:
            hw_.ugv.abort("the UAV's battery covers only the lift and the way home");
            current().ugv_outcome = "aborted";
            current().note = "flight budget while hovering";
            return enter(UavMissionState::kRetract, "the battery covers only the lift and the way home");
          case FlightBudget::HoverCall::kRecall:
            hw_.ugv.recall("the UAV's flight budget");  // the miniUGV logs its own return
            break;
          case FlightBudget::HoverCall::kGoOn:
            break;
        }
      }
      return;
    }

    case UavMissionState::kRetract: {
      if (!current().landed) hw_.flight.command_position(release_W_, current().opening.entry_yaw_rad, 0.5);
      if (winch_->reeled_in(w)) {
        winch_->idle();
        const UgvReport r = hw_.ugv.report();
        hw_.ugv.retracted();
        HiddenSpaceVisit& v = current();
        v.retracted_s = now;
        v.state = VisitState::kServiced;
        v.object_retrieved = r.object_held;
        carrying_ = r.object_held;
        hw_.flight.command_takeoff(std::max(s.p_W.z(), home_W().z() + options_.search_altitude_m));
        return enter(UavMissionState::kLiftoff, r.object_held ? "miniUGV aboard with the object" : "miniUGV aboard, no object");
      }
      if (in_state_s > options_.retract_timeout_s) {
        winch_->idle();
        return finish(UavMissionOutcome::kRetractFailed, "the miniUGV was not reeled in in time");
      }
      winch_->reel_in();
      return;
    }

    case UavMissionState::kLiftoff:
      if (s.p_W.z() >= home_W().z() + options_.search_altitude_m - 0.2) {
        if (carrying_) {
          const Eigen::Vector3d drop(options_.drop_zone_W.x(), options_.drop_zone_W.y(),
                                     home_W().z() + options_.drop_altitude_m);
          if (path_.fly_to(drop, options_.cruise_speed_mps, true)) return enter(UavMissionState::kDeliver, "to the drop zone");
          current().note = "no flight to the drop zone with the miniUGV below";
          return go_home(current().note);
        }
        return resume_search("searching on");
      }
      if (in_state_s > options_.takeoff_timeout_s) return finish(UavMissionOutcome::kTakeoffFailed, "no climb after the hidden space");
      return;

    case UavMissionState::kDeliver:
      if (in_state_s > options_.deliver_timeout_s) {
        current().note = "delivery timed out";
        return go_home(current().note);
      }
      if (path_.follow(s) && settled(true)) {
        hw_.ugv.release_object();
        return enter(UavMissionState::kDrop, "over the drop zone: EPM off");
      }
      return;

    case UavMissionState::kDrop:
      if (in_state_s >= options_.drop_time_s) {
        current().object_dropped = true;
        carrying_ = false;
        if (budget_.calls_home(s)) return go_home("the battery covers the way home only");
        return resume_search("object dropped");
      }
      return;

    case UavMissionState::kReturnHome:
      if (path_.follow(s) && settled(true)) {
        hw_.flight.command_land();
        return enter(UavMissionState::kLandHome, "over home");
      }
      if (in_state_s > options_.return_timeout_s) {
        hw_.flight.command_land();
        return enter(UavMissionState::kLandHome, "return timed out: landing where it is");
      }
      return;

    case UavMissionState::kLandHome:
      if (s.on_ground) {
        // Home with the object still below: the delivery failed, whatever the battery
        // and the pattern say (it was not the flight budget that ended the search).
        if (carrying_)
          return finish(UavMissionOutcome::kDeliveryFailed, "landed at home with the object: " +
                                                                 (current_ >= 0 ? current().note : std::string("no delivery")));
        const bool early = !pattern_.done();
        return finish(early ? UavMissionOutcome::kFlightBudget : UavMissionOutcome::kSearchComplete,
                      early ? "landed at home, pattern not finished" : "landed at home");
      }
      if (in_state_s > options_.land_timeout_s) return finish(UavMissionOutcome::kAborted, "no touchdown at home");
      return;

    case UavMissionState::kIdle:
    case UavMissionState::kDone:
      return;
  }
}

}  // namespace ferret
