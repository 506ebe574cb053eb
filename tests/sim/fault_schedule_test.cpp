// A fault plan on the clock (sim/fault_schedule.hpp): faults start at their time or
// after their state's first entry, act for their duration, fire once when instantaneous,
// and turn into the link's impairment per direction.
#include "ferret/sim/fault_schedule.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <string_view>

#include "ferret/core/yaml_config.hpp"

namespace ferret {
namespace {

constexpr std::array<std::string_view, 2> kUav{"lower", "ugv_ops"};
constexpr std::array<std::string_view, 2> kUgv{"explore", "return"};

FaultSchedule schedule(const std::string& yaml) {
  return FaultSchedule(fault_plan_from_yaml(yaml::load_string(yaml, "m.yaml")["faults"], "m.yaml",
                                            FaultStates{kUav, kUgv}));
}

TEST(FaultSchedule, ATimedFaultActsFromItsStartForItsDuration) {
  FaultSchedule s = schedule("faults: [{kind: winch_stall, at_s: 10, duration_s: 5}]\n");
  EXPECT_FALSE(s.acts(FaultKind::kWinchStall, FaultTarget::kUav));
  s.advance(9.99);
  EXPECT_FALSE(s.acts(FaultKind::kWinchStall, FaultTarget::kUav));
  s.advance(10.0);
  EXPECT_TRUE(s.acts(FaultKind::kWinchStall, FaultTarget::kUav));
  EXPECT_FALSE(s.acts(FaultKind::kWinchStall, FaultTarget::kUgv));  // another target
  EXPECT_FALSE(s.acts(FaultKind::kWinchServoError, FaultTarget::kUav));
  s.advance(14.9);
  EXPECT_TRUE(s.acts(FaultKind::kWinchStall, FaultTarget::kUav));
  s.advance(15.0);
  EXPECT_FALSE(s.acts(FaultKind::kWinchStall, FaultTarget::kUav));
  ASSERT_TRUE(s.started_s()[0]);
  EXPECT_DOUBLE_EQ(*s.started_s()[0], 10.0);
}

TEST(FaultSchedule, AStateStartedFaultWaitsForTheFirstEntryThenItsDelay) {
  FaultSchedule s =
      schedule("faults: [{kind: link_outage, on: ugv.explore, at_s: 20, duration_s: 60}]\n");
  s.note_state(FaultRobot::kUav, "explore", 5.0);  // the UAV has no such state: no start
  s.note_state(FaultRobot::kUgv, "return", 6.0);
  s.advance(500.0);
  EXPECT_FALSE(s.started_s()[0]);
  s.note_state(FaultRobot::kUgv, "explore", 600.0);
  s.advance(619.0);
  EXPECT_FALSE(s.acts(FaultKind::kLinkOutage, FaultTarget::kBothWays));
  s.note_state(FaultRobot::kUgv, "explore", 619.5);  // still in it: the first entry counts
  s.advance(620.0);
  EXPECT_TRUE(s.acts(FaultKind::kLinkOutage, FaultTarget::kBothWays));
  s.advance(679.9);
  EXPECT_TRUE(s.acts(FaultKind::kLinkOutage, FaultTarget::kBothWays));
  s.advance(680.0);
  EXPECT_FALSE(s.acts(FaultKind::kLinkOutage, FaultTarget::kBothWays));
}

TEST(FaultSchedule, APermanentFaultNeverEnds) {
  FaultSchedule s =
      schedule("faults: [{kind: motor_stall, target: left_wheel, permanent: true}]\n");
  s.advance(1e9);
  EXPECT_TRUE(s.acts(FaultKind::kMotorStall, FaultTarget::kLeftWheel));
  EXPECT_FALSE(s.acts(FaultKind::kMotorStall, FaultTarget::kRightWheel));
}

TEST(FaultSchedule, TheStrongestOfOverlappingFaultsActs) {
  FaultSchedule s = schedule(R"(faults:
  - {kind: wheel_slip, at_s: 0, duration_s: 100, strength: 0.2}
  - {kind: wheel_slip, at_s: 10, duration_s: 10, strength: 0.6}
)");
  s.advance(5.0);
  EXPECT_DOUBLE_EQ(s.acting(FaultKind::kWheelSlip, FaultTarget::kUgv)->strength, 0.2);
  s.advance(15.0);
  EXPECT_DOUBLE_EQ(s.acting(FaultKind::kWheelSlip, FaultTarget::kUgv)->strength, 0.6);
  s.advance(25.0);
  EXPECT_DOUBLE_EQ(s.acting(FaultKind::kWheelSlip, FaultTarget::kUgv)->strength, 0.2);
}

TEST(FaultSchedule, AnInstantaneousFaultIsDueOnceAfterItsStart) {
  FaultSchedule s = schedule(R"(faults:
  - {kind: battery_sag, target: uav, at_s: 30, strength: 0.25}
  - {kind: battery_sag, target: ugv, at_s: 10}
)");
  s.advance(29.0);
  EXPECT_TRUE(s.take_due(FaultKind::kBatterySag, FaultTarget::kUav).empty());
  s.advance(31.0);
  const auto due = s.take_due(FaultKind::kBatterySag, FaultTarget::kUav);
  ASSERT_EQ(due.size(), 1u);
  EXPECT_DOUBLE_EQ(due[0].strength, 0.25);
  EXPECT_TRUE(s.take_due(FaultKind::kBatterySag, FaultTarget::kUav).empty());  // once
  EXPECT_EQ(s.take_due(FaultKind::kBatterySag, FaultTarget::kUgv).size(), 1u);
  EXPECT_FALSE(s.acts(FaultKind::kBatterySag, FaultTarget::kUav));  // never "acting"
}

TEST(FaultSchedule, LinkFaultsBecomeEachDirectionsImpairment) {
  FaultSchedule s = schedule(R"(faults:
  - {kind: link_loss, at_s: 0, duration_s: 100, strength: 0.5, burst_s: 2}
  - {kind: link_loss, target: uav_to_ugv, at_s: 0, duration_s: 100, strength: 0.2}
  - {kind: link_latency, target: ugv_to_uav, at_s: 0, duration_s: 100, strength: 0.25, jitter_s: 0.1}
  - {kind: link_outage, target: uav_to_ugv, at_s: 50, duration_s: 10}
  - {kind: link_duplicate, at_s: 0, duration_s: 100, strength: 0.1}
)");
  s.advance(1.0);
  const link::LinkImpairment up = s.link_impairment(FaultTarget::kUavToUgv, 0.05);
  EXPECT_FALSE(up.outage);
  EXPECT_DOUBLE_EQ(up.drop_fraction, 1.0 - 0.5 * 0.8);  // escapes both losses
  EXPECT_DOUBLE_EQ(up.burst_deliveries, 40.0);          // 2 s at 0.05 s a delivery
  EXPECT_EQ(up.latency_deliveries, 0);
  EXPECT_DOUBLE_EQ(up.duplicate_fraction, 0.1);
  const link::LinkImpairment down = s.link_impairment(FaultTarget::kUgvToUav, 0.05);
  EXPECT_DOUBLE_EQ(down.drop_fraction, 0.5);
  EXPECT_EQ(down.latency_deliveries, 5);
  EXPECT_EQ(down.jitter_deliveries, 2);
  s.advance(55.0);
  EXPECT_TRUE(s.link_impairment(FaultTarget::kUavToUgv, 0.05).outage);
  EXPECT_FALSE(s.link_impairment(FaultTarget::kUgvToUav, 0.05).outage);
  s.advance(200.0);
  EXPECT_TRUE(s.link_impairment(FaultTarget::kUavToUgv, 0.05).none());
  EXPECT_TRUE(s.link_impairment(FaultTarget::kUgvToUav, 0.05).none());
}

}  // namespace
}  // namespace ferret
