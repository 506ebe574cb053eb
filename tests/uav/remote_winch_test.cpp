#include "ferret/uav/remote_winch.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <nlohmann/json.hpp>

#include "ferret/tether_model/simulated_winch.hpp"

namespace ferret {
namespace {

using link::StreamMessage;
using nlohmann::json;

// The client's channel straight into the service (the same bytes as over TCP).
class DirectChannel final : public link::RpcChannel {
 public:
  explicit DirectChannel(WinchService& s) : service_(s) {}
  StreamMessage call(const std::string& request) override { return service_.handle({request, {}}); }

 private:
  WinchService& service_;
};

// A simulated winch driven through the protocol ends where the same winch driven
// directly ends, to the bit: commands and states cross exactly.
TEST(RemoteWinch, TheSimulatedWinchThroughTheProtocolIsTheWinchItself) {
  tether::SimulatedWinch direct({}), served({});
  WinchService service(served);
  DirectChannel channel(service);
  RemoteWinch remote(channel);
  direct.set_torque_enabled(true);
  remote.set_torque_enabled(true);
  for (int k = 0; k < 200; ++k) {
    const double v = k < 100 ? 0.45 : -0.2;
    direct.command_velocity_mps(v);
    remote.command_velocity_mps(v);
    direct.advance(0.01, 2.0);
    served.advance(0.01, 2.0);
    const tether::WinchState a = direct.read_state(), b = remote.read_state();
    ASSERT_EQ(a.released_m, b.released_m) << k;
    ASSERT_EQ(a.speed_mps, b.speed_mps) << k;
    ASSERT_EQ(a.tension_n, b.tension_n) << k;
  }
  EXPECT_GT(remote.read_state().released_m, 0.2);  // it paid out, then reeled some in
}

TEST(RemoteWinch, TheServiceRefusesBadRequestsAndOtherOps) {
  tether::SimulatedWinch winch({});
  winch.set_torque_enabled(true);
  WinchService service(winch);
  const auto refused = [&](const std::string& request) {
    const json r = json::parse(service.handle({request, {}}).header);
    EXPECT_FALSE(r.at("ok").get<bool>()) << request;
    const std::string error = r.value("error", "");
    EXPECT_FALSE(error.empty());
    return error;
  };
  EXPECT_EQ(refused(R"({"op":"winch_velocity"})"), "'speed_mps': expected a number in [-100, 100]");
  refused(R"({"op":"winch_velocity","speed_mps":1e300})");
  refused(R"({"op":"winch_velocity","speed_mps":"fast"})");
  EXPECT_EQ(refused(R"({"op":"winch_torque","enabled":1})"), "'enabled': expected a boolean");
  EXPECT_EQ(refused("not json"), "the request is not a JSON object");
  // Not the winch's: named, with the winch's ops.
  EXPECT_EQ(refused(R"({"op":"takeoff"})"),
            "'op': 'takeoff' is not an op of the winch protocol (known: winch_state, winch_torque, "
            "winch_velocity)");
  winch.advance(1.0, 0.0);
  EXPECT_EQ(winch.read_state().released_m, 0.0);  // no command got through
}

TEST(RemoteWinch, TheClientRefusesBrokenReplies) {
  struct Replay final : link::RpcChannel {
    std::string reply;
    StreamMessage call(const std::string&) override { return {reply, {}}; }
  } replay;
  RemoteWinch remote(replay);
  for (const std::string& reply :
       {std::string("oops"), std::string(R"({"released_m":1})"),
        std::string(R"({"ok":false,"error":"servo silent"})"),
        std::string(R"({"ok":true,"released_m":1,"speed_mps":0})"),
        std::string(R"({"ok":true,"released_m":-0.5,"speed_mps":0,"tension_n":1})"),
        std::string(R"({"ok":true,"released_m":1e999,"speed_mps":0,"tension_n":1})")}) {
    replay.reply = reply;
    EXPECT_THROW((void)remote.read_state(), WinchProtocolError) << reply;
  }
  replay.reply = R"({"ok":false,"error":"servo silent"})";
  EXPECT_THROW(remote.command_velocity_mps(0.1), WinchProtocolError);
  replay.reply = R"({"ok":true,"released_m":2.5,"speed_mps":-0.1,"tension_n":3})";
  EXPECT_EQ(remote.read_state().released_m, 2.5);
}

}  // namespace
}  // namespace ferret
