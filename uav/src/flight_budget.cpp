#include "ferret/uav/flight_budget.hpp"

namespace ferret {

bool FlightBudget::calls_home(const FlightState& s, double before_s) const {
  const double home_s = before_s + (s.p_W - home_W_).norm() / options_.cruise_speed_mps + 30.0;
  return s.battery_fraction <
         drain_factor_ * home_s / options_.flight_endurance_s + options_.battery_reserve_fraction;
}

void FlightBudget::observe(double now_s, double battery_fraction) {
  constexpr double kSpacing_s = 1.0, kWindow_s = 60.0, kShortest_s = 20.0;
  if (!battery_.empty() && now_s - battery_.back().first < kSpacing_s) return;
  battery_.emplace_back(now_s, battery_fraction);
  while (now_s - battery_.front().first > kWindow_s) battery_.pop_front();
  const double span_s = battery_.back().first - battery_.front().first;
  if (span_s < kShortest_s) return;
  const double rate_per_s = (battery_.front().second - battery_.back().second) / span_s;
  const double factor =
      rate_per_s * options_.flight_endurance_s / options_.max_healthy_drain_factor;
  // A healthy battery (readings a little off included) keeps the endurance's budget.
  drain_factor_ = factor > 1.05 ? factor : 1.0;
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
