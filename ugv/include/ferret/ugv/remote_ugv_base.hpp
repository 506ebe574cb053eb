#pragma once
// The miniUGV's base across a process boundary (docs/robots.md, "The base protocol"):
// UgvBaseService answers requests against a UgvBase (the simulated world serves its
// simulated base with it), and RemoteUgvBase is a UgvBase whose every call is one
// request over an RpcChannel. A robot process's controller drives a RemoteUgvBase as it
// drives any base; what serves it decides whether the wheels are simulated.
//
// One request, one reply, JSON headers over link::MessageStream (the flight adapter's
// framing). Numbers travel as JSON numbers, which carry a double exactly, so a mission
// over the protocol makes the same decisions as one with the base in its process.

#include <memory>
#include <string>

#include "ferret/link/message_stream.hpp"
#include "ferret/ugv/ugv_base.hpp"

namespace ferret::link {
class JsonDispatcher;
}

namespace ferret {

/// The protocol version both halves speak; a server that answers another is refused.
inline constexpr int kUgvBaseProtocol = 1;
/// The most beams a scan and detections a frame may carry (a reply beyond is broken).
inline constexpr std::size_t kMaxRemoteBeams = 4096;
inline constexpr std::size_t kMaxRemoteDetections = 256;

/// The server answered, but refused the request or broke the protocol (a plain
/// link::StreamError is the connection's: lost, silent, or not a message stream).
class UgvBaseProtocolError : public link::StreamError {
 public:
  using link::StreamError::StreamError;
};

class UgvBaseService {
 public:
  /// `server_name` is what "hello" answers ("sim", ...).
  UgvBaseService(UgvBase& base, std::string server_name);
  ~UgvBaseService();
  UgvBaseService(const UgvBaseService&) = delete;
  UgvBaseService& operator=(const UgvBaseService&) = delete;

  /// The reply to one request. Never throws for a bad request: it is a reply with
  /// "ok": false and an "error" naming the field and what was expected.
  [[nodiscard]] link::StreamMessage handle(const link::StreamMessage& request) const;

  /// The ops it answers (protocol 1's). A server adds its own beside them (the
  /// simulated world's "ugv_deployment").
  [[nodiscard]] link::JsonDispatcher& dispatcher() { return *dispatcher_; }

 private:
  UgvBase& base_;
  std::string name_;
  std::unique_ptr<link::JsonDispatcher> dispatcher_;
};

class RemoteUgvBase final : public UgvBase {
 public:
  /// Greets the server ("hello") and checks its protocol version. `backend` is what the
  /// run's first lines print ("sim" for the simulated world's base). Throws
  /// UgvBaseProtocolError for a server that speaks another version, link::StreamError
  /// for one that does not answer.
  RemoteUgvBase(link::RpcChannel& channel, std::string backend);

  [[nodiscard]] std::string backend() const override { return backend_; }
  /// What the server said it is in its hello.
  [[nodiscard]] const std::string& server_name() const { return server_; }
  [[nodiscard]] Pose2 odometry() const override;
  [[nodiscard]] double speed_mps() const override;
  [[nodiscard]] RangeScan ir_scan() override;
  [[nodiscard]] CameraFrame camera_frame(double time_s) override;
  void command_velocity(double v_mps, double w_radps) override;
  void set_epm(bool on) override;
  [[nodiscard]] UgvStatus status() const override;

 private:
  link::RpcChannel& channel_;
  std::string backend_;
  std::string server_;
};

}  // namespace ferret
