#pragma once
// What the link means over a network that drops, duplicates, reorders and damages
// datagrams (docs/link.md, "Semantics"). Independent of sockets: a session takes the
// datagrams that arrived and hands back the ones to send, so the tests drive two
// sessions through a LossyChannel on a SimClock, and the robots through a UdpLink.
//
// - State streams (telemetry, heartbeat): only the newest counts. A frame is accepted
//   only if its sequence number is newer than the last accepted on its stream;
//   duplicates and late (reordered) frames are dropped and counted.
// - Requests (UAV -> miniUGV): reliable and in order. The UAV keeps one request in
//   flight, resends it until it is acknowledged or gives up after a number of tries;
//   the miniUGV acks every copy and delivers each request id once, and never one
//   below an id it delivered.

#include <array>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "ferret/core/clock.hpp"
#include "ferret/link/codec.hpp"
#include "ferret/link/messages.hpp"
#include "ferret/link/watchdog.hpp"

namespace ferret::link {

/// One datagram's bytes.
using Datagram = std::vector<std::uint8_t>;

/// What a session saw, for logs.
struct LinkCounters {
  std::uint64_t received = 0;   ///< datagrams handed to receive()
  std::uint64_t accepted = 0;   ///< frames acted on: newer state, new requests, the awaited ack
  std::uint64_t corrupted = 0;  ///< datagrams decode() refused (by reason in `rejected`)
  std::uint64_t duplicates =
      0;  ///< a state frame's sequence again; a request delivered before; an ack not awaited
  std::uint64_t stale = 0;     ///< state frames behind the newest accepted (reordered or late)
  std::uint64_t restarts = 0;  ///< the peer's sequence started over (a restarted process)
  std::uint64_t unexpected =
      0;                     ///< valid frames of a type this side sends, not receives (looped back)
  std::uint64_t sent = 0;    ///< datagrams handed out to send
  std::uint64_t resent = 0;  ///< of those, requests sent again
  std::uint64_t given_up = 0;                                     ///< requests never acknowledged
  std::array<std::uint64_t, Rejection::kReasonCount> rejected{};  ///< by Rejection::Reason

  /// One line: "received 120 accepted 100 corrupted 3 (crc mismatch 3) ...".
  [[nodiscard]] std::string summary() const;
};

/// Sequence numbers for a sender: one counter a stream (message type), from 1.
class FrameNumbering {
 public:
  [[nodiscard]] std::uint32_t next(MessageType type) {
    return ++last_[static_cast<std::size_t>(type) - 1];
  }

 private:
  std::array<std::uint32_t, 4> last_{};
};

/// The receiver's side of one state stream: is a frame newer than the newest accepted?
/// Sequence numbers compare modulo 2^32 (RFC 1982), so wrapping is not going back.
class StateStreamFilter {
 public:
  enum class Verdict {
    kAccepted,   ///< newer: use it
    kDuplicate,  ///< the sequence number of the newest accepted again
    kStale,      ///< older, within reorder_window of the newest: late, dropped
    kRestarted,  ///< older by more than reorder_window: the sender started over; use it
  };
  /// @param reorder_window  how far behind the newest a frame may be and still be a late
  ///        frame of the same sender rather than the first of a restarted one
  explicit StateStreamFilter(std::uint32_t reorder_window) : reorder_window_(reorder_window) {}
  Verdict accept(std::uint32_t sequence);
  void reset() { has_newest_ = false; }
  [[nodiscard]] std::optional<std::uint32_t> newest() const;

 private:
  std::uint32_t reorder_window_;
  bool has_newest_ = false;
  std::uint32_t newest_ = 0;
};

/// How a request ended, for the UAV's mission to act on.
struct RequestResult {
  enum class Status { kAcknowledged, kGivenUp };
  UavRequest request;
  Status status = Status::kAcknowledged;
  int attempts = 0;  ///< times it was sent
};

struct RequestSenderOptions {
  /// The request in flight is sent again this long after its last send while no ack
  /// came: a few round trips of a WiFi link, and requests are rare.
  double resend_period_s = 0.2;
  /// Sends of one request before it is given up (with the default period: 10 s).
  int max_attempts = 50;
  /// The first request's id. A UAV restarted while the miniUGV's session runs on should
  /// start above the ids it used (docs/link.md, "Restarts").
  std::uint32_t first_request_id = 1;
};

/// The UAV's side of reliable requests: one in flight, the rest queued in order. The
/// request in flight is sent at once, then every resend_period_s until its ack; after
/// max_attempts sends and one more period without an ack it is given up, and the next
/// one goes. One in flight at a time is what keeps requests in order: the next id is
/// sent only once the miniUGV has the previous one (or it was given up).
class RequestSender {
 public:
  /// @throws std::invalid_argument for a period that is not > 0 or max_attempts < 1
  RequestSender(const Clock& clock, RequestSenderOptions options = {});

  /// Queues a request; its request_id is set here. Returns that id.
  std::uint32_t submit(UavRequest request);
  /// The request to send now, if one is due (its first send, or a resend); gives up
  /// the one in flight when its time is over (see take_results()).
  [[nodiscard]] std::optional<UavRequest> due();
  /// An ack arrived; true when it acknowledged the request in flight.
  bool acknowledge(std::uint32_t request_id);
  /// Requests acknowledged or given up since the last call, in the order they ended.
  [[nodiscard]] std::vector<RequestResult> take_results();

  [[nodiscard]] std::optional<std::uint32_t> in_flight() const;
  /// Requests not yet ended, the one in flight included.
  [[nodiscard]] std::size_t pending() const { return queue_.size(); }
  [[nodiscard]] std::uint64_t resends() const { return resends_; }
  [[nodiscard]] std::uint64_t given_up() const { return given_up_; }

