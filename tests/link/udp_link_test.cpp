#include "ferret/link/udp_link.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ferret/core/clock.hpp"
#include "ferret/core/error.hpp"
#include "ferret/link/codec.hpp"
#include "ferret/link/link_session.hpp"
#include "ferret/link/message_stream.hpp"

namespace ferret::link {
namespace {

// Generous: a loopback datagram arrives in microseconds; the wait only bounds a
// failure. Nothing here asserts how long anything took.
constexpr int kWaitMs = 2000;

UdpLinkOptions at(const std::string& bind, const std::string& peer = {}) {
  UdpLinkOptions o;
  o.bind = bind;
  o.peer = peer;
  return o;
}

TEST(LinkIpv4Address, ParsesDottedQuadsAndLocalhost) {
  const Ipv4Address a = parse_ipv4_address("192.168.1.20:47811", "--peer");
  EXPECT_EQ(a.ip, (std::array<std::uint8_t, 4>{192, 168, 1, 20}));
  EXPECT_EQ(a.port, 47811);
  EXPECT_EQ(a.to_string(), "192.168.1.20:47811");
  EXPECT_EQ(parse_ipv4_address("localhost:9", "--peer").to_string(), "127.0.0.1:9");
  EXPECT_EQ(parse_ipv4_address("0.0.0.0:0", "--bind", {}, /*allow_any_port=*/true).port, 0);
}

TEST(LinkIpv4Address, BadTextIsInputErrorNamingTheAddress) {
  for (const char* bad :
       {"127.0.0.1:70000", "nonsense", "127.0.0.1", "127.0.0.1:", "127.1:80", "1.2.3.4.5:80",
        "256.0.0.1:80", "127.0.0.1:80x", "127.0.0.1:-1", ":80", "127.0.0.1:0", "host.example:80"}) {
    try {
      (void)parse_ipv4_address(bad, "--peer");
      ADD_FAILURE() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), "--peer");
      EXPECT_NE(std::string(e.what()).find(std::string("(got ") + bad + ")"), std::string::npos)
          << e.what();
    }
  }
  try {
    (void)parse_ipv4_address("127.0.0.1:70000", "udp link", "peer");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(
        e.what(),
        "udp link: peer: expected a port in 1..65535 after the address (got 127.0.0.1:70000)");
  }
}

TEST(UdpLink, BadOptionsAndABusyPortAreInputErrors) {
  EXPECT_THROW(UdpLink(at("nonsense")), InputError);
  EXPECT_THROW(UdpLink(at("127.0.0.1:0", "127.0.0.1:70000")), InputError);
  const UdpLink first;
  try {
    const UdpLink second(at(first.local_address().to_string()));
    FAIL() << "bound the same port twice";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "bind");
    EXPECT_NE(std::string(e.what()).find(first.local_address().to_string()), std::string::npos)
        << e.what();
  }
}

TEST(UdpLink, TwoEndpointsOnLoopbackExchangeFrames) {
  UdpLink ugv;  // any free port: tests run side by side
  UdpLink uav(at("127.0.0.1:0", ugv.local_address().to_string()));
  EXPECT_NE(ugv.local_address().port, 0);
  EXPECT_FALSE(ugv.receive(0).has_value());  // nothing there: returns at once

  ASSERT_TRUE(uav.send(encode(1, Heartbeat{2.5})));
  const auto got = ugv.receive(kWaitMs);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->from, uav.local_address());
  const DecodeResult r = decode(got->bytes);
  ASSERT_TRUE(r.ok()) << r.rejection().message();
  EXPECT_EQ(std::get<Heartbeat>(r.frame().message).t_s, 2.5);

  // And back, to the address the datagram came from.
  ASSERT_TRUE(ugv.send_to(got->from, encode(1, Ack{9})));
  const auto back = uav.receive(kWaitMs);
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(std::get<Ack>(decode(back->bytes).frame().message).request_id, 9u);

  EXPECT_THROW(ugv.send(encode(2, Ack{1})), std::logic_error);  // it has no peer
}

