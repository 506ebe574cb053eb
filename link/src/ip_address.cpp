#include "ferret/link/ip_address.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <netinet/in.h>

#include <charconv>
#include <cstring>

#include "ferret/core/error.hpp"

namespace ferret::link {
namespace {
constexpr std::string_view kAddressForm = "an IPv4 address:port such as 127.0.0.1:47810";
}  // namespace

std::string Ipv4Address::to_string() const {
  return fmt::format("{}.{}.{}.{}:{}", ip[0], ip[1], ip[2], ip[3], port);
}

Ipv4Address parse_ipv4_address(std::string_view text, const std::string& source,
                               const std::string& field, bool allow_any_port) {
  const auto bad = [&](std::string_view expected) {
    return InputError(source, field, std::string(expected), std::string(text));
  };
  const std::size_t colon = text.rfind(':');
  if (colon == std::string_view::npos) throw bad(kAddressForm);
  const std::string host(text.substr(0, colon));
  const std::string_view port_text = text.substr(colon + 1);
  Ipv4Address a;
  if (host == "localhost") {
    a.ip = {127, 0, 0, 1};
  } else {
    in_addr addr{};
    // inet_pton takes only the four dotted decimals: no "127.1", no octal, no names.
    if (inet_pton(AF_INET, host.c_str(), &addr) != 1) throw bad(kAddressForm);
    std::memcpy(a.ip.data(), &addr.s_addr, 4);
  }
  const std::uint32_t lowest = allow_any_port ? 0 : 1;
  const std::string port_range = fmt::format("a port in {}..65535 after the address", lowest);
  std::uint32_t port = 0;
  const auto [end, ec] =
      std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (port_text.empty() || ec != std::errc() || end != port_text.data() + port_text.size() ||
      port > 65535 || port < lowest)
    throw bad(port_range);
  a.port = static_cast<std::uint16_t>(port);
  return a;
}

}  // namespace ferret::link