 private:
  void finish(RequestResult::Status status);

  const Clock* clock_;
  RequestSenderOptions options_;
  std::uint32_t next_id_;
  std::deque<UavRequest> queue_;  ///< front: in flight
  int attempts_ = 0;              ///< sends of the front
  double last_sent_s_ = 0.0;
  std::uint64_t resends_ = 0, given_up_ = 0;
  std::vector<RequestResult> results_;
};

/// The miniUGV's side: delivers a request id once, and only above every id delivered
/// before (a copy, or a very late one, is acknowledged again and not delivered).
class RequestReceiver {
 public:
  /// True: a new request, deliver it. False: one delivered before (or older).
  bool accept(const UavRequest& request);
  /// Forgets the ids delivered: the UAV started over (its ids restart at 1).
  void reset() { last_delivered_ = 0; }
  [[nodiscard]] std::uint32_t last_delivered() const { return last_delivered_; }

 private:
  std::uint32_t last_delivered_ = 0;
};

/// What both ends share: decoding with counters, numbering, the outbox, a watchdog on
/// the peer. Each side handles the frames it receives.
class LinkSession {
 public:
  virtual ~LinkSession() = default;
  LinkSession(const LinkSession&) = delete;
  LinkSession& operator=(const LinkSession&) = delete;

  /// A datagram from the peer. Bad bytes are counted, never thrown.
  void receive(std::span<const std::uint8_t> datagram);
  /// The datagrams to send now (what was queued, and what the clock says is due).
  [[nodiscard]] virtual std::vector<Datagram> take_outgoing();

  [[nodiscard]] const LinkCounters& counters() const { return counters_; }
  /// The peer's watchdog: heard on every frame accepted from it.
  [[nodiscard]] const Watchdog& watchdog() const { return watchdog_; }
  /// The peer has been silent past its timeout (or never spoke): hold.
  [[nodiscard]] bool peer_silent() const { return watchdog_.expired(); }

 protected:
  LinkSession(const Clock& clock, double peer_timeout_s, std::uint32_t reorder_window);
  virtual void handle(const Frame& frame) = 0;
  /// Encodes and queues a message with the next sequence number of its stream.
  void queue(const Message& message);
  /// Runs a state frame through its stream's filter and counts the verdict; true when
  /// it is to be used.
  bool accept_state(const Frame& frame);

  const Clock& clock_;
  LinkCounters counters_;
  Watchdog watchdog_;

 private:
  FrameNumbering numbering_;
  std::array<StateStreamFilter, 4> filters_;  ///< by message type (requests and acks unused)
  std::vector<Datagram> outbox_;
};

struct UavLinkOptions {
  /// The UAV's heartbeat, so the miniUGV hears it between requests and learns what the
  /// UAV last heard of it: 20 Hz, as the telemetry.
  double heartbeat_period_s = 0.05;
  /// The winch holds its length after this long without telemetry: six frames at 20 Hz.
  double telemetry_timeout_s = 0.3;
  RequestSenderOptions requests;
  /// Frames at most this far behind the newest are late ones (dropped); further behind,
  /// the miniUGV restarted (accepted). 32 frames are 1.6 s of telemetry at 20 Hz, far
  /// beyond any reordering of a WiFi link.
  std::uint32_t reorder_window = 32;
};

/// The UAV's end of the link.
class UavLinkSession final : public LinkSession {
 public:
  /// @throws std::invalid_argument for a period or timeout that is not > 0
  explicit UavLinkSession(const Clock& clock, UavLinkOptions options = {});

  /// Queues a request (sent by take_outgoing()); returns its request_id.
  std::uint32_t request(UavRequest request) { return requests_.submit(std::move(request)); }
  /// Heartbeats when due, the request in flight when due, in that order.
  [[nodiscard]] std::vector<Datagram> take_outgoing() override;

  /// The newest telemetry accepted, if any (check peer_silent() before trusting it).
  [[nodiscard]] const std::optional<UgvTelemetry>& telemetry() const { return telemetry_; }
  [[nodiscard]] std::vector<RequestResult> take_request_results() {
    return requests_.take_results();
  }
  [[nodiscard]] const RequestSender& requests() const { return requests_; }

 private:
  void handle(const Frame& frame) override;

  UavLinkOptions options_;
  RequestSender requests_;
  std::optional<double> last_heartbeat_s_;
  std::optional<UgvTelemetry> telemetry_;
};

struct UgvLinkOptions {
  /// The miniUGV stops and holds after this long without hearing the UAV: a little
  /// over two missed heartbeats at 5 Hz.
  double uav_timeout_s = 0.5;
  /// As UavLinkOptions::reorder_window, for the UAV's heartbeats (32 are 6.4 s at 5 Hz).
  std::uint32_t reorder_window = 32;
};

/// The miniUGV's end of the link.
class UgvLinkSession final : public LinkSession {
 public:
  /// @throws std::invalid_argument for a timeout that is not > 0
  explicit UgvLinkSession(const Clock& clock, UgvLinkOptions options = {});

  /// Queues a telemetry frame (sent by take_outgoing()).
  /// @throws std::invalid_argument when validate() refuses it (encode())
  void send_telemetry(const UgvTelemetry& telemetry) { queue(telemetry); }
  /// The next request delivered, oldest first; each request id comes out once.
  [[nodiscard]] std::optional<UavRequest> next_request();
  /// The newest heartbeat accepted, if any.
  [[nodiscard]] const std::optional<Heartbeat>& heartbeat() const { return heartbeat_; }

 private:
  void handle(const Frame& frame) override;

  RequestReceiver requests_;
  std::deque<UavRequest> delivered_;
  std::optional<Heartbeat> heartbeat_;
};

}  // namespace ferret::link
