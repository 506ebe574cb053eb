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

// A battery draining four times as fast as the endurance says keeps four times the way
// home in hand; one draining as a healthy one does at full speed keeps the nominal budget.
TEST(FlightBudget, ABatteryDrainingFasterThanItShouldKeepsMoreForTheWayHome) {
  FlightBudget healthy = budget(), failing = budget();  // endurance 1000 s, factor 1.15
  healthy.set_home({0.0, 0.0, 4.0});
  failing.set_home({0.0, 0.0, 4.0});
  for (int t = 0; t <= 60; ++t) {
    healthy.observe(t, 1.0 - 1.15 * t / 1000.0);  // full speed, healthy
    failing.observe(t, 1.0 - 4.6 * t / 1000.0);   // four times that
  }
  EXPECT_EQ(healthy.drain_factor(), 1.0);
  EXPECT_NEAR(failing.drain_factor(), 4.0, 1e-9);
  // 200 m from home: 50 s home, 5 % nominal; 20 % at four times the drain, + 10 % reserve.
  EXPECT_FALSE(healthy.calls_home(at(200.0, 0.16)));
  EXPECT_TRUE(failing.calls_home(at(200.0, 0.29)));
  EXPECT_FALSE(failing.calls_home(at(200.0, 0.31)));
}

TEST(FlightBudget, TheDrainIsLearnedOverTheLastMinuteOnly) {
  FlightBudget b = budget();
  for (int t = 0; t <= 10; ++t) b.observe(t, 1.0 - 0.01 * t);  // fast, but 10 s: too short
  EXPECT_EQ(b.drain_factor(), 1.0);
  for (int t = 11; t <= 30; ++t) b.observe(t, 0.9 - 0.01 * (t - 10));
  EXPECT_GT(b.drain_factor(), 5.0);
  double level = 0.7;
  for (int t = 31; t <= 200; ++t) b.observe(t, level -= 0.0005);  // healthy again
  EXPECT_EQ(b.drain_factor(), 1.0);
}

}  // namespace
}  // namespace ferret
