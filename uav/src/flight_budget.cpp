#include "ferret/uav/flight_budget.hpp"

namespace ferret {

bool FlightBudget::calls_home(const FlightState& s, double before_s) const {
  const double home_s = before_s + (s.p_W - home_W_).norm() / options_.cruise_speed_mps + 30.0;
  return s.battery_fraction <
         home_s / options_.flight_endurance_s + options_.battery_reserve_fraction;
}

FlightBudget::HoverCall FlightBudget::while_hovering(const FlightState& s, const UgvReport& r,
                                                     double released_m) {
  // Hovering burns the flight budget while the miniUGV works: call it back while
  // the battery still covers its way back along the tether, the reel-in, the climb
  // and the way home; below what the reel-in and the way home need, drag it out.
  const double tether_m = r.tether_to_anchor_m + (r.p_WG - r.tether_anchor_W).norm();
  const double lift_s = released_m / options_.retract_speed_mps + 10.0;
  if (calls_home(s, lift_s)) return HoverCall::kLiftOut;
  if (!recalled_ && calls_home(s, lift_s + tether_m / options_.ugv_return_speed_mps)) {
    recalled_ = true;
    return HoverCall::kRecall;
  }
  return HoverCall::kGoOn;
}

}  // namespace ferret