TEST(UdpLink, DropsDatagramsLongerThanItsLimit) {
  UdpLinkOptions small = at("127.0.0.1:0");
  small.max_datagram_bytes = 64;
  UdpLink ugv(small);
  UdpLink uav(at("127.0.0.1:0", ugv.local_address().to_string()));
  ASSERT_TRUE(uav.send(std::vector<std::uint8_t>(65, 1)));
  ASSERT_TRUE(uav.send(std::vector<std::uint8_t>(64, 2)));
  const auto got = ugv.receive(kWaitMs);
  ASSERT_TRUE(got.has_value());
  EXPECT_EQ(got->bytes, std::vector<std::uint8_t>(64, 2));
  EXPECT_EQ(ugv.oversized(), 1u);
}

TEST(UdpLink, TwoSessionsTalkOverLoopback) {
  SimClock clock;
  UdpLink ugv_socket;
  UdpLink uav_socket(at("127.0.0.1:0", ugv_socket.local_address().to_string()));
  UdpLink ugv_to_uav(at("127.0.0.1:0", uav_socket.local_address().to_string()));
  UavLinkSession uav(clock);
  UgvLinkSession ugv(clock);
  UavRequest start;
  start.kind = UavRequest::Kind::kStartSearch;
  start.entry_x_m = 12.5;
  const std::uint32_t id = uav.request(start);

  // The UAV sends a heartbeat and the request; the miniUGV answers with an ack and its
  // telemetry (from a socket of its own, so both ends have a peer).
  exchange(uav_socket, uav, 0);
  for (int i = 0; i < 2; ++i) {
    const auto d = ugv_socket.receive(kWaitMs);
    ASSERT_TRUE(d.has_value()) << i;
    ugv.receive(d->bytes);
  }
  const auto delivered = ugv.next_request();
  ASSERT_TRUE(delivered.has_value()) << ugv.counters().summary();
  EXPECT_EQ(delivered->request_id, id);
  EXPECT_EQ(delivered->entry_x_m, 12.5);
  EXPECT_FALSE(ugv.peer_silent());

  UgvTelemetry telemetry;
  telemetry.t_s = 1.0;
  telemetry.x_m = 0.5;
  ugv.send_telemetry(telemetry);
  exchange(ugv_to_uav, ugv, 0);  // the ack and the telemetry
  for (int i = 0; i < 2 && (!uav.telemetry() || uav.requests().pending() > 0); ++i)
    ASSERT_GT(exchange(uav_socket, uav, kWaitMs), 0u) << uav.counters().summary();
  ASSERT_TRUE(uav.telemetry().has_value());
  EXPECT_EQ(uav.requests().pending(), 0u);  // acknowledged
  EXPECT_EQ(uav.telemetry()->x_m, 0.5);
  EXPECT_EQ(uav.counters().corrupted, 0u);
}

}  // namespace
}  // namespace ferret::link

namespace ferret::link {
namespace {

// The robot link's datagrams relayed in a stream message's blob (sim-world's network).
TEST(RelayedDatagrams, PackAndUnpackAreInverseAndABrokenBlobIsRefused) {
  const std::vector<std::vector<std::uint8_t>> datagrams = {
      {1, 2, 3}, {}, std::vector<std::uint8_t>(300, 7)};
  const std::vector<std::uint8_t> blob = pack_datagrams(datagrams);
  ASSERT_EQ(blob.size(), 3u * 4u + 3u + 300u);
  EXPECT_EQ(blob[0], 3);  // little-endian length first
  EXPECT_EQ(blob[1], 0);
  EXPECT_EQ(unpack_datagrams(blob), datagrams);
  EXPECT_TRUE(unpack_datagrams({}).empty());
  std::vector<std::uint8_t> cut(blob.begin(), blob.end() - 1);  // the last datagram one byte short
  EXPECT_THROW((void)unpack_datagrams(cut), StreamError);
  EXPECT_THROW((void)unpack_datagrams({5, 0}), StreamError);     // a length cut short
  EXPECT_THROW((void)unpack_datagrams(blob, 100), StreamError);  // 300 bytes over a limit of 100
  const std::vector<std::uint8_t> huge = {0xff, 0xff, 0xff, 0xff, 1};
  EXPECT_THROW((void)unpack_datagrams(huge), StreamError);  // 4 GiB claimed, 1 byte there
}

}  // namespace
}  // namespace ferret::link
