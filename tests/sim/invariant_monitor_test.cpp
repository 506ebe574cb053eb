// The safety invariants checked from the truth (sim/invariant_monitor.hpp): each kind
// caught when injected, as one episode with its start, states and worst value; a clean
// run safe.
#include "ferret/sim/invariant_monitor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace ferret {
namespace {

InvariantLimits limits() {
  InvariantLimits l;
  l.max_tension_n = 10.0;
  l.tether_length_m = 15.0;
  l.contact_tolerance_m = 0.01;
  l.state_timeout_s["uav"]["lower"] = 60.0;
  l.state_timeout_s["ugv"]["explore"] = 600.0;
  return l;
}

InvariantSample at(double t_s) {
  InvariantSample s;
  s.t_s = t_s;
  s.tension_n = 2.0;
  s.released_m = 3.0;
  s.uav_state = "ugv_ops";
  s.ugv_state = "explore";
  s.ugv_battery = 0.8;
  return s;
}

TEST(InvariantMonitor, ACleanRunIsSafe) {
  InvariantMonitor m(limits());
  for (int i = 0; i < 1000; ++i) {
    InvariantSample s = at(0.1 * i);
    s.tension_n = 9.99;  // at the limit is within it
    s.released_m = 15.0;
    s.ugv_contact_depth_m = 0.01;  // deep, but not against a wall: no contact
    m.observe(s);
  }
  m.finish(at(100.0), false, "", true);
  EXPECT_TRUE(m.safe());
  for (std::size_t k = 0; k < kInvariantKinds; ++k)
    EXPECT_EQ(m.count(static_cast<InvariantKind>(k)), 0);
}

TEST(InvariantMonitor, OverTensionIsOneEpisodeWithItsStartAndPeak) {
  InvariantMonitor m(limits());
  const double tension[] = {5, 11, 14, 12, 8, 3, 10.5, 9};
  for (int i = 0; i < 8; ++i) {
    InvariantSample s = at(i);
    s.tension_n = tension[i];
    if (i == 1) s.uav_state = "retract";
    m.observe(s);
  }
  ASSERT_EQ(m.count(InvariantKind::kTensionOverLimit), 2);  // two rising edges
  const InvariantViolation& v = m.violations()[0];
  EXPECT_EQ(v.kind, InvariantKind::kTensionOverLimit);
  EXPECT_DOUBLE_EQ(v.t_s, 1.0);
  EXPECT_DOUBLE_EQ(v.until_s, 3.0);
  EXPECT_EQ(v.uav_state, "retract");  // the states when it started
  EXPECT_DOUBLE_EQ(v.value, 14.0);
  EXPECT_DOUBLE_EQ(v.limit, 10.0);
  EXPECT_DOUBLE_EQ(m.violations()[1].t_s, 6.0);
  EXPECT_FALSE(m.safe());
}

TEST(InvariantMonitor, ATensionNobodyCanReadIsNotUnderTheLimit) {
  InvariantMonitor m(limits());
  InvariantSample s = at(0);
  s.tension_n = std::numeric_limits<double>::quiet_NaN();
  m.observe(s);
  EXPECT_EQ(m.count(InvariantKind::kTensionOverLimit), 1);
}

TEST(InvariantMonitor, CatchesEachKindWhenInjected) {
  struct Case {
    InvariantKind kind;
    void (*inject)(InvariantSample&);
  };
  const Case cases[] = {
      {InvariantKind::kTensionOverLimit, [](InvariantSample& s) { s.tension_n = 30.0; }},
      {InvariantKind::kTetherOverLength, [](InvariantSample& s) { s.released_m = 15.2; }},
      {InvariantKind::kUavCollision, [](InvariantSample& s) { s.uav_collision = true; }},
      {InvariantKind::kUgvBodyContact,
       [](InvariantSample& s) {
         s.ugv_body_contact = true;
         s.ugv_contact_depth_m = 0.05;
       }},
      {InvariantKind::kBatteryEmpty, [](InvariantSample& s) { s.uav_battery = 0.0; }},
      {InvariantKind::kBatteryEmpty, [](InvariantSample& s) { s.ugv_battery = -0.1; }},
  };
  for (const Case& c : cases) {
    InvariantMonitor m(limits());
    m.observe(at(0));
    InvariantSample bad = at(1);
    c.inject(bad);
    m.observe(bad);
    m.observe(at(2));
    EXPECT_EQ(m.violations().size(), 1u) << to_string(c.kind);
    EXPECT_EQ(m.count(c.kind), 1) << to_string(c.kind);
    if (!m.violations().empty()) {
      EXPECT_DOUBLE_EQ(m.violations()[0].t_s, 1.0);
    }
  }
}

TEST(InvariantMonitor, BothBatteriesAreTheirOwnEpisodes) {
  InvariantMonitor m(limits());
  InvariantSample s = at(0);
  s.uav_battery = 0.0;
  m.observe(s);
  s.t_s = 1;
  s.ugv_battery = 0.0;
  m.observe(s);
  ASSERT_EQ(m.count(InvariantKind::kBatteryEmpty), 2);
  EXPECT_EQ(m.violations()[0].detail, "uav");
  EXPECT_EQ(m.violations()[1].detail, "ugv");
  // No miniUGV battery reported (aboard, off): nothing to check.
  InvariantMonitor aboard(limits());
  s.uav_battery = 0.5;
  s.ugv_battery.reset();
  aboard.observe(s);
  EXPECT_TRUE(aboard.safe());
}

TEST(InvariantMonitor, AStateHeldPastItsTimeoutOncePerVisit) {
  InvariantMonitor m(limits());
  InvariantSample s = at(0);
  s.uav_state = "lower";
  s.ugv_state = "";                 // no controller: no clock
  for (int i = 0; i <= 200; ++i) {  // 100 s in `lower`, timeout 60 s
    s.t_s = 0.5 * i;
    m.observe(s);
  }
  ASSERT_EQ(m.count(InvariantKind::kStateTimeout), 1);
  const InvariantViolation& v = m.violations()[0];
  EXPECT_EQ(v.detail, "uav.lower");
  EXPECT_DOUBLE_EQ(v.t_s, 60.5);  // the first step past it
  EXPECT_DOUBLE_EQ(v.limit, 60.0);
  // Left and entered again: a new visit, its own clock.
  s.uav_state = "ugv_ops";
  s.t_s = 101;
  m.observe(s);
  s.uav_state = "lower";
  for (int i = 0; i <= 100; ++i) {  // 50 s: within the timeout
    s.t_s = 102 + 0.5 * i;
    m.observe(s);
  }
  EXPECT_EQ(m.count(InvariantKind::kStateTimeout), 1);
  // States without a timeout are never flagged.
  s.uav_state = "search";
  for (int i = 0; i <= 10; ++i) {
    s.t_s = 200 + 1000.0 * i;
    m.observe(s);
  }
  EXPECT_EQ(m.count(InvariantKind::kStateTimeout), 1);
}

TEST(InvariantMonitor, AMiniUgvLeftBehindNeedsAReason) {
  InvariantMonitor with_reason(limits());
  with_reason.finish(at(10), true, "the tether snagged: recall failed", true);
  EXPECT_TRUE(with_reason.safe());
  InvariantMonitor without(limits());
  without.finish(at(10), true, "", true);
  EXPECT_EQ(without.count(InvariantKind::kUgvLeftBehind), 1);
  InvariantMonitor aboard(limits());
  aboard.finish(at(10), false, "", true);
  EXPECT_TRUE(aboard.safe());
}

TEST(InvariantMonitor, AMissionThatDoesNotEndIsAHang) {
  InvariantMonitor m(limits());
  m.finish(at(14400), false, "", false);
  ASSERT_EQ(m.count(InvariantKind::kNoEnd), 1);
  EXPECT_DOUBLE_EQ(m.violations()[0].t_s, 14400.0);
}

TEST(InvariantMonitor, NamesEveryKind) {
  for (std::size_t k = 0; k < kInvariantKinds; ++k)
    EXPECT_NE(to_string(static_cast<InvariantKind>(k)), "?") << k;
  EXPECT_EQ(to_string(InvariantKind::kTensionOverLimit), "tension_over_limit");
}

TEST(InvariantMonitor, AContactShallowerThanTheToleranceIsNone) {
  InvariantLimits l = limits();  // tolerance 0.01 m
  InvariantMonitor m(l);
  InvariantSample s = at(1);
  s.ugv_body_contact = true;
  s.ugv_contact_depth_m = 0.005;
  m.observe(s);
  EXPECT_TRUE(m.safe());
  l.contact_tolerance_m = 0.0;  // every contact, even one stopped at the face
  InvariantMonitor strict(l);
  s.ugv_contact_depth_m = 0.0;
  strict.observe(s);
  ASSERT_EQ(strict.count(InvariantKind::kUgvBodyContact), 1);
}

}  // namespace
}  // namespace ferret
