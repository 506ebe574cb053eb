#pragma once
// Request/response messages over TCP between a robot process and what serves its
// hardware: an onboard flight adapter (docs/flight_adapter.md) or a simulated one. A message is a
// JSON header and an optional binary blob (a camera frame): on the wire, two little-endian uint32
// lengths (header, blob), then the header's UTF-8 bytes, then the blob.

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "ferret/link/ip_address.hpp"

namespace ferret::link {

/// A broken or closed connection, or a peer that does not speak the framing.
class StreamError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StreamMessage {
  std::string header;              ///< one JSON object
  std::vector<std::uint8_t> blob;  ///< may be empty
};

class MessageStream {
 public:
  static constexpr std::size_t kMaxHeaderBytes = 1u << 20;  ///< 1 MiB of JSON
  static constexpr std::size_t kMaxBlobBytes = 64u << 20;   ///< 64 MiB: a 4K depth frame fits

  /// Connects, retrying for up to `timeout_s` (the server may still be starting).
  /// Throws StreamError naming the address when nothing answers.
  [[nodiscard]] static MessageStream connect(const Ipv4Address& address, double timeout_s);
  MessageStream(MessageStream&&) noexcept;
  MessageStream& operator=(MessageStream&&) noexcept;
  ~MessageStream();

  void send(const StreamMessage& message);
  void send(const std::string& header) { send(StreamMessage{header, {}}); }
  /// The next message, or none after `timeout_ms` (-1: wait) without one starting.
  /// Throws StreamError when the peer closed the connection, sent a frame beyond the
  /// limits, or stopped for 5 s in the middle of one.
  [[nodiscard]] std::optional<StreamMessage> receive(int timeout_ms);
  [[nodiscard]] int fd() const { return fd_; }
  [[nodiscard]] const std::string& peer() const { return peer_; }

 private:
  friend class MessageListener;
  MessageStream(int fd, std::string peer) : fd_(fd), peer_(std::move(peer)) {}
  void read_exact(std::uint8_t* data, std::size_t size);
  int fd_ = -1;
  std::string peer_;
};

class MessageListener {
 public:
  /// Listens on `address` (port 0: the system picks one, see port()). Throws InputError
  /// naming `source` and `field` (the configuration's) when it cannot be bound.
  MessageListener(const Ipv4Address& address, const std::string& source, const std::string& field);
  MessageListener(MessageListener&&) noexcept;
  MessageListener& operator=(MessageListener&&) noexcept;
  ~MessageListener();
  /// A connection, or none after `timeout_ms`.
  [[nodiscard]] std::optional<MessageStream> accept(int timeout_ms);
  [[nodiscard]] std::uint16_t port() const { return port_; }

 private:
  int fd_ = -1;
  std::uint16_t port_ = 0;
};

/// A request/response channel (the robot process's side): the hardware backends that
/// live across a process boundary (the flight adapter, the simulated world's winch and
/// miniUGV base) call through it. A reply with "ok": false becomes a StreamError with
/// its "error" text.
class RpcChannel {
 public:
  virtual ~RpcChannel() = default;
  /// Sends `request` (a JSON object with an "op") and returns the reply.
  [[nodiscard]] virtual StreamMessage call(const std::string& request) = 0;
};

/// RpcChannel over a MessageStream: one request, then its reply within `reply_timeout_ms`
/// (a StreamError after it: an adapter that does not answer is a broken adapter).
class StreamRpcChannel final : public RpcChannel {
 public:
  StreamRpcChannel(MessageStream stream, int reply_timeout_ms)
      : stream_(std::move(stream)), reply_timeout_ms_(reply_timeout_ms) {}
  [[nodiscard]] StreamMessage call(const std::string& request) override;
  [[nodiscard]] MessageStream& stream() { return stream_; }

 private:
  MessageStream stream_;
  int reply_timeout_ms_;
};

/// The robot link's datagrams carried in a stream message's blob (the simulated world
/// relays them between the robot processes through its simulated network): each as a
/// little-endian uint32 length, then its bytes.
[[nodiscard]] std::vector<std::uint8_t> pack_datagrams(
    const std::vector<std::vector<std::uint8_t>>& datagrams);
/// The datagrams of a blob; StreamError for a length past the blob's end, or a datagram
/// longer than `max_datagram_bytes` (the robot link's are a few hundred bytes).
[[nodiscard]] std::vector<std::vector<std::uint8_t>> unpack_datagrams(
    const std::vector<std::uint8_t>& blob, std::size_t max_datagram_bytes = 65536);

}  // namespace ferret::link
