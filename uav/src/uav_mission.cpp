#include "ferret/uav/uav_mission.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "ferret/perception/marker_family.hpp"
#include "ferret/tether_model/required_length.hpp"

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
  if (release != "land" && release != "hover") throw InputError(source, "uav.release", "land or hover", release);
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

// The tether length the miniUGV's last report asks for at a position: l_0, the taut
// tether from the entry to its last fixed point, and straight on from there. The
// winch controllers predict the miniUGV's motion between reports with it.
class ReportedTetherLength final : public tether::RequiredLengthModel {
 public:
  explicit ReportedTetherLength(double entry_offset_m) : l0_m_(entry_offset_m) {}
  void update(const UgvReport& r) {
    anchor_W_ = r.tether_anchor_W;
    to_anchor_m_ = r.tether_to_anchor_m;
  }
  [[nodiscard]] double required_length_m(const Eigen::Vector2d& p_WG) const override {
    return l0_m_ + to_anchor_m_ + (p_WG - anchor_W_).norm();
  }

 private:
  double l0_m_;
  Eigen::Vector2d anchor_W_ = Eigen::Vector2d::Zero();
  double to_anchor_m_ = 0.0;
};

namespace {

// The cells across the black square of the marker min_marker_side_px was set for
// (ArUco 4x4 with its border), which the search's range scales from.
constexpr double kSearchMarkerCells = 6.0;

double yaw_of(const Eigen::Vector3d& d) { return std::atan2(d.y(), d.x()); }

// Legs of a boustrophedon over the area at height z: along x (legs stepping in y),
// or along y; consecutive legs run opposite ways, so each way of a pass is flown on
// every other leg.
void add_pass(std::vector<Eigen::Vector3d>& out, const Eigen::Vector4d& a, double spacing, double z,
              bool along_x) {
  const double lo = along_x ? a[1] : a[0], hi = along_x ? a[3] : a[2];
  const double from = along_x ? a[0] : a[1], to = along_x ? a[2] : a[3];
  const int legs = std::max(1, static_cast<int>(std::ceil((hi - lo) / spacing)));
  const double step = (hi - lo) / legs;
  for (int i = 0; i < legs; ++i) {
    const double c = lo + (i + 0.5) * step;
    const double s = (i % 2 == 0) ? from : to, e = (i % 2 == 0) ? to : from;
    out.emplace_back(along_x ? s : c, along_x ? c : s, z);
    out.emplace_back(along_x ? e : c, along_x ? c : e, z);
  }
}

}  // namespace

UavMission::UavMission(Hardware hardware, const Clock& clock, FlightPlanner planner,
                       CameraModel marker_camera, CameraModel depth_camera,
                       UavMissionOptions options, TransitionLog* log)
    : hw_(hardware),
      clock_(clock),
      planner_(std::move(planner)),
      marker_camera_(std::move(marker_camera)),
      depth_camera_(std::move(depth_camera)),
      options_(std::move(options)),
      log_(log),
      landing_(options_.landing),
      modes_(tether::TetherModeSwitcher::Options::from_mission(options_.tether,
                                                               options_.touchdown_height_m)),
      survey_frames_(depth_camera_) {
  options_.validate("uav mission options");
  detector_ = make_marker_detector(options_.marker);
  options_.winch_control.limits.total_length_m = options_.tether.total_length_m;
  required_ = std::make_shared<ReportedTetherLength>(options_.tether.entry_offset_m);
  winch_ctl_ = tether::tether_controllers().make(
      options_.winch_controller, {options_.winch_control, options_.winch_controllers, required_},
      "uav mission options", "uav.winch_controller");

  leg_spacing_m_ = options_.leg_spacing_m;
  if (leg_spacing_m_ <= 0.0) {
    // A 4x4 marker (6 cells across its black square) spans min_marker_side_px at
    // d_max; it is decoded reliably up to about two thirds of that. What the decoder
    // needs is pixels a cell, so a marker of more cells is read nearer: d_max is where
    // the cells span min_marker_side_px / 6 px each (tag36h11's 8 cells: 3/4 of a 4x4
    // marker's range; docs/mission.md). Seen from a leg flying at it, it must lie within
    // the camera's half-width at about half that range (a wall marker near the ground
    // leaves the pitched camera's view when the UAV comes closer); every other leg flies
    // each way, so legs are one reach apart.
    const int cells = marker_bitmap(options_.marker.dictionary, 0).black_square_cells;
    const double d_max_m = marker_camera_.fx_px * options_.marker.marker_size_m /
                           (std::max(1.0, options_.marker.min_marker_side_px) *
                            std::max(1, cells) / kSearchMarkerCells);
    const double half_fov = std::atan2(0.5 * marker_camera_.width_px, marker_camera_.fx_px);
    leg_spacing_m_ = std::clamp(0.5 * d_max_m * std::tan(half_fov), 1.0, 50.0);
  }
  add_pass(pattern_, options_.search_area_m, leg_spacing_m_, options_.search_altitude_m, true);
  first_pass_end_ = pattern_.size();
  if (options_.passes > 1)
    add_pass(pattern_, options_.search_area_m, leg_spacing_m_, options_.search_altitude_m, false);
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
  winch_idle();
  enter(UavMissionState::kDone, std::string(to_string(outcome)) + ": " + reason);
}

