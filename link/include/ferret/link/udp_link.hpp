#pragma once
// The robot link's transport: a non-blocking IPv4 UDP endpoint on POSIX sockets. UDP
// because the link's state messages are only worth their newest copy (a retransmitted
// old pose is worse than none) and requests carry their own acks (link_session.hpp).
// Loopback by default; on the robots, the WiFi addresses.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/link/ip_address.hpp"

namespace ferret::link {

class LinkSession;

/// Where the UAV and the miniUGV listen unless told otherwise (docs/link.md).
inline constexpr std::string_view kDefaultUavAddress = "127.0.0.1:47810";
inline constexpr std::string_view kDefaultUgvAddress = "127.0.0.1:47811";

struct UdpLinkOptions {
  std::string bind = "127.0.0.1:0";  ///< the local address:port; port 0 takes any free port
  std::string peer;                  ///< where send() goes; empty: only send_to()
  /// Received datagrams longer than this are counted (oversized()) and dropped: the
  /// largest frame is 307 bytes, and a WiFi datagram should stay under one MTU.
  std::size_t max_datagram_bytes = 1472;
};

struct ReceivedDatagram {
  std::vector<std::uint8_t> bytes;
  Ipv4Address from;
};

class UdpLink {
 public:
  /// Opens and binds the socket.
  /// @throws InputError naming the option and the address: a malformed address, or one
  ///         that cannot be bound (in use, not this machine's)
  explicit UdpLink(const UdpLinkOptions& options = {});
  ~UdpLink();
  UdpLink(UdpLink&& other) noexcept;
  UdpLink& operator=(UdpLink&& other) noexcept;
  UdpLink(const UdpLink&) = delete;
  UdpLink& operator=(const UdpLink&) = delete;

  /// The address bound (with the port the system chose for port 0).
  [[nodiscard]] const Ipv4Address& local_address() const { return local_; }
  [[nodiscard]] const std::optional<Ipv4Address>& peer() const { return peer_; }

  /// Sends to the peer. False when the datagram could not be sent (the socket's buffer
  /// is full, the network is down): the link is lossy anyway, and a robot must not stop
  /// on a WiFi glitch. The reason is in last_send_error().
  /// @throws std::logic_error when no peer was configured
  bool send(std::span<const std::uint8_t> datagram);
  bool send_to(const Ipv4Address& to, std::span<const std::uint8_t> datagram);
  /// The next datagram, waiting at most timeout_ms for one (0: only what is there).
  [[nodiscard]] std::optional<ReceivedDatagram> receive(int timeout_ms);

  [[nodiscard]] const std::string& last_send_error() const { return last_send_error_; }
  [[nodiscard]] std::uint64_t send_failures() const { return send_failures_; }
  [[nodiscard]] std::uint64_t oversized() const { return oversized_; }

 private:
  int fd_ = -1;
  Ipv4Address local_;
  std::optional<Ipv4Address> peer_;
  std::vector<std::uint8_t> buffer_;
  std::size_t max_datagram_bytes_;
  std::string last_send_error_;
  std::uint64_t send_failures_ = 0;
  std::uint64_t oversized_ = 0;
};

/// One round of a session over a socket: hands every datagram waiting on `udp` to the
/// session (waiting at most timeout_ms for the first), then sends what the session has
/// to send to the peer. Returns the datagrams received.
std::size_t exchange(UdpLink& udp, LinkSession& session, int timeout_ms);

}  // namespace ferret::link
