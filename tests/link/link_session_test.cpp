#include "ferret/link/link_session.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <variant>
#include <vector>

#include "ferret/core/clock.hpp"
#include "ferret/link/codec.hpp"
#include "ferret/link/lossy_channel.hpp"

namespace ferret::link {
namespace {

using Verdict = StateStreamFilter::Verdict;

UgvTelemetry telemetry_at(double t_s, double x_m = 0.0) {
  UgvTelemetry t;
  t.t_s = t_s;
  t.x_m = x_m;
  return t;
}
UavRequest request_of(UavRequest::Kind kind) {
  UavRequest r;
  r.kind = kind;
  return r;
}

TEST(LinkStateStreamFilter, AcceptsOnlyNewerAndCountsTheRest) {
  StateStreamFilter f(32);
  EXPECT_FALSE(f.newest().has_value());
  EXPECT_EQ(f.accept(10), Verdict::kAccepted);  // the first frame, whatever its number
  EXPECT_EQ(f.accept(10), Verdict::kDuplicate);
  EXPECT_EQ(f.accept(12), Verdict::kAccepted);  // 11 lost: newer is enough
  EXPECT_EQ(f.accept(11), Verdict::kStale);     // 11 came late
  EXPECT_EQ(f.accept(12), Verdict::kDuplicate);
  EXPECT_EQ(*f.newest(), 12u);
}

TEST(LinkStateStreamFilter, WrapsAroundAndTakesAFarJumpBackAsARestart) {
  StateStreamFilter f(32);
  EXPECT_EQ(f.accept(0xFFFFFFFEu), Verdict::kAccepted);
  EXPECT_EQ(f.accept(1), Verdict::kAccepted);  // past 2^32: still newer
  EXPECT_EQ(f.accept(0xFFFFFFFFu), Verdict::kStale);
  StateStreamFilter g(32);
  EXPECT_EQ(g.accept(1000), Verdict::kAccepted);
  EXPECT_EQ(g.accept(1000 - 32), Verdict::kStale);  // within the window: late
  EXPECT_EQ(g.accept(1), Verdict::kRestarted);      // far behind: started over
  EXPECT_EQ(g.accept(2), Verdict::kAccepted);
  EXPECT_EQ(g.accept(999), Verdict::kAccepted);  // and the old numbers are newer now
}

TEST(LinkRequestSender, ResendsEveryPeriodUntilAckedThenSendsTheNext) {
  SimClock clock;
  RequestSender s(clock, {.resend_period_s = 0.2, .max_attempts = 50, .first_request_id = 1});
  UavRequest recall;
  recall.kind = UavRequest::Kind::kRecall;
  EXPECT_EQ(s.submit(recall), 1u);
  EXPECT_EQ(s.submit(UavRequest{}), 2u);
  EXPECT_FALSE(s.in_flight().has_value());  // queued, not yet sent
  auto due = s.due();
  ASSERT_TRUE(due.has_value());
  EXPECT_EQ(due->request_id, 1u);
  EXPECT_EQ(due->kind, UavRequest::Kind::kRecall);
  EXPECT_FALSE(s.due().has_value());  // sent just now
  clock.set(0.1);
  EXPECT_FALSE(s.due().has_value());
  clock.set(0.2);
  ASSERT_TRUE(s.due().has_value());  // one period without an ack
  EXPECT_EQ(s.resends(), 1u);
  EXPECT_FALSE(s.acknowledge(2));  // not the one in flight
  EXPECT_TRUE(s.acknowledge(1));
  EXPECT_FALSE(s.acknowledge(1));  // a second copy of the ack
  due = s.due();
  ASSERT_TRUE(due.has_value());
  EXPECT_EQ(due->request_id, 2u);
  const auto results = s.take_results();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].request.request_id, 1u);
  EXPECT_EQ(results[0].status, RequestResult::Status::kAcknowledged);
  EXPECT_EQ(results[0].attempts, 2);
}

TEST(LinkRequestSender, GivesUpAfterItsAttemptsAndReportsIt) {
  SimClock clock;
  RequestSender s(clock, {.resend_period_s = 0.5, .max_attempts = 3, .first_request_id = 100});
  s.submit(UavRequest{});
  s.submit(UavRequest{});
  int sends_of_first = 0;
  int k = 0;
  std::optional<UavRequest> second;
  while (!second) {
    clock.set(0.1 * k++);
    if (auto d = s.due()) {
      if (d->request_id == 100)
        ++sends_of_first;
      else
        second = d;
    }
    ASSERT_LT(k, 100);
  }
  EXPECT_EQ(sends_of_first, 3);
  EXPECT_EQ(second->request_id, 101u);
  // Three sends at 0, 0.5, 1.0 s, and one more period to wait for the last ack.
  EXPECT_NEAR(clock.now_s(), 1.5, 1e-9);
  EXPECT_EQ(s.given_up(), 1u);
  const auto results = s.take_results();
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].status, RequestResult::Status::kGivenUp);
  EXPECT_EQ(results[0].attempts, 3);
  EXPECT_FALSE(s.acknowledge(100));  // too late: it was given up
}

