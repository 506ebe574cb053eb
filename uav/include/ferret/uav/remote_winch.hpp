#pragma once
// The winch across a process boundary (docs/robots.md, "The winch across a process
// boundary"): add_winch_ops answers requests against a tether::Winch (the simulated
// world serves its simulated winch with them, beside the flight adapter's ops), and
// RemoteWinch is a Winch whose every call is one request over an RpcChannel. On the
// UAV the winch process drives DynamixelWinch directly.

#include <memory>

#include "ferret/link/message_stream.hpp"
#include "ferret/tether_model/winch.hpp"

namespace ferret::link {
class JsonDispatcher;
}

namespace ferret {

/// The server answered, but refused the request or broke the protocol.
class WinchProtocolError : public link::StreamError {
 public:
  using link::StreamError::StreamError;
};

/// Adds the winch protocol's ops ("winch_torque", "winch_velocity", "winch_state")
/// against `winch` to a server's dispatcher (the simulated world answers them beside the
/// flight adapter's). A bad request is refused naming the field and never reaches the
/// winch. `winch` must outlive the dispatcher.
void add_winch_ops(link::JsonDispatcher& dispatcher, tether::Winch& winch);

/// A server of the winch alone.
class WinchService {
 public:
  explicit WinchService(tether::Winch& winch);
  ~WinchService();
  /// The reply to one request; never throws for a bad one: "ok": false with an "error"
  /// naming the field (an op that is not the winch's is refused too).
  [[nodiscard]] link::StreamMessage handle(const link::StreamMessage& request) const;

 private:
  std::unique_ptr<link::JsonDispatcher> dispatcher_;
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