void UavMission::winch_idle() { hw_.winch.command_velocity_mps(0.0); }

void UavMission::start() {
  if (state_ != UavMissionState::kIdle) return;
  const FlightState s = hw_.flight.state();
  home_W_ = s.p_W;
  last_tick_s_ = clock_.now_s();
  hw_.winch.set_torque_enabled(true);
  winch_idle();
  hw_.flight.command_takeoff(home_W_.z() + options_.search_altitude_m);
  enter(UavMissionState::kTakeoff, "mission started");
}

void UavMission::stop(const std::string& reason) {
  if (done()) return;
  if (state_ == UavMissionState::kUgvOps) hw_.ugv.abort(reason);
  const FlightState s = hw_.flight.state();
  if (!s.on_ground) hw_.flight.command_position(s.p_W, s.yaw_rad, 0.0);
  finish(UavMissionOutcome::kAborted, reason);
}

bool UavMission::fly_to(const Eigen::Vector3d& goal, double speed_mps, bool carrying,
                        std::optional<double> yaw_rad) {
  const FlightState s = hw_.flight.state();
  // A new path starts where the UAV comes to a stop, not where it is: the planner checks
  // the way from its start, and a UAV at 3 m/s still covers two metres braking along the
  // way it was flying (which went round what lay ahead). The braking line is checked too;
  // when it is not clear, the new path starts at the old one's next corner, reached
  // along a segment that was checked.
  Eigen::Vector3d from = s.p_W;
  if (const double v = s.v_W.norm(); v > 0.3) {
    const Eigen::Vector3d stop = s.p_W + s.v_W * (v / (2.0 * options_.braking_accel_mps2));
    const auto brake = planner_(s.p_W, stop, carrying);
    if (brake && brake->size() == 2)
      from = stop;
    else if (!path_.empty())
      from = path_[std::min(path_next_, path_.size() - 1)];
  }
  auto path = planner_(from, goal, carrying);
  if (!path || path->empty()) {
    ++plans_failed_;
    path_.clear();
    return false;
  }
  path_ = std::move(*path);
  path_next_ = 0;
  path_speed_mps_ = speed_mps;
  path_yaw_rad_ = yaw_rad;
  return true;
}

