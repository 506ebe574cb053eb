// Winch supervision against a winch that only records what it is commanded.

#include "ferret/uav/winch_supervision.hpp"

#include <gtest/gtest.h>

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

tether::WinchState released(double m) {
  tether::WinchState w;
  w.released_m = m;
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

TEST(WinchSupervision, AnUnknownControllerIsRefusedWhenBuilt) {
  RecordingWinch winch;
  WinchSupervision::Options o = options();
  o.controller = "pid";
  EXPECT_ANY_THROW(WinchSupervision(winch, o));
}

}  // namespace
}  // namespace ferret
