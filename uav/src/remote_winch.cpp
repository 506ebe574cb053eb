#include "ferret/uav/remote_winch.hpp"

#include <cmath>
#include <nlohmann/json.hpp>

#include "ferret/core/error.hpp"

namespace ferret {
namespace {

using link::StreamMessage;
using nlohmann::json;

std::string dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

StreamMessage refused(const std::string& op, const std::string& error) {
  return {dump({{"ok", false}, {"op", op}, {"error", error}}), {}};
}

json parse_reply(const StreamMessage& m, const std::string& op) {
  json j = json::parse(m.header, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("ok") || !j["ok"].is_boolean())
    throw WinchProtocolError("winch: the reply to '" + op + "' is not a JSON object with a boolean 'ok'");
  if (!j["ok"].get<bool>()) {
    const std::string why = j.contains("error") && j["error"].is_string() ? j["error"].get<std::string>() : "no reason given";
    throw WinchProtocolError("winch: '" + op + "' refused: " + printable(why));
  }
  return j;
}

double finite(const json& j, const char* key, const std::string& op) {
  if (!j.contains(key) || !j[key].is_number())
    throw WinchProtocolError("winch: the reply to '" + op + "' has no number '" + key + "'");
  const double v = j[key].get<double>();
  if (!std::isfinite(v)) throw WinchProtocolError("winch: '" + std::string(key) + "' is not finite");
  return v;
}

}  // namespace

std::optional<StreamMessage> WinchService::handle(const std::string& op, const std::string& request) {
  if (op != "winch_torque" && op != "winch_velocity" && op != "winch_state") return std::nullopt;
  const json r = json::parse(request, nullptr, false);
  if (r.is_discarded() || !r.is_object()) return refused(op, "the request is not a JSON object");
  try {
    if (op == "winch_torque") {
      if (!r.contains("enabled") || !r["enabled"].is_boolean()) return refused(op, "'enabled': expected a boolean");
      winch_.set_torque_enabled(r["enabled"].get<bool>());
      return StreamMessage{R"({"ok":true})", {}};
    }
    if (op == "winch_velocity") {
      // A spool turns at metres a second; beyond 100 m/s it is a client bug.
      if (!r.contains("speed_mps") || !r["speed_mps"].is_number() || !std::isfinite(r["speed_mps"].get<double>()) ||
          std::abs(r["speed_mps"].get<double>()) > 100.0)
        return refused(op, "'speed_mps': expected a number in [-100, 100]");
      winch_.command_velocity_mps(r["speed_mps"].get<double>());
      return StreamMessage{R"({"ok":true})", {}};
    }
    const tether::WinchState s = winch_.read_state();
    return StreamMessage{
        dump({{"ok", true}, {"released_m", s.released_m}, {"speed_mps", s.speed_mps}, {"tension_n", s.tension_n}}), {}};
  } catch (const std::exception& e) {  // the winch's own error (a servo that does not answer)
    return refused(op, e.what());
  }
}

void RemoteWinch::set_torque_enabled(bool enabled) {
  (void)parse_reply(channel_.call(dump({{"op", "winch_torque"}, {"enabled", enabled}})), "winch_torque");
}

void RemoteWinch::command_velocity_mps(double speed_mps) {
  (void)parse_reply(channel_.call(dump({{"op", "winch_velocity"}, {"speed_mps", speed_mps}})), "winch_velocity");
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
