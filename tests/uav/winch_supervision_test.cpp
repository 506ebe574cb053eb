// Winch supervision against a winch that only records what it is commanded.

#include "ferret/uav/winch_supervision.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace ferret {
namespace {

class RecordingWinch final : public tether::Winch {
 public:
  void set_torque_enabled(bool on) override { torque = on; }
  void command_velocity_mps(double v) override { commands.push_back(v); }
  tether::WinchState read_state() override { return {}; }
  bool torque = false;
  std::vector<double> commands;
};

WinchSupervision::Options options() {
  WinchSupervision::Options o;
  o.entry_offset_m = 1.0;
  o.controller = "baseline";
  o.control.slack_reference_m = 0.10;
  o.retract_speed_mps = 0.4;
  return o;
}

tether::WinchState released(double m, double tension_n = 0.0) {
  tether::WinchState w;
  w.released_m = m;
  w.tension_n = tension_n;
  return w;
}

TEST(WinchSupervision, LowersToTheEntryAndTheSlackThenHandsOverAndReelsIn) {
  RecordingWinch winch;
  WinchSupervision ws(winch, options());
  ws.switch_on();
  EXPECT_TRUE(winch.torque);
  EXPECT_EQ(winch.commands.back(), 0.0);
  // l_0 + the slack reference: 1.10 m, within a centimetre.
  EXPECT_FALSE(ws.ugv_at_entry(released(1.08)));
  EXPECT_TRUE(ws.ugv_at_entry(released(1.095)));
  // Level: the guard pays out at its lowering speed; near the entry, no further than it.
  ws.keep_touchdown_guard();
  const UgvReport level;
  ws.lower(0.0, level, released(0.2));
  EXPECT_DOUBLE_EQ(winch.commands.back(), tether::TouchdownGuard::Options{}.lowering_speed_mps);
  ws.lower(0.1, level, released(1.08));
  EXPECT_NEAR(winch.commands.back(), 1.10 - 1.08 + 0.05, 1e-12);
  ws.start_taut_control();
  EXPECT_EQ(winch.commands.back(), 0.0);
  // Not heard from (the link silent): the winch holds its length.
  UgvReport silent;
  silent.link_ok = false;
  silent.running = true;
  ws.follow_ugv(1.0, silent, released(1.1));
  EXPECT_EQ(winch.commands.back(), 0.0);
  ws.reel_in();
  EXPECT_DOUBLE_EQ(winch.commands.back(), -0.4);
  EXPECT_FALSE(ws.reeled_in(released(0.02)));
  EXPECT_TRUE(ws.reeled_in(released(0.01)));
}

TEST(WinchSupervision, ASilentLinkHoldsTheLineYetPaysOutAgainstAPullAboveTheGuard) {
  RecordingWinch winch;
  WinchSupervision ws(winch, options());
  ws.switch_on();
  ws.start_taut_control();
  UgvReport silent;
  silent.link_ok = false;
  silent.running = true;
  // The line's defaults: 0.5 N hanging, a 1.5 N guard, 10 N the limit, 0.6 m/s the
  // spool's top speed: the pull above 2 N over the 8 N left, times 0.6 m/s.
  const auto command_at = [&](double tension_n) {
    ws.follow_ugv(1.0, silent, released(2.0, tension_n));
    return winch.commands.back();
  };
  EXPECT_EQ(command_at(0.0), 0.0);
  EXPECT_EQ(command_at(0.5), 0.0);  // the hanging part alone
  EXPECT_EQ(command_at(2.0), 0.0);  // at the guard
  EXPECT_NEAR(command_at(4.0), 0.6 * 2.0 / 8.0, 1e-12);
  EXPECT_NEAR(command_at(6.0), 0.6 * 4.0 / 8.0, 1e-12);
  EXPECT_NEAR(command_at(10.0), 0.6, 1e-12);
  EXPECT_NEAR(command_at(40.0), 0.6, 1e-12);  // no faster than the spool
  EXPECT_EQ(command_at(std::numeric_limits<double>::quiet_NaN()), 0.0);
  // A miniUGV that has not started is not followed either: the same yield.
  UgvReport idle;
  ws.follow_ugv(1.0, idle, released(2.0, 6.0));
  EXPECT_NEAR(winch.commands.back(), 0.3, 1e-12);
}

TEST(WinchSupervision, AnUnknownControllerIsRefusedWhenBuilt) {
  RecordingWinch winch;
  WinchSupervision::Options o = options();
  o.controller = "pid";
  EXPECT_ANY_THROW(WinchSupervision(winch, o));
}

}  // namespace
}  // namespace ferret