TEST(LinkRequestSender, RefusesOptionsThatCannotWork) {
  SimClock clock;
  EXPECT_THROW(RequestSender(clock, {.resend_period_s = 0.0}), std::invalid_argument);
  EXPECT_THROW(RequestSender(clock, {.resend_period_s = 0.2, .max_attempts = 0}),
               std::invalid_argument);
}

TEST(LinkRequestReceiver, DeliversEachIdOnceAndNeverOneBelowTheLast) {
  RequestReceiver r;
  UavRequest q;
  q.request_id = 1;
  EXPECT_TRUE(r.accept(q));
  EXPECT_FALSE(r.accept(q));  // a resend
  q.request_id = 3;           // 2 was given up by the UAV: the gap is allowed
  EXPECT_TRUE(r.accept(q));
  q.request_id = 2;  // a copy of 2 arriving after 3: never out of order
  EXPECT_FALSE(r.accept(q));
  EXPECT_EQ(r.last_delivered(), 3u);
}

// ------------------------------------------------------------------ two sessions

// The UAV and the miniUGV on one SimClock, a LossyChannel each way, stepping at the
// miniUGV's 20 Hz control rate.
struct TwoRobots {
  SimClock clock;
  UavLinkSession uav;
  UgvLinkSession ugv;
  LossyChannel to_ugv, to_uav;
  static constexpr double kDt = 0.05;
  int step_count = 0;

  TwoRobots(const LossyChannelOptions& down, const LossyChannelOptions& up,
            UavLinkOptions uav_options = {})
      : uav(clock, uav_options), ugv(clock), to_ugv(down), to_uav(up) {}

  void step(const std::optional<UgvTelemetry>& telemetry = std::nullopt) {
    clock.set(++step_count * kDt);
    if (telemetry) ugv.send_telemetry(*telemetry);
    to_ugv.send(uav.take_outgoing());
    to_uav.send(ugv.take_outgoing());
    for (const auto& d : to_ugv.deliver()) ugv.receive(d);
    for (const auto& d : to_uav.deliver()) uav.receive(d);
  }
};

LossyChannelOptions bad_network(std::uint64_t seed) {
  return {.drop_fraction = 0.2,
          .duplicate_fraction = 0.15,
          .reorder_fraction = 0.25,
          .max_reorder_delay = 4,
          .corrupt_fraction = 0.05,
          .seed = seed};
}

