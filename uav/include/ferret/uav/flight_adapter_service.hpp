#pragma once
// The flight adapter protocol's server half (docs/flight_adapter.md): one request in,
// one reply out, against a FlightController and its cameras. The reference adapter
// serves the simulated M100 through it, so both halves of the protocol are exercised
// on every test run; an adapter written in C++ against DJI's Onboard SDK can link it
// and implement FlightController and UavCameras over the SDK.

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>

#include "ferret/link/message_stream.hpp"
#include "ferret/uav/flight_controller.hpp"

namespace ferret::link {
class JsonDispatcher;
}

namespace ferret {

class FlightAdapterService {
 public:
  struct Hooks {
    /// The protocol's velocity set-point (m/s in the world, yaw rate rad/s), held until
    /// the next command. Empty: "velocity" is refused as unsupported.
    std::function<void(const Eigen::Vector3d& v_W, double yaw_rate_radps)> velocity;
  };

  /// `adapter_name` is what "hello" answers ("sim", "dji-osdk", ...).
  FlightAdapterService(FlightController& flight, UavCameras& cameras, std::string adapter_name,
                       Hooks hooks = {});
  ~FlightAdapterService();
  FlightAdapterService(const FlightAdapterService&) = delete;
  FlightAdapterService& operator=(const FlightAdapterService&) = delete;

  /// The reply to one request. Never throws for a bad request: it is a reply with
  /// "ok": false and an "error" naming the field and what was expected.
  [[nodiscard]] link::StreamMessage handle(const link::StreamMessage& request);

  /// Answers requests on `stream` until the peer closes it or `keep_going()` says no
  /// (checked every 100 ms while idle).
  void serve(link::MessageStream& stream, const std::function<bool()>& keep_going);

  /// The ops it answers (protocol 1's). A server adds its own beside them (the
  /// simulator's "sim_advance", the winch's ops on the same connection).
  [[nodiscard]] link::JsonDispatcher& dispatcher() { return *dispatcher_; }

 private:
  FlightController& flight_;
  UavCameras& cameras_;
  std::string adapter_name_;
  Hooks hooks_;
  std::unique_ptr<link::JsonDispatcher> dispatcher_;
};

}  // namespace ferret
