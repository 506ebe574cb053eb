#pragma once
// An IPv4 address and port, as the robot link (UDP) and the robot processes' message
// streams (TCP) take them from configuration.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace ferret::link {

struct Ipv4Address {
  std::array<std::uint8_t, 4> ip{127, 0, 0, 1};
  std::uint16_t port = 0;
  /// "127.0.0.1:47810".
  [[nodiscard]] std::string to_string() const;
  bool operator==(const Ipv4Address&) const = default;
};

/// Parses "a.b.c.d:port" (dotted decimal) or "localhost:port". A port of 0 (any free
/// port) is allowed only where `allow_any_port` says so (binding or listening, not sending or
/// connecting).
/// @throws InputError(source, field, "an IPv4 address:port ...", text)
[[nodiscard]] Ipv4Address parse_ipv4_address(std::string_view text, const std::string& source,
                                             const std::string& field = {},
                                             bool allow_any_port = false);

}  // namespace ferret::link