bool UavMission::follow(const FlightState& s) {
  if (path_.empty()) return true;
  // Corners of a planned path are passed closely: the plan is collision-checked along
  // its segments only, so cutting a corner could graze what the planner went round.
  // A corner is left only once reached and slowed down, so the turn happens on it.
  while (path_next_ + 1 < path_.size() &&
         (path_[path_next_] - s.p_W).norm() <= std::min(0.15, options_.waypoint_tolerance_m) &&
         s.v_W.norm() < 0.5)
    ++path_next_;
  const Eigen::Vector3d& target = path_[path_next_];
  const bool last = path_next_ + 1 == path_.size();
  // At the end the setpoint and heading are still commanded: a heading that changed
  // (a refined opening) is turned to even when the position is already reached.
  const bool arrived = last && (target - s.p_W).norm() <= options_.waypoint_tolerance_m && s.v_W.norm() < 0.3;
  // Face the way it flies (the marker camera looks ahead); the final heading when given.
  double yaw = s.yaw_rad;
  const Eigen::Vector3d d = target - s.p_W;
  if (d.head<2>().norm() > 0.5) yaw = yaw_of(d);
  const bool final_heading = last && path_yaw_rad_ && d.head<2>().norm() < 1.0;
  if (final_heading) yaw = *path_yaw_rad_;
  // Turn on the spot at the start of a segment: the planner checked the segment with
  // the UAV facing along it, and its shape is not round.
  const Eigen::Vector3d& hold = path_[path_next_ > 0 ? path_next_ - 1 : 0];
  if (!final_heading && (s.p_W - hold).norm() < 0.3 &&
      std::abs(std::remainder(yaw - s.yaw_rad, 2 * std::numbers::pi)) > 0.15) {
    hw_.flight.command_position(hold, yaw, path_speed_mps_);
    return false;
  }
  hw_.flight.command_position(target, yaw, path_speed_mps_);
  return arrived;
}

bool UavMission::battery_calls_home(const FlightState& s, double before_s) const {
  const double home_s = before_s + (s.p_W - home_W_).norm() / options_.cruise_speed_mps + 30.0;
  return s.battery_fraction < home_s / options_.flight_endurance_s + options_.battery_reserve_fraction;
}

void UavMission::go_home(const std::string& reason) {
  const Eigen::Vector3d above = home_W_ + Eigen::Vector3d(0, 0, options_.search_altitude_m);
  if (!fly_to(above, options_.cruise_speed_mps, carrying_)) path_ = {above};  // straight: the way it came is clear
  path_next_ = 0;
  path_speed_mps_ = options_.cruise_speed_mps;
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
    visit.pattern_index = pattern_next_;
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
  if (!fly_to(p, options_.cruise_speed_mps, false, face)) {
    if (++survey_view_ < options_.survey_views) return start_survey_view();
    choose_release("no flight to any survey point");
  }
}

