#pragma once
// POSIX socket helpers shared by the UDP link and the TCP message streams (internal).

#include <netinet/in.h>

#include <cstring>
#include <string>

#include "ferret/link/ip_address.hpp"

namespace ferret::link::internal {

inline sockaddr_in to_sockaddr(const Ipv4Address& a) {
  sockaddr_in s{};
  s.sin_family = AF_INET;
  s.sin_port = htons(a.port);
  std::memcpy(&s.sin_addr.s_addr, a.ip.data(), 4);  // the bytes in network order
  return s;
}

inline Ipv4Address from_sockaddr(const sockaddr_in& s) {
  Ipv4Address a;
  std::memcpy(a.ip.data(), &s.sin_addr.s_addr, 4);
  a.port = ntohs(s.sin_port);
  return a;
}

inline std::string errno_text(int err) { return std::strerror(err); }

}  // namespace ferret::link::internal