TEST(LinkSessions, OverABadNetworkRequestsArriveOnceAndInOrderAndTelemetryNeverGoesBack) {
  TwoRobots robots(bad_network(11), bad_network(12));
  std::vector<std::uint32_t> submitted;
  std::vector<std::uint32_t> delivered;
  std::vector<double> telemetry_times;
  Rng rng(5);
  for (int k = 0; k < 20 * 600; ++k) {  // 10 simulated minutes
    // Bursts of requests at random moments: several queue up behind the one in flight.
    if (rng.bernoulli(0.01)) {
      const auto n = rng.uniform_int(1, 4);
      for (std::int64_t i = 0; i < n; ++i) {
        UavRequest r;
        r.kind = static_cast<UavRequest::Kind>(rng.uniform_int(1, 5));
        r.reason = "burst";
        submitted.push_back(robots.uav.request(r));
      }
    }
    UgvTelemetry t;
    t.t_s = robots.clock.now_s() + TwoRobots::kDt;
    robots.step(t);
    while (auto r = robots.ugv.next_request()) delivered.push_back(r->request_id);
    if (const auto& latest = robots.uav.telemetry()) {
      if (telemetry_times.empty() || telemetry_times.back() != latest->t_s)
        telemetry_times.push_back(latest->t_s);
    }
  }
  for (int k = 0; k < 20 * 30 && robots.uav.requests().pending() > 0; ++k) robots.step();
  while (auto r = robots.ugv.next_request()) delivered.push_back(r->request_id);

  ASSERT_GT(submitted.size(), 100u);
  EXPECT_EQ(robots.uav.requests().pending(), 0u);
  EXPECT_EQ(robots.uav.requests().given_up(), 0u);  // 50 tries never all fail at 20 % loss
  EXPECT_EQ(delivered, submitted);                  // each once, in order, none lost
  std::size_t acknowledged = 0;
  for (const auto& r : robots.uav.take_request_results())
    acknowledged += r.status == RequestResult::Status::kAcknowledged;
  EXPECT_EQ(acknowledged, submitted.size());

  ASSERT_GT(telemetry_times.size(), 5000u);
  for (std::size_t i = 1; i < telemetry_times.size(); ++i)
    ASSERT_GT(telemetry_times[i], telemetry_times[i - 1]) << "telemetry went back at " << i;

  // The network did misbehave, and both sides saw it.
  const auto& at_uav = robots.uav.counters();
  const auto& at_ugv = robots.ugv.counters();
  EXPECT_GT(at_uav.stale, 100u) << at_uav.summary();
  EXPECT_GT(at_uav.duplicates, 100u) << at_uav.summary();
  EXPECT_GT(at_uav.corrupted, 100u) << at_uav.summary();
  EXPECT_GT(at_ugv.duplicates, 10u) << at_ugv.summary();  // resent requests, acked again
  EXPECT_GT(at_ugv.corrupted, 10u) << at_ugv.summary();
  EXPECT_GT(at_uav.resent, 10u) << at_uav.summary();
  EXPECT_EQ(at_uav.restarts + at_ugv.restarts, 0u);
  EXPECT_EQ(at_uav.unexpected + at_ugv.unexpected, 0u);
  EXPECT_EQ(at_uav.received, robots.to_uav.counters().delivered);
}

TEST(LinkSessions, EachSideHoldsWhenThePeerFallsSilent) {
  LossyChannelOptions perfect;
  LossyChannelOptions dead;
  dead.drop_fraction = 1.0;
  TwoRobots robots(perfect, perfect);
  EXPECT_TRUE(robots.uav.peer_silent());  // nobody heard yet
  EXPECT_TRUE(robots.ugv.peer_silent());
  for (int k = 0; k < 10; ++k) robots.step(telemetry_at(robots.clock.now_s()));
  EXPECT_FALSE(robots.uav.peer_silent());
  EXPECT_FALSE(robots.ugv.peer_silent());

  // Cut both directions: the winch holds after 0.3 s, the miniUGV after 0.5 s.
  robots.to_ugv = LossyChannel(dead);
  robots.to_uav = LossyChannel(dead);
  const double cut_at = robots.clock.now_s();
  double uav_held_at = -1, ugv_held_at = -1;
  for (int k = 0; k < 40; ++k) {
    robots.step(telemetry_at(robots.clock.now_s()));
    if (uav_held_at < 0 && robots.uav.peer_silent()) uav_held_at = robots.clock.now_s();
    if (ugv_held_at < 0 && robots.ugv.peer_silent()) ugv_held_at = robots.clock.now_s();
  }
  // The last telemetry arrived at cut_at; the watchdogs expire within a step of their
  // timeouts after the last frame heard.
  EXPECT_GT(uav_held_at - cut_at, 0.3 - 1e-9);
  EXPECT_LE(uav_held_at - cut_at, 0.3 + TwoRobots::kDt + 1e-9);
  // Heartbeats come every 0.05 s: the miniUGV last heard the UAV up to 0.05 s before the cut.
  ASSERT_TRUE(robots.ugv.heartbeat().has_value());
  const double last_heartbeat_s = robots.ugv.heartbeat()->t_s;
  EXPECT_LE(last_heartbeat_s, cut_at);
  EXPECT_GT(ugv_held_at - last_heartbeat_s, 0.5 - 1e-9);
  EXPECT_LE(ugv_held_at - last_heartbeat_s, 0.5 + TwoRobots::kDt + 1e-9);
}

TEST(LinkSessions, ARestartedMiniUgvIsHeardAgainAtOnce) {
  LossyChannelOptions perfect;
  TwoRobots robots(perfect, perfect);
  for (int k = 0; k < 100; ++k) robots.step(telemetry_at(robots.clock.now_s()));
  // A new miniUGV process: its telemetry numbers start over at 1.
  SimClock its_clock;
  UgvLinkSession restarted(its_clock);
  restarted.send_telemetry(telemetry_at(0.25));
  for (const auto& d : restarted.take_outgoing()) robots.uav.receive(d);
  ASSERT_TRUE(robots.uav.telemetry().has_value());
  EXPECT_EQ(robots.uav.telemetry()->t_s, 0.25);
  EXPECT_EQ(robots.uav.counters().restarts, 1u);
}

