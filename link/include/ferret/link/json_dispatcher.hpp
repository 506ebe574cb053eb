#pragma once
// The server half of the JSON request/reply protocols over a MessageStream (the flight
// adapter's, the miniUGV base's, the winch's and the simulated world's own ops): a
// request is a JSON object whose "op" names a handler; the reply is the handler's
// fields with "ok": true, or {"ok": false, "op": ..., "error": ...} for anything that
// goes wrong, always in the same words. Included by the protocols' sources only: it
// brings nlohmann/json.

#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "ferret/link/message_stream.hpp"

namespace ferret::link {

/// A request a handler refuses: its message is the reply's "error" (name the field and
/// what was expected).
class RequestError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct JsonRequest {
  const nlohmann::json& fields;           ///< the whole request object, "op" included
  const std::vector<std::uint8_t>& blob;  ///< the request's blob (often empty)
};

struct JsonReply {
  JsonReply() = default;
  // Implicit: a handler returns its fields.
  JsonReply(nlohmann::json reply_fields) : fields(std::move(reply_fields)) {}  // NOLINT
  JsonReply(nlohmann::json reply_fields, std::vector<std::uint8_t> reply_blob)
      : fields(std::move(reply_fields)), blob(std::move(reply_blob)) {}
  nlohmann::json fields;  ///< an object, or null for none; the dispatcher adds "ok": true
  std::vector<std::uint8_t> blob;
};

class JsonDispatcher {
 public:
  using Handler = std::function<JsonReply(const JsonRequest&)>;

  /// `protocol` names the protocol in the error for an unknown op ("the flight adapter
  /// protocol 1").
  explicit JsonDispatcher(std::string protocol) : protocol_(std::move(protocol)) {}

  /// Adds `op`. Throws std::logic_error for an op that has a handler already.
  void add(const std::string& op, Handler handler);
  [[nodiscard]] bool contains(const std::string& op) const { return handlers_.contains(op); }
  /// The ops it answers, sorted.
  [[nodiscard]] std::vector<std::string> ops() const;

  /// The reply to one request. Never throws: a header that is not a JSON object, an
  /// "op" missing or not a string, an op without a handler (the error lists the known
  /// ones) and any exception of a handler (RequestError, InputError, the device's own)
  /// become {"ok": false, "op": the op or "", "error": its text}.
  [[nodiscard]] StreamMessage handle(const StreamMessage& request) const;

  /// Answers requests on `stream` until the peer closes it or `keep_going()` says no
  /// (checked every 100 ms while idle).
  void serve(MessageStream& stream, const std::function<bool()>& keep_going) const;

 private:
  std::string protocol_;
  std::map<std::string, Handler> handlers_;
};

/// The JSON text of `j`, bytes that are not UTF-8 replaced (a reply must always dump).
[[nodiscard]] std::string dump_json(const nlohmann::json& j);

/// Field readers for handlers; each throws RequestError naming the field.
/// A number in [lo, hi]: "'key': expected a number" / "... in [lo, hi], got v".
[[nodiscard]] double request_number(const nlohmann::json& request, const char* key, double lo,
                                    double hi);
/// A boolean: "'key': expected a boolean".
[[nodiscard]] bool request_bool(const nlohmann::json& request, const char* key);

}  // namespace ferret::link
