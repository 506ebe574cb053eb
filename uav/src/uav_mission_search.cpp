// The UAV mission's search: the climb to the search altitude, the coverage pattern
// flown leg by leg while marker frames are looked at, and the approach to the survey
// point of a marker's opening once it is seen often enough (the sightings).

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ferret/uav/uav_mission.hpp"

namespace ferret {

void UavMission::on_takeoff(const Tick& t) {
  if (t.uav.p_W.z() >= home_W().z() + options_.search_altitude_m - 0.2)
    return enter(UavMissionState::kSearch, "at the search altitude");
  if (t.in_state_s > options_.takeoff_timeout_s)
    return finish(UavMissionOutcome::kTakeoffFailed, "not at the search altitude in time");
}

void UavMission::on_search(const Tick& t) {
  if (budget_.calls_home(t.uav)) return go_home("the battery covers the way home only");
  look_for_markers();
  if (state_ != UavMissionState::kSearch) return;
  if (pattern_.done()) return go_home("search pattern flown");
  if (path_.empty() && !path_.fly_to(pattern_.next_waypoint(), options_.search_speed_mps, false)) {
    pattern_.advance();  // an unreachable waypoint: on to the next
    return;
  }
  if (path_.follow(t.uav)) {
    pattern_.advance();
    path_.clear();
  }
}

void UavMission::on_approach(const Tick& t) {
  if (budget_.calls_home(t.uav)) return go_home("the battery covers the way home only");
  refine_opening();
  if (t.in_state_s > options_.approach_timeout_s) {
    current().state = VisitState::kSkipped;
    current().note = "approach timed out";
    return resume_search("approach timed out");
  }
  // The survey frame is taken level and facing the opening, as planned for.
  if (path_.follow(t.uav) &&
      settled(std::abs(std::remainder(t.uav.yaw_rad - path_.final_yaw_rad().value_or(t.uav.yaw_rad),
                                      2 * std::numbers::pi)) < 0.05,
              t)) {
    // Near the opening, facing it, with the nearest frames' estimate of it: a hover
    // release needs no landing zone, so no survey.
    if (options_.release == ReleaseMode::kHover) return hover_over_opening("uav.release is hover");
    enter(UavMissionState::kSurvey, "over the survey point");
  }
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
    if (std::any_of(visits_.begin(), visits_.end(),
                    [&](const HiddenSpaceVisit& v) { return v.marker_id == d.id; }))
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
    enter(UavMissionState::kApproach, "marker " + std::to_string(d.id) + ": opening at (" +
                                          std::to_string(e.x()).substr(0, 6) + ", " +
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

}  // namespace ferret
