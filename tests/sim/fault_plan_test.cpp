// The faults of a mission (sim/fault_plan.hpp): the `faults:` section read and written
// back, every bad input an InputError naming the file and the field, and the random
// draw the same for the same seed and inside each kind's ranges.
#include "ferret/sim/fault_plan.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <set>
#include <string>
#include <string_view>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"
#include "support/input_refusal.hpp"

namespace ferret {
namespace {

using ::testing::HasSubstr;

constexpr std::array<std::string_view, 3> kUavStates{"search", "lower", "ugv_ops"};
constexpr std::array<std::string_view, 2> kUgvStates{"explore", "return"};
const FaultStates kStates{kUavStates, kUgvStates};

FaultPlan parse(const std::string& text) {
  return fault_plan_from_yaml(yaml::load_string(text, "m.yaml")["faults"], "m.yaml", kStates);
}

test::Refusal refusal(const std::string& text) {
  return test::refusal_of(text, "m.yaml", [](const std::string& t) { return parse(t); });
}

TEST(FaultPlan, ReadsEachFaultWithItsKindsDefaults) {
  const FaultPlan p = parse(R"(
faults:
  - {kind: link_outage, on: ugv.explore, at_s: 20, duration_s: 60, target: uav_to_ugv}
  - {kind: link_loss, permanent: true, strength: 0.5, burst_s: 2}
  - {kind: battery_drain, target: ugv, at_s: 300}
  - {kind: imu_spike, at_s: 12.5}
)");
  ASSERT_EQ(p.faults.size(), 4u);
  const Fault& outage = p.faults[0];
  EXPECT_EQ(outage.kind, FaultKind::kLinkOutage);
  EXPECT_EQ(outage.target, FaultTarget::kUavToUgv);
  EXPECT_EQ(outage.start.robot, FaultRobot::kUgv);
  EXPECT_EQ(outage.start.state, "explore");
  EXPECT_DOUBLE_EQ(outage.start.at_s, 20.0);
  EXPECT_EQ(outage.duration_s, 60.0);
  const Fault& loss = p.faults[1];
  EXPECT_EQ(loss.target, FaultTarget::kBothWays);  // the kind's first target
  EXPECT_EQ(loss.start.robot, FaultRobot::kNone);
  EXPECT_DOUBLE_EQ(loss.start.at_s, 0.0);
  EXPECT_FALSE(loss.duration_s.has_value());  // to the end
  EXPECT_DOUBLE_EQ(loss.strength, 0.5);
  EXPECT_DOUBLE_EQ(loss.extra, 2.0);
  const Fault& drain = p.faults[2];
  EXPECT_EQ(drain.target, FaultTarget::kUgv);
  EXPECT_EQ(drain.duration_s, 300.0);      // its default duration
  EXPECT_DOUBLE_EQ(drain.strength, 2.0);   // its default factor
  EXPECT_EQ(p.faults[3].duration_s, 0.0);  // instantaneous
  EXPECT_DOUBLE_EQ(p.faults[3].strength, 30.0);
}

TEST(FaultPlan, NoSectionMeansNoFaults) {
  EXPECT_TRUE(parse("tether: {total_length_m: 15}\n").empty());
  EXPECT_TRUE(parse("faults:\n").empty());
  EXPECT_TRUE(parse("faults: []\n").empty());
}

TEST(FaultPlan, WritesWhatItReadsBack) {
  const FaultPlan p = parse(R"(
faults:
  - {kind: link_latency, target: ugv_to_uav, at_s: 0.1, duration_s: 33.3, strength: 0.25, jitter_s: 0.05}
  - {kind: controller_stop, target: uav, on: uav.lower, duration_s: 45}
  - {kind: motor_stall, target: right_wheel, on: ugv.return, permanent: true}
  - {kind: grasp_fail, on: ugv.explore, at_s: 1}
)");
  const std::string text = fault_plan_to_yaml(p);
  EXPECT_EQ(parse(text), p) << text;
  EXPECT_EQ(fault_plan_to_yaml(parse(text)), text);
}

TEST(FaultPlan, DescribesAFaultOnOneLine) {
  const FaultPlan p = parse(R"(
faults:
  - {kind: link_outage, on: ugv.explore, at_s: 20, duration_s: 60}
  - {kind: wheel_slip, at_s: 5, permanent: true, strength: 0.4}
  - {kind: battery_sag, target: uav, at_s: 100, strength: 0.25}
)");
  EXPECT_EQ(describe(p.faults[0]), "link_outage both_ways on ugv.explore +20 s for 60 s");
  EXPECT_EQ(describe(p.faults[1]), "wheel_slip ugv 0.4 fraction at 5 s to the end");
  EXPECT_EQ(describe(p.faults[2]), "battery_sag uav 0.25 fraction at 100 s");
}

TEST(FaultPlan, ALastingFaultActsFromItsStartForItsDuration) {
  Fault f;
  f.duration_s = 10.0;
  EXPECT_FALSE(f.active(std::nullopt, 5.0));  // not started
  EXPECT_FALSE(f.active(20.0, 19.9));
  EXPECT_TRUE(f.active(20.0, 20.0));
  EXPECT_TRUE(f.active(20.0, 29.9));
  EXPECT_FALSE(f.active(20.0, 30.0));
  f.duration_s = std::nullopt;
  EXPECT_TRUE(f.active(20.0, 1e6));
  f.duration_s = 0.0;
  EXPECT_FALSE(f.active(20.0, 20.0));  // instantaneous: fired once, never "active"
}

TEST(FaultPlan, RefusesBadFaultsNamingTheField) {
  struct Case {
    const char* yaml;
    const char* field;
    const char* says;
  };
  const Case cases[] = {
      {"faults: {kind: link_loss}\n", "faults", "a list of faults"},
      {"faults: [{kind: meteor}]\n", "faults[0].kind", "link_loss, link_outage"},
      {"faults: [{at_s: 3}]\n", "faults[0].kind", "required field missing"},
      {"faults: [{kind: link_loss, strength: 1.5}]\n", "faults[0].strength", "[0, 1]"},
      {"faults: [{kind: link_loss, strength: .nan}]\n", "faults[0].strength", ""},
      {"faults: [{kind: link_loss, at_s: -1}]\n", "faults[0].at_s", ""},
      {"faults: [{kind: link_loss, at_s: .inf}]\n", "faults[0].at_s", ""},
      {"faults: [{kind: link_outage, duration_s: 500}]\n", "faults[0].duration_s", "[1, 120]"},
      {"faults: [{kind: link_outage, strength: 1}]\n", "faults[0].strength", "has none"},
      {"faults: [{kind: link_outage, burst_s: 1}]\n", "faults[0].burst_s", "has none"},
      {"faults: [{kind: link_loss, jitter_s: 1}]\n", "faults[0].jitter_s", "has none"},
      {"faults: [{kind: imu_spike, duration_s: 1}]\n", "faults[0].duration_s", "once"},
      {"faults: [{kind: grasp_fail, permanent: true}]\n", "faults[0].permanent", "once"},
      {"faults: [{kind: uav_gust, permanent: true}]\n", "faults[0].permanent", "cannot last"},
      {"faults: [{kind: link_loss, permanent: true, duration_s: 3}]\n", "faults[0].duration_s",
       "permanent"},
      {"faults: [{kind: motor_stall, target: uav}]\n", "faults[0].target",
       "left_wheel, right_wheel"},
      {"faults: [{kind: link_loss, on: ugv.fly}]\n", "faults[0].on", "ugv.explore, ugv.return"},
      {"faults: [{kind: link_loss, on: boat.search}]\n", "faults[0].on", "uav.search"},
      {"faults: [{kind: link_loss, on: uav}]\n", "faults[0].on", "ROBOT.STATE"},
      {"faults: [{kind: link_loss, colour: red}]\n", "faults[0].colour", ""},
      {"faults: [{kind: link_loss}, {kind: link_loss, strength: x}]\n", "faults[1].strength", ""},
      {"faults: [[1, 2]]\n", "faults[0]", ""},
  };
  for (const Case& c : cases) {
    const test::Refusal r = refusal(c.yaml);
    EXPECT_EQ(r.field, c.field) << c.yaml;
    EXPECT_THAT(r.what, HasSubstr(c.says)) << c.yaml;
  }
}

TEST(FaultPlan, RefusesAbsurdlyManyFaults) {
  std::string text = "faults:\n";
  for (std::size_t i = 0; i <= kMaxFaults; ++i) text += "  - {kind: ir_stuck}\n";
  const test::Refusal r = refusal(text);
  EXPECT_EQ(r.field, "faults");
  EXPECT_THAT(r.what, HasSubstr("at most 256"));
}

TEST(FaultPlan, TheKindsTableIsInEnumOrderWithSaneRanges) {
  std::set<std::string_view> names;
  for (std::size_t i = 0; i < fault_kinds().size(); ++i) {
    const FaultKindSpec& s = fault_kinds()[i];
    EXPECT_EQ(static_cast<std::size_t>(s.kind), i) << s.name;  // spec() indexes by the enum
    EXPECT_TRUE(names.insert(s.name).second) << s.name;
    EXPECT_FALSE(s.targets.empty()) << s.name;
    if (!s.instantaneous) {
      EXPECT_LE(s.duration_lo_s, s.draw_duration_lo_s) << s.name;
      EXPECT_LE(s.draw_duration_lo_s, s.draw_duration_hi_s) << s.name;
      EXPECT_LE(s.draw_duration_hi_s, s.duration_hi_s) << s.name;
      EXPECT_GE(s.duration_s, s.duration_lo_s) << s.name;
      EXPECT_LE(s.duration_s, s.duration_hi_s) << s.name;
    }
    for (const auto& n : {s.strength, s.extra})
      if (n) {
        EXPECT_LE(n->lo, n->draw_lo) << s.name;
        EXPECT_LE(n->draw_lo, n->draw_hi) << s.name;
        EXPECT_LE(n->draw_hi, n->hi) << s.name;
        EXPECT_GE(n->fallback, n->lo) << s.name;
        EXPECT_LE(n->fallback, n->hi) << s.name;
      }
  }
  EXPECT_EQ(names.size(), 24u);
}

TEST(FaultPlan, TheSameSeedDrawsTheSamePlanAndAnotherSeedAnother) {
  const FaultDrawOptions o;
  const FaultPlan a = draw_fault_plan(7, o, kStates);
  EXPECT_EQ(a, draw_fault_plan(7, o, kStates));
  EXPECT_NE(a, draw_fault_plan(8, o, kStates));
  // A drawn plan written out reads back the same: the campaign's replay command.
  EXPECT_EQ(parse(fault_plan_to_yaml(a)), a) << fault_plan_to_yaml(a);
}

TEST(FaultPlan, DrawsWithinTheKindsRangesAndTheOptions) {
  FaultDrawOptions o;
  o.min_faults = 2;
  o.max_faults = 5;
  o.horizon_s = 600.0;
  std::set<FaultKind> seen_kinds;
  int state_starts = 0, permanent = 0, total = 0;
  for (std::uint64_t seed = 1; seed <= 400; ++seed) {
    const FaultPlan p = draw_fault_plan(seed, o, kStates);
    ASSERT_GE(p.faults.size(), 2u);
    ASSERT_LE(p.faults.size(), 5u);
    for (const Fault& f : p.faults) {
      ++total;
      const FaultKindSpec& s = spec(f.kind);
      seen_kinds.insert(f.kind);
      EXPECT_NE(std::find(s.targets.begin(), s.targets.end(), f.target), s.targets.end());
      if (f.start.robot == FaultRobot::kNone) {
        EXPECT_GE(f.start.at_s, 0.0);
        EXPECT_LT(f.start.at_s, 600.0);
      } else {
        ++state_starts;
        EXPECT_LT(f.start.at_s, o.max_delay_after_state_s);
      }
      if (s.instantaneous) {
        EXPECT_EQ(f.duration_s, 0.0);
      } else if (!f.duration_s) {
        ++permanent;
        EXPECT_TRUE(s.may_be_permanent) << s.name;
      } else {
        EXPECT_GE(*f.duration_s, s.draw_duration_lo_s) << s.name;
        EXPECT_LE(*f.duration_s, s.draw_duration_hi_s) << s.name;
      }
      if (s.strength) {
        EXPECT_GE(f.strength, s.strength->draw_lo) << s.name;
        EXPECT_LE(f.strength, s.strength->draw_hi) << s.name;
      } else {
        EXPECT_EQ(f.strength, 0.0) << s.name;
      }
    }
  }
  EXPECT_EQ(seen_kinds.size(), fault_kinds().size());  // every kind gets drawn
  EXPECT_NEAR(static_cast<double>(state_starts) / total, 0.5, 0.08);
  EXPECT_GT(permanent, 0);
  EXPECT_LT(static_cast<double>(permanent) / total, 0.15);
}

TEST(FaultPlan, DrawsOnlyTheKindsAskedForAndTimesWithoutStates) {
  FaultDrawOptions o;
  o.kinds = {FaultKind::kLinkOutage, FaultKind::kLinkLoss};
  for (std::uint64_t seed = 1; seed <= 50; ++seed)
    for (const Fault& f : draw_fault_plan(seed, o, FaultStates{}).faults) {
      EXPECT_TRUE(f.kind == FaultKind::kLinkOutage || f.kind == FaultKind::kLinkLoss);
      EXPECT_EQ(f.start.robot, FaultRobot::kNone);
    }
  o.min_faults = 3;
  o.max_faults = 2;
  EXPECT_THROW((void)draw_fault_plan(1, o, kStates), std::invalid_argument);
}

}  // namespace
}  // namespace ferret
