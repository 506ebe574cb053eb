// The winch protocol's two parsers on arbitrary bytes (docs/robots.md, "The winch across
// a process boundary"): the first byte picks the side.
// - Even: a request to WinchService over a recording winch. Every reply is a JSON
//   object with a boolean "ok"; a refused request never reaches the winch; a velocity
//   is finite and within 100 m/s.
// - Odd: the reply a server sends RemoteWinch to each call; only WinchProtocolError,
//   and a state read is finite with a length >= 0.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>

#include "ferret/uav/remote_winch.hpp"
#include "rpc_replay.hpp"

namespace {

using ferret::link::StreamMessage;

struct RecordingWinch final : ferret::tether::Winch {
  int commands = 0;
  void set_torque_enabled(bool) override { ++commands; }
  void command_velocity_mps(double v) override {
    if (!std::isfinite(v) || std::abs(v) > 100) std::abort();
    ++commands;
  }
  ferret::tether::WinchState read_state() override { return {}; }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (data[0] % 2 == 0) {
    RecordingWinch winch;
    ferret::WinchService service(winch);
    const StreamMessage reply = service.handle({text, {}});
    const auto r = nlohmann::json::parse(reply.header, nullptr, false);
    if (r.is_discarded() || !r.is_object() || !r.contains("ok") || !r["ok"].is_boolean())
      std::abort();
    if (!r["ok"].get<bool>() && winch.commands != 0) std::abort();
    return 0;
  }
  ferret::fuzz::RpcReplay channel;
  channel.reply.header = text;
  ferret::RemoteWinch winch(channel);
  try {
    const ferret::tether::WinchState s = winch.read_state();
    if (!std::isfinite(s.released_m) || s.released_m < 0 || !std::isfinite(s.speed_mps) ||
        !std::isfinite(s.tension_n))
      std::abort();
  } catch (const ferret::WinchProtocolError&) {
  }
  try {
    winch.set_torque_enabled(true);
    winch.command_velocity_mps(0.3);
  } catch (const ferret::WinchProtocolError&) {
  }
  return 0;
}