void UavMission::choose_release(const std::string& why_no_zone) {
  HiddenSpaceVisit& v = current();
  if (options_.no_landing_zone == "skip") {
    v.state = "skipped";
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
  if (!fly_to(release_W_, 1.0, false, o.entry_yaw_rad)) {
    v.state = "skipped";
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
      if (s.p_W.z() >= home_W_.z() + options_.search_altitude_m - 0.2)
        return enter(UavMissionState::kSearch, "at the search altitude");
      if (in_state_s > options_.takeoff_timeout_s)
        return finish(UavMissionOutcome::kTakeoffFailed, "not at the search altitude in time");
      return;

    case UavMissionState::kSearch: {
      if (battery_calls_home(s)) return go_home("the battery covers the way home only");
      look_for_markers();
      if (state_ != UavMissionState::kSearch) return;
      if (pattern_next_ >= pattern_.size()) return go_home("search pattern flown");
      if (path_.empty() && !fly_to(pattern_[pattern_next_], options_.search_speed_mps, false)) {
        ++pattern_next_;  // an unreachable waypoint: on to the next
        return;
      }
      if (follow(s)) {
        ++pattern_next_;
        path_.clear();
      }
      return;
    }

    case UavMissionState::kApproach:
      if (battery_calls_home(s)) return go_home("the battery covers the way home only");
      refine_opening();
      if (in_state_s > options_.approach_timeout_s) {
        current().state = "skipped";
        current().note = "approach timed out";
        return resume_search("approach timed out");
      }
      // The survey frame is taken level and facing the opening, as planned for.
      if (follow(s) && settled(std::abs(std::remainder(s.yaw_rad - path_yaw_rad_.value_or(s.yaw_rad),
                                                       2 * std::numbers::pi)) < 0.05)) {
        // Near the opening, facing it, with the nearest frames' estimate of it: a hover
        // release needs no landing zone, so no survey.
        if (options_.release == "hover") return hover_over_opening("uav.release is hover");
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
        if (fly_to(release_W_, 1.0, false, v.opening.entry_yaw_rad))
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
        current().state = "skipped";
        current().note = "landing timed out";
        path_.clear();
        hw_.flight.command_takeoff(home_W_.z() + options_.search_altitude_m);
        return resume_search("landing timed out");
      }
      if (!current().landed) {  // hover release: lower once the hover is steady
        if (follow(s) && settled(true)) enter(UavMissionState::kLower, "hovering over the opening");
        return;
      }
      if (!path_.empty()) {
        if (follow(s) && settled(true)) {
          path_.clear();
          hw_.flight.command_land();
        }
        return;
      }
      if (s.on_ground) {
        guard_ = std::make_unique<tether::TouchdownGuard>(options_.touchdown);
        return enter(UavMissionState::kLower, "landed beside the opening");
      }
      return;
    }

    case UavMissionState::kLower: {
      if (!guard_) guard_ = std::make_unique<tether::TouchdownGuard>(options_.touchdown);
      if (!current().landed) hw_.flight.command_position(release_W_, current().opening.entry_yaw_rad, 0.5);
      const UgvReport r = hw_.ugv.report();
      // The miniUGV starts with the winch's slack reference paid out beyond l_0: a
      // metre of line is stiff (1.5 kN/m), so a line ending exactly taut at the entry
      // pulls tens of newtons the moment the robot moves.
      const double l0 = options_.tether.entry_offset_m + options_.winch_control.slack_reference_m;
      if (w.released_m >= l0 - 0.01) {
        winch_idle();
        guard_.reset();
        winch_ctl_->reset();
        recalled_ = false;
        hw_.ugv.deploy(current().opening.p_WE, current().opening.entry_yaw_rad);
        current().deployed_s = now;
        return enter(UavMissionState::kUgvOps, "miniUGV at the entry (l_t " + std::to_string(w.released_m).substr(0, 4) + " m)");
      }
      if (in_state_s > options_.lower_timeout_s) {
        current().note = "lowering timed out (touchdown angle)";
        return enter(UavMissionState::kRetract, "lowering timed out");
      }
      // The touchdown check matters near the floor; above it the miniUGV hangs level.
      const auto action = guard_->update(now, r.roll_rad, r.pitch_rad, w.released_m);
      (void)action;
      hw_.winch.command_velocity_mps(std::min(guard_->spool_velocity_mps(), l0 - w.released_m + 0.05));
      return;
    }

    case UavMissionState::kUgvOps: {
      if (!current().landed) hw_.flight.command_position(release_W_, current().opening.entry_yaw_rad, 0.5);
      const UgvReport r = hw_.ugv.report();
      current().max_released_m = std::max(current().max_released_m, w.released_m);
      // Over the robot link the miniUGV answers its search request a moment later:
      // until it has started (or while it is not heard) the winch cannot know where the
      // line must go, and holds its length. In one process it has started at once.
      const bool heard = r.link_ok && (r.running || r.done || r.wants_retraction);
      if (heard) required_->update(r);
      tether::TetherObservation obs;
      obs.t_s = now;
      obs.released_m = w.released_m;
      obs.spool_speed_mps = w.speed_mps;
      obs.winch_tension_n = w.tension_n;
      obs.ugv.p_WG = r.p_WG;
      obs.ugv.v_WG = r.v_WG;
      obs.slack_margin_m = r.tether_uncertainty_m;
      // Without word from the miniUGV the winch holds its length (the miniUGV holds too,
      // docs/link.md "Watchdogs").
      hw_.winch.command_velocity_mps(heard ? winch_ctl_->step(obs) : 0.0);
      if (r.done || r.wants_retraction) {
        current().ugv_outcome = r.outcome.empty() ? "at the entry" : r.outcome;
        return enter(UavMissionState::kRetract, "miniUGV asks to be lifted out (" + current().ugv_outcome + ")");
      }
      if (in_state_s > options_.ugv_ops_timeout_s) {
        hw_.ugv.abort("the UAV's time for the hidden space ran out");
        current().ugv_outcome = "aborted";
        return enter(UavMissionState::kRetract, "hidden-space time ran out");
      }
      // Hovering burns the flight budget while the miniUGV works: call it back while
      // the battery still covers its way back along the tether, the reel-in, the climb
      // and the way home; below what the reel-in and the way home need, drag it out.
      if (!current().landed) {
        const double tether_m = r.tether_to_anchor_m + (r.p_WG - r.tether_anchor_W).norm();
        const double lift_s = w.released_m / options_.retract_speed_mps + 10.0;
        if (battery_calls_home(s, lift_s)) {
          hw_.ugv.abort("the UAV's battery covers only the lift and the way home");
          current().ugv_outcome = "aborted";
          current().note = "flight budget while hovering";
          return enter(UavMissionState::kRetract, "the battery covers only the lift and the way home");
        }
        if (!recalled_ && battery_calls_home(s, lift_s + tether_m / options_.ugv_return_speed_mps)) {
          recalled_ = true;
          hw_.ugv.recall("the UAV's flight budget");  // the miniUGV logs its own return
        }
      }
      return;
    }

    case UavMissionState::kRetract: {
      if (!current().landed) hw_.flight.command_position(release_W_, current().opening.entry_yaw_rad, 0.5);
      if (w.released_m <= 0.01) {
        winch_idle();
        const UgvReport r = hw_.ugv.report();
        hw_.ugv.retracted();
        HiddenSpaceVisit& v = current();
        v.retracted_s = now;
        v.state = "serviced";
        v.object_retrieved = r.object_held;
        carrying_ = r.object_held;
        hw_.flight.command_takeoff(std::max(s.p_W.z(), home_W_.z() + options_.search_altitude_m));
        return enter(UavMissionState::kLiftoff, r.object_held ? "miniUGV aboard with the object" : "miniUGV aboard, no object");
      }
      if (in_state_s > options_.retract_timeout_s) {
        winch_idle();
        return finish(UavMissionOutcome::kRetractFailed, "the miniUGV was not reeled in in time");
      }
      hw_.winch.command_velocity_mps(-options_.retract_speed_mps);
      return;
    }

    case UavMissionState::kLiftoff:
      if (s.p_W.z() >= home_W_.z() + options_.search_altitude_m - 0.2) {
        if (carrying_) {
          const Eigen::Vector3d drop(options_.drop_zone_W.x(), options_.drop_zone_W.y(),
                                     home_W_.z() + options_.drop_altitude_m);
          if (fly_to(drop, options_.cruise_speed_mps, true)) return enter(UavMissionState::kDeliver, "to the drop zone");
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
      if (follow(s) && settled(true)) {
        hw_.ugv.release_object();
        return enter(UavMissionState::kDrop, "over the drop zone: EPM off");
      }
      return;

    case UavMissionState::kDrop:
      if (in_state_s >= options_.drop_time_s) {
        current().object_dropped = true;
        carrying_ = false;
        if (battery_calls_home(s)) return go_home("the battery covers the way home only");
        return resume_search("object dropped");
      }
      return;

    case UavMissionState::kReturnHome:
      if (follow(s) && settled(true)) {
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
        const bool early = pattern_next_ < pattern_.size();
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
