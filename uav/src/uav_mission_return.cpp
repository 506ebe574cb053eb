// The UAV mission after a hidden space and at the end: the climb back, the flight to
// the drop zone with the object and its release, the way home and the landing there.

#include <string>

#include "ferret/uav/uav_mission.hpp"

namespace ferret {

void UavMission::on_liftoff(const Tick& t) {
  if (t.uav.p_W.z() >= home_W().z() + options_.search_altitude_m - 0.2) {
    if (carrying_) {
      const Eigen::Vector3d drop(options_.drop_zone_W.x(), options_.drop_zone_W.y(),
                                 home_W().z() + options_.drop_altitude_m);
      if (path_.fly_to(drop, options_.cruise_speed_mps, true))
        return enter(UavMissionState::kDeliver, "to the drop zone");
      current().note = "no flight to the drop zone with the miniUGV below";
      return go_home(current().note);
    }
    return resume_search("searching on");
  }
  if (t.in_state_s > options_.takeoff_timeout_s)
    return finish(UavMissionOutcome::kTakeoffFailed, "no climb after the hidden space");
}

void UavMission::on_deliver(const Tick& t) {
  if (t.in_state_s > options_.deliver_timeout_s) {
    current().note = "delivery timed out";
    return go_home(current().note);
  }
  if (path_.follow(t.uav) && settled(true, t)) {
    hw_.ugv.release_object();
    return enter(UavMissionState::kDrop, "over the drop zone: EPM off");
  }
}

void UavMission::on_drop(const Tick& t) {
  if (t.in_state_s >= options_.drop_time_s) {
    current().object_dropped = true;
    carrying_ = false;
    if (budget_.calls_home(t.uav)) return go_home("the battery covers the way home only");
    return resume_search("object dropped");
  }
}

void UavMission::on_return_home(const Tick& t) {
  if (path_.follow(t.uav) && settled(true, t)) {
    hw_.flight.command_land();
    return enter(UavMissionState::kLandHome, "over home");
  }
  if (t.in_state_s > options_.return_timeout_s) {
    hw_.flight.command_land();
    return enter(UavMissionState::kLandHome, "return timed out: landing where it is");
  }
}

void UavMission::on_land_home(const Tick& t) {
  if (t.uav.on_ground) {
    // Home with the object still below: the delivery failed, whatever the battery
    // and the pattern say (it was not the flight budget that ended the search).
    if (carrying_)
      return finish(UavMissionOutcome::kDeliveryFailed,
                    "landed at home with the object: " +
                        (current_ >= 0 ? current().note : std::string("no delivery")));
    const bool early = !pattern_.done();
    return finish(early ? UavMissionOutcome::kFlightBudget : UavMissionOutcome::kSearchComplete,
                  early ? "landed at home, pattern not finished" : "landed at home");
  }
  if (t.in_state_s > options_.land_timeout_s)
    return finish(UavMissionOutcome::kAborted, "no touchdown at home");
}

}  // namespace ferret