TEST(LinkSessions, ARestartedUavsRequestsAreDeliveredAgain) {
  LossyChannelOptions perfect;
  TwoRobots robots(perfect, perfect);
  for (int i = 0; i < 3; ++i) robots.uav.request(request_of(UavRequest::Kind::kRecall));
  for (int k = 0; k < 20 * 60; ++k) robots.step();  // a minute: heartbeats number past the window
  int delivered = 0;
  while (robots.ugv.next_request()) ++delivered;
  ASSERT_EQ(delivered, 3);
  // A new UAV process: heartbeats and request ids start over at 1.
  UavLinkSession restarted(robots.clock);
  restarted.request(request_of(UavRequest::Kind::kAbort));
  for (const auto& d : restarted.take_outgoing()) robots.ugv.receive(d);
  const auto request = robots.ugv.next_request();
  ASSERT_TRUE(request.has_value());
  EXPECT_EQ(request->request_id, 1u);
  EXPECT_EQ(request->kind, UavRequest::Kind::kAbort);
}

TEST(LinkSessions, OwnFramesLoopedBackAndGarbageAreCountedNotActedOn) {
  SimClock clock;
  UavLinkSession uav(clock);
  uav.request(request_of(UavRequest::Kind::kAbort));
  for (const auto& d : uav.take_outgoing()) uav.receive(d);  // a heartbeat and a request
  uav.receive(std::vector<std::uint8_t>{'F', 'L', 3});
  uav.receive(std::vector<std::uint8_t>(40, 0xFF));
  const auto& c = uav.counters();
  EXPECT_EQ(c.received, 4u);
  EXPECT_EQ(c.unexpected, 2u);
  EXPECT_EQ(c.corrupted, 2u);
  EXPECT_EQ(c.rejected[static_cast<std::size_t>(Rejection::Reason::kTruncated)], 1u);
  EXPECT_EQ(c.rejected[static_cast<std::size_t>(Rejection::Reason::kBadMagic)], 1u);
  EXPECT_EQ(c.accepted, 0u);
  EXPECT_TRUE(uav.peer_silent());
  EXPECT_FALSE(uav.telemetry().has_value());
  EXPECT_NE(c.summary().find("corrupted 2 (truncated 1, bad magic 1)"), std::string::npos)
      << c.summary();
}

TEST(LinkSessions, TheUavHeartbeatsAtItsPeriodWithNothingElseToSay) {
  SimClock clock;
  UavLinkSession uav(clock);  // 0.05 s
  int heartbeats = 0;
  for (int k = 0; k <= 100; ++k) {  // 1 s at 100 Hz
    clock.set(k * 0.01);
    heartbeats += static_cast<int>(uav.take_outgoing().size());
  }
  EXPECT_EQ(heartbeats, 21);  // at 0, 0.05, ..., 1.0 s
  UavLinkOptions no_period;
  no_period.heartbeat_period_s = 0;
  EXPECT_THROW(UavLinkSession(clock, no_period), std::invalid_argument);
  EXPECT_THROW(UgvLinkSession(clock, {.uav_timeout_s = -1}), std::invalid_argument);
}

TEST(LinkSessions, TheHeartbeatEchoesTheNewestTelemetryTheUavAccepted) {
  SimClock clock;
  UavLinkSession uav(clock);
  const auto heartbeat_echo = [&] {
    for (const auto& d : uav.take_outgoing()) {
      const DecodeResult r = decode(d);
      if (r.ok() && std::holds_alternative<Heartbeat>(r.frame().message))
        return std::get<Heartbeat>(r.frame().message).ugv_telemetry_t_s;
    }
    return -1.0;
  };
  EXPECT_EQ(heartbeat_echo(), 0.0);  // none heard yet
  SimClock ugv_clock;
  UgvLinkSession ugv(ugv_clock);
  const auto send = [&](double t_s) {
    ugv_clock.set(t_s);
    ugv.send_telemetry(telemetry_at(t_s));
    return ugv.take_outgoing();
  };
  const auto first = send(2.5), second = send(2.55);
  for (const auto& d : second) uav.receive(d);
  for (const auto& d : first) uav.receive(d);  // late: dropped as stale, not echoed
  clock.set(1.0);
  EXPECT_EQ(heartbeat_echo(), 2.55);
}

}  // namespace
}  // namespace ferret::link
