#pragma once
// The winch across a process boundary (docs/robots.md, "The winch across a process
// boundary"): WinchService answers requests against a tether::Winch (the simulated
// world serves its simulated winch with it, beside the flight adapter's ops), and
// RemoteWinch is a Winch whose every call is one request over an RpcChannel. On the
// UAV the winch process drives DynamixelWinch directly.

#include <optional>
#include <string>

#include "ferret/link/message_stream.hpp"
#include "ferret/tether_model/winch.hpp"

namespace ferret {

/// The server answered, but refused the request or broke the protocol.
class WinchProtocolError : public link::StreamError {
 public:
  using link::StreamError::StreamError;
};

class WinchService {
 public:
  explicit WinchService(tether::Winch& winch) : winch_(winch) {}
  /// The reply to a request whose op is one of "winch_torque", "winch_velocity",
  /// "winch_state"; none for another op (the caller's to answer). Never throws for a bad
  /// request: "ok": false with an "error" naming the field.
  [[nodiscard]] std::optional<link::StreamMessage> handle(const std::string& op, const std::string& request);

 private:
  tether::Winch& winch_;
};

class RemoteWinch final : public tether::Winch {
 public:
  explicit RemoteWinch(link::RpcChannel& channel) : channel_(channel) {}
  void set_torque_enabled(bool enabled) override;
  void command_velocity_mps(double speed_mps) override;
  /// Throws WinchProtocolError for a reply without finite numbers, or a negative length.
  [[nodiscard]] tether::WinchState read_state() override;

 private:
  link::RpcChannel& channel_;
};

}  // namespace ferret
