// The UAV mission while the miniUGV is out: lowering it to the entry, its mission with
// the winch keeping the tether taut (and the flight budget watching a hover), and the
// reel-in.

#include <algorithm>
#include <string>

#include "ferret/uav/uav_mission.hpp"

namespace ferret {

void UavMission::hold_over_release() {
  // A hover release keeps the UAV over the point it lowered from; a landed one sits.
  if (!current().landed)
    hw_.flight.command_position(release_W_, current().opening.entry_yaw_rad, 0.5);
}

void UavMission::on_lower(const Tick& t) {
  winch_->keep_touchdown_guard();
  hold_over_release();
  const UgvReport r = hw_.ugv.report();
  if (winch_->ugv_at_entry(t.winch)) {
    winch_->start_taut_control();
    budget_.miniugv_released();
    hw_.ugv.deploy(current().opening.p_WE, current().opening.entry_yaw_rad);
    current().deployed_s = t.now_s;
    return enter(
        UavMissionState::kUgvOps,
        "miniUGV at the entry (l_t " + std::to_string(t.winch.released_m).substr(0, 4) + " m)");
  }
  if (t.in_state_s > options_.lower_timeout_s) {
    current().note = "lowering timed out (touchdown angle)";
    return enter(UavMissionState::kRetract, "lowering timed out");
  }
  winch_->lower(t.now_s, r, t.winch);
}

void UavMission::on_ugv_ops(const Tick& t) {
  hold_over_release();
  const UgvReport r = hw_.ugv.report();
  current().max_released_m = std::max(current().max_released_m, t.winch.released_m);
  winch_->follow_ugv(t.now_s, r, t.winch);
  if (r.done || r.wants_retraction) {
    current().ugv_outcome = r.outcome.empty() ? "at the entry" : r.outcome;
    return enter(UavMissionState::kRetract,
                 "miniUGV asks to be lifted out (" + current().ugv_outcome + ")");
  }
  if (t.in_state_s > options_.ugv_ops_timeout_s) {
    hw_.ugv.abort("the UAV's time for the hidden space ran out");
    current().ugv_outcome = "aborted";
    return enter(UavMissionState::kRetract, "hidden-space time ran out");
  }
  // Hovering burns the flight budget while the miniUGV works.
  if (!current().landed) {
    switch (budget_.while_hovering(t.uav, r, t.winch.released_m)) {
      case FlightBudget::HoverCall::kLiftOut:
        hw_.ugv.abort("the UAV's battery covers only the lift and the way home");
        current().ugv_outcome = "aborted";
        current().note = "flight budget while hovering";
        return enter(UavMissionState::kRetract,
                     "the battery covers only the lift and the way home");
      case FlightBudget::HoverCall::kRecall:
        hw_.ugv.recall("the UAV's flight budget");  // the miniUGV logs its own return
        break;
      case FlightBudget::HoverCall::kGoOn:
        break;
    }
  }
}

void UavMission::on_retract(const Tick& t) {
  hold_over_release();
  if (winch_->reeled_in(t.winch)) {
    winch_->idle();
    const UgvReport r = hw_.ugv.report();
    hw_.ugv.retracted();
    HiddenSpaceVisit& v = current();
    v.retracted_s = t.now_s;
    v.state = VisitState::kServiced;
    v.object_retrieved = r.object_held;
    carrying_ = r.object_held;
    hw_.flight.command_takeoff(std::max(t.uav.p_W.z(), home_W().z() + options_.search_altitude_m));
    return enter(UavMissionState::kLiftoff,
                 r.object_held ? "miniUGV aboard with the object" : "miniUGV aboard, no object");
  }
  if (t.in_state_s > options_.retract_timeout_s) {
    winch_->idle();
    return finish(UavMissionOutcome::kRetractFailed, "the miniUGV was not reeled in in time");
  }
  winch_->reel_in();
}

}  // namespace ferret
