// The JSON protocols' dispatcher (link/json_dispatcher.hpp) on arbitrary request bytes:
// the header is the input up to its first NUL, the blob what follows. A dispatcher with
// ops that answer, refuse (RequestError, InputError, a device's error) and echo the blob.
// Every reply must be a JSON object with a boolean "ok" and nothing else may escape; a
// refusal names an op (a string, "" before one is read) and a non-empty error; a
// handler runs only for a request whose "op" is its name; an unknown op's error lists
// the known ones; a good reply carries the handler's fields and blob.
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/link/json_dispatcher.hpp"

namespace {

using ferret::link::JsonReply;
using ferret::link::JsonRequest;
using nlohmann::json;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = text.find('\0');
  ferret::link::StreamMessage request{text.substr(0, nul), {}};
  if (nul != std::string::npos)
    request.blob.assign(text.begin() + static_cast<long>(nul) + 1, text.end());

  std::string ran;  // the op whose handler ran
  ferret::link::JsonDispatcher d("the fuzz protocol 1");
  d.add("number", [&](const JsonRequest& r) -> JsonReply {
    ran = "number";
    return json{{"x", ferret::link::request_number(r.fields, "x", -1e3, 1e3)}};
  });
  d.add("flag", [&](const JsonRequest& r) -> JsonReply {
    ran = "flag";
    return json{{"on", ferret::link::request_bool(r.fields, "on")}};
  });
  d.add("echo", [&](const JsonRequest& r) -> JsonReply {
    ran = "echo";
    return {json{{"request", r.fields}}, r.blob};
  });
  d.add("device", [&](const JsonRequest&) -> JsonReply {
    ran = "device";
    throw std::runtime_error("the device does not answer");
  });
  d.add("input", [&](const JsonRequest&) -> JsonReply {
    ran = "input";
    throw ferret::InputError("request", "x", "a number");
  });

  const ferret::link::StreamMessage reply = d.handle(request);
  const json r = json::parse(reply.header, nullptr, false);
  if (r.is_discarded() || !r.is_object() || !r.contains("ok") || !r["ok"].is_boolean())
    std::abort();
  const json q = json::parse(request.header, nullptr, false);
  const bool has_op = !q.is_discarded() && q.is_object() && q.contains("op") && q["op"].is_string();
  const std::string op = has_op ? q["op"].get<std::string>() : "";
  if (ran != (d.contains(op) ? op : "")) std::abort();  // the handler of its op, or none
  if (!r["ok"].get<bool>()) {
    if (!r.contains("op") || !r["op"].is_string() || r["op"].get<std::string>() != op) std::abort();
    if (!r.contains("error") || !r["error"].is_string() || r["error"].get<std::string>().empty())
      std::abort();
    if (has_op && !d.contains(op) &&
        r["error"].get<std::string>().find("(known: device, echo, flag, input, number)") ==
            std::string::npos)
      std::abort();
    if (!reply.blob.empty()) std::abort();
    return 0;
  }
  if (ran == "device" || ran == "input" || !d.contains(op)) std::abort();  // these always refuse
  if (ran == "echo" && (reply.blob != request.blob || !r.contains("request"))) std::abort();
  return 0;
}
