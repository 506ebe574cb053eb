#include "ferret/link/message_stream.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstring>
#include <thread>

#include "ferret/core/error.hpp"
#include "socket_util.hpp"

namespace ferret::link {
namespace {

using internal::from_sockaddr;
using internal::to_sockaddr;
std::string errno_text() { return internal::errno_text(errno); }

void put_u32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
std::uint32_t get_u32(const std::uint8_t* p) {
  std::uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(p[i]) << (8 * i);
  return v;
}

// Small requests and replies in lockstep: Nagle's delay would add 40 ms a round trip.
// A peer that stops in the middle of a frame is a broken peer, not a slow one: reads
// and writes give up after kStallS (MessageStream::receive waits for a frame's start
// as long as it is told).
constexpr int kStallS = 5;
void configure(int fd) {
  const int one = 1;
  (void)::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  const timeval stall{kStallS, 0};
  (void)::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &stall, sizeof stall);
  (void)::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &stall, sizeof stall);
}

}  // namespace

MessageStream MessageStream::connect(const Ipv4Address& address, double timeout_s) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  for (;;) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) throw StreamError("socket: " + errno_text());
    const sockaddr_in sa = to_sockaddr(address);
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&sa), sizeof sa) == 0) {
      configure(fd);
      return MessageStream(fd, address.to_string());
    }
    const std::string why = errno_text();
    ::close(fd);
    if (std::chrono::steady_clock::now() >= deadline)
      throw StreamError("nothing answers at " + address.to_string() + " (" + why + ")");
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

MessageStream::MessageStream(MessageStream&& o) noexcept : fd_(o.fd_), peer_(std::move(o.peer_)) {
  o.fd_ = -1;
}
MessageStream& MessageStream::operator=(MessageStream&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = o.fd_;
    peer_ = std::move(o.peer_);
    o.fd_ = -1;
  }
  return *this;
}
MessageStream::~MessageStream() {
  if (fd_ >= 0) ::close(fd_);
}

void MessageStream::send(const StreamMessage& m) {
  if (m.header.size() > kMaxHeaderBytes || m.blob.size() > kMaxBlobBytes)
    throw StreamError("message beyond the stream's limits for " + peer_);
  std::uint8_t prefix[8];
  put_u32(prefix, static_cast<std::uint32_t>(m.header.size()));
  put_u32(prefix + 4, static_cast<std::uint32_t>(m.blob.size()));
  const auto write_all = [&](const void* data, std::size_t size) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    while (size > 0) {
      const ssize_t n = ::send(fd_, p, size, MSG_NOSIGNAL);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw StreamError("connection to " + peer_ + " lost: " + errno_text());
      p += n;
      size -= static_cast<std::size_t>(n);
    }
  };
  write_all(prefix, sizeof prefix);
  write_all(m.header.data(), m.header.size());
  if (!m.blob.empty()) write_all(m.blob.data(), m.blob.size());
}

void MessageStream::read_exact(std::uint8_t* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::recv(fd_, data, size, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n == 0) throw StreamError(peer_ + " closed the connection");
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK))
      throw StreamError(peer_ + " stopped in the middle of a message");
    if (n < 0) throw StreamError("connection to " + peer_ + " lost: " + errno_text());
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

std::optional<StreamMessage> MessageStream::receive(int timeout_ms) {
  pollfd p{fd_, POLLIN, 0};
  for (;;) {
    const int r = ::poll(&p, 1, timeout_ms);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) throw StreamError("poll: " + errno_text());
    if (r == 0) return std::nullopt;
    break;
  }
  std::uint8_t prefix[8];
  read_exact(prefix, sizeof prefix);
  const std::uint32_t header_bytes = get_u32(prefix), blob_bytes = get_u32(prefix + 4);
  if (header_bytes > kMaxHeaderBytes || blob_bytes > kMaxBlobBytes)
    throw StreamError(peer_ + " sent a frame beyond the limits (header " +
                      std::to_string(header_bytes) + " B, blob " + std::to_string(blob_bytes) +
                      " B): not a ferret stream?");
  StreamMessage m;
  m.header.resize(header_bytes);
  read_exact(reinterpret_cast<std::uint8_t*>(m.header.data()), header_bytes);
  m.blob.resize(blob_bytes);
  if (blob_bytes > 0) read_exact(m.blob.data(), blob_bytes);
  return m;
}

