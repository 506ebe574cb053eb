#include "ferret/link/json_dispatcher.hpp"

#include <cmath>

namespace ferret::link {

using nlohmann::json;

void JsonDispatcher::add(const std::string& op, Handler handler) {
  if (!handlers_.emplace(op, std::move(handler)).second)
    throw std::logic_error("JsonDispatcher of " + protocol_ + ": op '" + op + "' added twice");
}

std::vector<std::string> JsonDispatcher::ops() const {
  std::vector<std::string> out;
  out.reserve(handlers_.size());
  for (const auto& [op, handler] : handlers_) out.push_back(op);
  return out;
}

StreamMessage JsonDispatcher::handle(const StreamMessage& request) const {
  std::string op;
  try {
    const json r = json::parse(request.header, nullptr, false);
    if (r.is_discarded() || !r.is_object()) throw RequestError("the request is not a JSON object");
    if (!r.contains("op") || !r["op"].is_string()) throw RequestError("'op': expected a string");
    op = r["op"].get<std::string>();
    const auto it = handlers_.find(op);
    if (it == handlers_.end()) {
      std::string known;
      for (const auto& [name, handler] : handlers_) known += (known.empty() ? "" : ", ") + name;
      throw RequestError("'op': '" + op + "' is not an op of " + protocol_ + " (known: " + known +
                         ")");
    }
    JsonReply reply = it->second(JsonRequest{r, request.blob});
    reply.fields["ok"] = true;
    return {dump_json(reply.fields), std::move(reply.blob)};
  } catch (const std::exception& e) {
    // A refusal, or the device's own error (a command it cannot take now).
    return {dump_json(json{{"ok", false}, {"op", op}, {"error", e.what()}}), {}};
  }
}

void JsonDispatcher::serve(MessageStream& stream, const std::function<bool()>& keep_going) const {
  while (keep_going()) {
    std::optional<StreamMessage> request;
    try {
      request = stream.receive(100);
    } catch (const StreamError&) {
      return;  // the client went away
    }
    if (request) stream.send(handle(*request));
  }
}

std::string dump_json(const json& j) {
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

double request_number(const json& request, const char* key, double lo, double hi) {
  if (!request.contains(key) || !request[key].is_number())
    throw RequestError(std::string("'") + key + "': expected a number");
  const double v = request[key].get<double>();
  if (!std::isfinite(v) || v < lo || v > hi)
    throw RequestError(std::string("'") + key + "': expected a number in [" + json(lo).dump() +
                       ", " + json(hi).dump() + "], got " + json(v).dump());
  return v;
}

bool request_bool(const json& request, const char* key) {
  if (!request.contains(key) || !request[key].is_boolean())
    throw RequestError(std::string("'") + key + "': expected a boolean");
  return request[key].get<bool>();
}

}  // namespace ferret::link
