// The UAV mission by a hidden space's opening: the survey for a landing zone from the
// survey points round it, the choice between landing and hovering (or skipping), and
// the landing or the hover the miniUGV is lowered from.

#include <cmath>
#include <numbers>
#include <string>

#include "ferret/uav/uav_mission.hpp"

namespace ferret {

void UavMission::on_survey(const Tick& t) {
  if (t.in_state_s > options_.survey_timeout_s) return choose_release("survey timed out");
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
      return enter(UavMissionState::kLand,
                   "landing zone " + std::to_string(c.x()).substr(0, 6) + ", " +
                       std::to_string(c.y()).substr(0, 6) + " (slope " +
                       std::to_string(v.landing_zone->slope_deg).substr(0, 4) + " deg, " +
                       std::to_string(taken) + " frames)");
  }
  if (++survey_view_ < options_.survey_views) {
    start_survey_view();
    return enter(UavMissionState::kApproach, "no safe landing zone in view (" + zones.reason +
                                                 ") in " + std::to_string(taken) +
                                                 " frames, next view");
  }
  return choose_release("no safe landing zone within reach of the opening (" +
                        std::to_string(taken) + " frames a view)");
}

void UavMission::on_land(const Tick& t) {
  if (t.in_state_s > options_.land_timeout_s) {
    current().state = VisitState::kSkipped;
    current().note = "landing timed out";
    path_.clear();
    hw_.flight.command_takeoff(home_W().z() + options_.search_altitude_m);
    return resume_search("landing timed out");
  }
  if (!current().landed) {  // hover release: lower once the hover is steady
    if (path_.follow(t.uav) && settled(true, t))
      enter(UavMissionState::kLower, "hovering over the opening");
    return;
  }
  if (!path_.empty()) {
    if (path_.follow(t.uav) && settled(true, t)) {
      path_.clear();
      hw_.flight.command_land();
    }
    return;
  }
  if (t.uav.on_ground) {
    winch_->arm_touchdown_guard();
    return enter(UavMissionState::kLower, "landed beside the opening");
  }
}

Eigen::Vector3d UavMission::survey_point(int view) const {
  const OpeningEstimate& o = visits_.at(static_cast<std::size_t>(current_)).opening;
  // Views: straight out from the opening, then swung 50 degrees either way.
  const double swing =
      (view == 0) ? 0.0
                  : ((view % 2) ? 1.0 : -1.0) * ((view + 1) / 2) * 50.0 * std::numbers::pi / 180.0;
  const double out = o.entry_yaw_rad + std::numbers::pi + swing;
  return {o.p_WE.x() + options_.survey_standoff_m * std::cos(out),
          o.p_WE.y() + options_.survey_standoff_m * std::sin(out),
          o.p_WE.z() + options_.survey_height_m};
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
  if (options_.no_landing_zone == NoLandingZone::kSkip) {
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

}  // namespace ferret