MessageListener::MessageListener(const Ipv4Address& address, const std::string& source,
                                 const std::string& field) {
  fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw StreamError("socket: " + errno_text());
  const int one = 1;
  (void)::setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  const sockaddr_in sa = to_sockaddr(address);
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&sa), sizeof sa) != 0 ||
      ::listen(fd_, 4) != 0) {
    const std::string why = errno_text();
    ::close(fd_);
    fd_ = -1;
    throw InputError(source, field, "an address this machine can listen on",
                     address.to_string() + " (" + why + ")");
  }
  sockaddr_in bound{};
  socklen_t len = sizeof bound;
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&bound), &len);
  port_ = ntohs(bound.sin_port);
}
MessageListener::MessageListener(MessageListener&& o) noexcept : fd_(o.fd_), port_(o.port_) {
  o.fd_ = -1;
}
MessageListener& MessageListener::operator=(MessageListener&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = o.fd_;
    port_ = o.port_;
    o.fd_ = -1;
  }
  return *this;
}
MessageListener::~MessageListener() {
  if (fd_ >= 0) ::close(fd_);
}

std::optional<MessageStream> MessageListener::accept(int timeout_ms) {
  pollfd p{fd_, POLLIN, 0};
  const int r = ::poll(&p, 1, timeout_ms);
  if (r <= 0) return std::nullopt;
  sockaddr_in peer{};
  socklen_t len = sizeof peer;
  const int fd = ::accept4(fd_, reinterpret_cast<sockaddr*>(&peer), &len, SOCK_CLOEXEC);
  if (fd < 0) return std::nullopt;
  configure(fd);
  return MessageStream(fd, from_sockaddr(peer).to_string());
}

StreamMessage StreamRpcChannel::call(const std::string& request) {
  stream_.send(request);
  auto reply = stream_.receive(reply_timeout_ms_);
  if (!reply)
    throw StreamError(stream_.peer() + " did not answer within " +
                      std::to_string(reply_timeout_ms_) + " ms");
  return std::move(*reply);
}

std::vector<std::uint8_t> pack_datagrams(const std::vector<std::vector<std::uint8_t>>& datagrams) {
  std::vector<std::uint8_t> blob;
  for (const auto& d : datagrams) {
    const auto n = static_cast<std::uint32_t>(d.size());
    for (int k = 0; k < 4; ++k) blob.push_back(static_cast<std::uint8_t>(n >> (8 * k)));
    blob.insert(blob.end(), d.begin(), d.end());
  }
  return blob;
}

std::vector<std::vector<std::uint8_t>> unpack_datagrams(const std::vector<std::uint8_t>& blob,
                                                        std::size_t max_datagram_bytes) {
  std::vector<std::vector<std::uint8_t>> out;
  std::size_t at = 0;
  while (at < blob.size()) {
    if (blob.size() - at < 4) throw StreamError("relayed datagrams: a length cut short");
    std::size_t n = 0;
    for (int k = 0; k < 4; ++k)
      n |= static_cast<std::size_t>(blob[at + static_cast<std::size_t>(k)]) << (8 * k);
    at += 4;
    if (n > max_datagram_bytes || n > blob.size() - at)
      throw StreamError("relayed datagrams: a datagram of " + std::to_string(n) + " bytes where " +
                        std::to_string(std::min(max_datagram_bytes, blob.size() - at)) +
                        " remain allowed");
    out.emplace_back(blob.begin() + static_cast<std::ptrdiff_t>(at),
                     blob.begin() + static_cast<std::ptrdiff_t>(at + n));
    at += n;
  }
  return out;
}

}  // namespace ferret::link
