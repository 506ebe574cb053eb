#include "ferret/link/udp_link.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "ferret/core/error.hpp"
#include "ferret/link/link_session.hpp"
#include "socket_util.hpp"

namespace ferret::link {
using internal::errno_text;
using internal::from_sockaddr;
using internal::to_sockaddr;

UdpLink::UdpLink(const UdpLinkOptions& options)
    : local_(parse_ipv4_address(options.bind, "udp link", "bind", /*allow_any_port=*/true)),
      buffer_(options.max_datagram_bytes + 1),  // one more: a datagram that fills it is too long
      max_datagram_bytes_(options.max_datagram_bytes) {
  if (!options.peer.empty()) peer_ = parse_ipv4_address(options.peer, "udp link", "peer");
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0)
    throw std::runtime_error("udp link: a socket for " + local_.to_string() + ": " +
                             errno_text(errno));
  const sockaddr_in addr = to_sockaddr(local_);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0) {
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    throw InputError("udp link", "bind", "a free address of this machine",
                     options.bind + ": " + errno_text(err));
  }
  sockaddr_in bound{};
  socklen_t len = sizeof bound;
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&bound), &len);
  local_ = from_sockaddr(bound);
}

UdpLink::~UdpLink() {
  if (fd_ >= 0) ::close(fd_);
}

UdpLink::UdpLink(UdpLink&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      local_(other.local_),
      peer_(other.peer_),
      buffer_(std::move(other.buffer_)),
      max_datagram_bytes_(other.max_datagram_bytes_),
      last_send_error_(std::move(other.last_send_error_)),
      send_failures_(other.send_failures_),
      oversized_(other.oversized_) {}

UdpLink& UdpLink::operator=(UdpLink&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
    local_ = other.local_;
    peer_ = other.peer_;
    buffer_ = std::move(other.buffer_);
    max_datagram_bytes_ = other.max_datagram_bytes_;
    last_send_error_ = std::move(other.last_send_error_);
    send_failures_ = other.send_failures_;
    oversized_ = other.oversized_;
  }
  return *this;
}

bool UdpLink::send(std::span<const std::uint8_t> datagram) {
  if (!peer_)
    throw std::logic_error("udp link " + local_.to_string() +
                           ": send() without a peer: use send_to()");
  return send_to(*peer_, datagram);
}

bool UdpLink::send_to(const Ipv4Address& to, std::span<const std::uint8_t> datagram) {
  const sockaddr_in addr = to_sockaddr(to);
  const ssize_t n = ::sendto(fd_, datagram.data(), datagram.size(), MSG_NOSIGNAL,
                             reinterpret_cast<const sockaddr*>(&addr), sizeof addr);
  if (n == static_cast<ssize_t>(datagram.size())) return true;
  ++send_failures_;
  last_send_error_ =
      "send to " + to.to_string() + ": " + (n < 0 ? errno_text(errno) : "short write");
  return false;
}

std::optional<ReceivedDatagram> UdpLink::receive(int timeout_ms) {
  pollfd p{fd_, POLLIN, 0};
  for (;;) {
    const int ready = ::poll(&p, 1, std::max(timeout_ms, 0));
    if (ready < 0 && errno == EINTR) continue;  // a signal is not a datagram: wait again
    if (ready <= 0) return std::nullopt;
    sockaddr_in from{};
    socklen_t len = sizeof from;
    const ssize_t n = ::recvfrom(fd_, buffer_.data(), buffer_.size(), MSG_DONTWAIT,
                                 reinterpret_cast<sockaddr*>(&from), &len);
    if (n < 0) {
      // EAGAIN: another reader took it; anything else (a queued ICMP error) is not a
      // datagram either. Look once more without waiting.
      timeout_ms = 0;
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR || errno == ECONNREFUSED)
        continue;
      return std::nullopt;
    }
    if (static_cast<std::size_t>(n) > max_datagram_bytes_) {
      ++oversized_;
      timeout_ms = 0;
      continue;
    }
    return ReceivedDatagram{{buffer_.begin(), buffer_.begin() + n}, from_sockaddr(from)};
  }
}

std::size_t exchange(UdpLink& udp, LinkSession& session, int timeout_ms) {
  std::size_t received = 0;
  while (auto d = udp.receive(received == 0 ? timeout_ms : 0)) {
    session.receive(d->bytes);
    ++received;
  }
  for (const auto& datagram : session.take_outgoing()) udp.send(datagram);
  return received;
}

}  // namespace ferret::link
