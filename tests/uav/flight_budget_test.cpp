// The flight budget: the way home against the battery, and the calls it makes while the
// UAV hovers with the miniUGV out.

#include "ferret/uav/flight_budget.hpp"

#include <gtest/gtest.h>

namespace ferret {
namespace {

// 1000 s of flight at 10 m/s, a 10 % reserve, reeled in at 1 m/s, the miniUGV back at 0.5 m/s.
FlightBudget budget() { return FlightBudget({10.0, 1000.0, 0.10, 1.0, 0.5}); }

FlightState at(double x_m, double battery) {
  FlightState s;
  s.p_W = {x_m, 0.0, 4.0};
  s.battery_fraction = battery;
  return s;
}

TEST(FlightBudget, TheWayHomeAndTheReserveCallTheUavHome) {
  FlightBudget b = budget();
  b.set_home({0.0, 0.0, 4.0});
  // 200 m from home: 20 s of cruise + 30 s = 5 % of the battery, plus the 10 % reserve.
  EXPECT_FALSE(b.calls_home(at(200.0, 0.151)));
  EXPECT_TRUE(b.calls_home(at(200.0, 0.149)));
  EXPECT_TRUE(b.calls_home(at(200.0, 0.151), 10.0));  // 10 s of hovering before the way home
  b.set_home({200.0, 0.0, 4.0});
  EXPECT_FALSE(b.calls_home(at(200.0, 0.131)));  // at home: 30 s and the reserve
}

TEST(FlightBudget, AHoverRecallsTheMiniUgvOnceThenLiftsItOut) {
  FlightBudget b = budget();
  b.set_home({0.0, 0.0, 4.0});
  UgvReport r;
  r.tether_anchor_W = {0.0, 0.0};
  r.tether_to_anchor_m = 2.0;
  r.p_WG = {3.0, 0.0};  // 5 m of tether: 10 s back; 5 m out: 5 s + 10 s to lift
  // At home: lift 15 s + 30 s = 4.5 %; with the miniUGV's way back, 5.5 %.
  EXPECT_EQ(b.while_hovering(at(0.0, 0.16), r, 5.0), FlightBudget::HoverCall::kGoOn);
  EXPECT_EQ(b.while_hovering(at(0.0, 0.15), r, 5.0), FlightBudget::HoverCall::kRecall);
  EXPECT_EQ(b.while_hovering(at(0.0, 0.15), r, 5.0), FlightBudget::HoverCall::kGoOn);  // once
  EXPECT_EQ(b.while_hovering(at(0.0, 0.14), r, 5.0), FlightBudget::HoverCall::kLiftOut);
  b.miniugv_released();  // the next hidden space
  EXPECT_EQ(b.while_hovering(at(0.0, 0.15), r, 5.0), FlightBudget::HoverCall::kRecall);
}

}  // namespace
}  // namespace ferret
