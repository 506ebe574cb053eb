#include "ferret/uav/remote_winch.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "ferret/core/error.hpp"
#include "ferret/link/json_dispatcher.hpp"

namespace ferret {
namespace {

using link::StreamMessage;
using nlohmann::json;

using link::dump_json;

json parse_reply(const StreamMessage& m, const std::string& op) {
  json j = json::parse(m.header, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("ok") || !j["ok"].is_boolean())
    throw WinchProtocolError("winch: the reply to '" + op +
                             "' is not a JSON object with a boolean 'ok'");
  if (!j["ok"].get<bool>()) {
    const std::string why = j.contains("error") && j["error"].is_string()
                                ? j["error"].get<std::string>()
                                : "no reason given";
    throw WinchProtocolError("winch: '" + op + "' refused: " + printable(why));
  }
  return j;
}

double finite(const json& j, const char* key, const std::string& op) {
  if (!j.contains(key) || !j[key].is_number())
    throw WinchProtocolError("winch: the reply to '" + op + "' has no number '" + key + "'");
  const double v = j[key].get<double>();
  if (!std::isfinite(v))
    throw WinchProtocolError("winch: '" + std::string(key) + "' is not finite");
  return v;
}

}  // namespace

void add_winch_ops(link::JsonDispatcher& dispatcher, tether::Winch& winch) {
  using link::JsonReply;
  using link::JsonRequest;
  // A bad request is refused before it reaches the winch; the winch's own error (a
  // servo that does not answer) is the dispatcher's refusal too.
  dispatcher.add("winch_torque", [&winch](const JsonRequest& r) -> JsonReply {
    winch.set_torque_enabled(link::request_bool(r.fields, "enabled"));
    return {};
  });
  dispatcher.add("winch_velocity", [&winch](const JsonRequest& r) -> JsonReply {
    // A spool turns at metres a second; beyond 100 m/s it is a client bug.
    const json& j = r.fields;
    if (!j.contains("speed_mps") || !j["speed_mps"].is_number() ||
        !std::isfinite(j["speed_mps"].get<double>()) ||
        std::abs(j["speed_mps"].get<double>()) > 100.0)
      throw link::RequestError("'speed_mps': expected a number in [-100, 100]");
    winch.command_velocity_mps(j["speed_mps"].get<double>());
    return {};
  });
  dispatcher.add("winch_state", [&winch](const JsonRequest&) -> JsonReply {
    const tether::WinchState s = winch.read_state();
    return json{
        {"released_m", s.released_m}, {"speed_mps", s.speed_mps}, {"tension_n", s.tension_n}};
  });
}

WinchService::WinchService(tether::Winch& winch)
    : dispatcher_(std::make_unique<link::JsonDispatcher>("the winch protocol")) {
  add_winch_ops(*dispatcher_, winch);
}

WinchService::~WinchService() = default;

StreamMessage WinchService::handle(const StreamMessage& request) const {
  return dispatcher_->handle(request);
}

void RemoteWinch::set_torque_enabled(bool enabled) {
  (void)parse_reply(channel_.call(dump_json({{"op", "winch_torque"}, {"enabled", enabled}})),
                    "winch_torque");
}

void RemoteWinch::command_velocity_mps(double speed_mps) {
  (void)parse_reply(channel_.call(dump_json({{"op", "winch_velocity"}, {"speed_mps", speed_mps}})),
                    "winch_velocity");
}

tether::WinchState RemoteWinch::read_state() {
  const std::string op = "winch_state";
  const json j = parse_reply(channel_.call(R"({"op":"winch_state"})"), op);
  tether::WinchState s;
  s.released_m = finite(j, "released_m", op);
  s.speed_mps = finite(j, "speed_mps", op);
  s.tension_n = finite(j, "tension_n", op);
  if (s.released_m < 0.0) throw WinchProtocolError("winch: 'released_m' is negative");
  return s;
}

}  // namespace ferret
