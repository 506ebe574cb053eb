#include "ferret/link/link_session.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>
#include <utility>

namespace ferret::link {
namespace {

double require_positive(double value, const char* field) {
  if (!std::isfinite(value) || value <= 0)
    throw std::invalid_argument(
        fmt::format("link options: {}: expected a number > 0 s (got {})", field, value));
  return value;
}

// Periods are compared with this much slack: a clock stepped at 20 Hz reads 0.6000000000000001
// where 0.6 was meant, and a heartbeat due at 0.8 must not wait for the next step.
constexpr double kClockSlack_s = 1e-9;

}  // namespace

std::string LinkCounters::summary() const {
  std::string out =
      fmt::format("received {} accepted {} corrupted {}", received, accepted, corrupted);
  if (corrupted > 0) {
    std::string by_reason;
    for (std::size_t i = 0; i < rejected.size(); ++i)
      if (rejected[i] > 0)
        by_reason += fmt::format("{}{} {}", by_reason.empty() ? "" : ", ",
                                 to_string(static_cast<Rejection::Reason>(i)), rejected[i]);
    out += " (" + by_reason + ")";
  }
  out +=
      fmt::format(" duplicates {} stale {} restarts {} unexpected {} sent {} resent {} given_up {}",
                  duplicates, stale, restarts, unexpected, sent, resent, given_up);
  return out;
}

// ------------------------------------------------------------------ state streams

StateStreamFilter::Verdict StateStreamFilter::accept(std::uint32_t sequence) {
  if (!has_newest_) {
    has_newest_ = true;
    newest_ = sequence;
    return Verdict::kAccepted;
  }
  const std::uint32_t ahead = sequence - newest_;  // modulo 2^32
  if (ahead == 0) return Verdict::kDuplicate;
  if (ahead < 0x80000000u) {
    newest_ = sequence;
    return Verdict::kAccepted;
  }
  const std::uint32_t behind = newest_ - sequence;
  if (behind <= reorder_window_) return Verdict::kStale;
  newest_ = sequence;
  return Verdict::kRestarted;
}

std::optional<std::uint32_t> StateStreamFilter::newest() const {
  return has_newest_ ? std::optional(newest_) : std::nullopt;
}

// ------------------------------------------------------------------ requests

RequestSender::RequestSender(const Clock& clock, RequestSenderOptions options)
    : clock_(&clock), options_(options), next_id_(options.first_request_id) {
  require_positive(options.resend_period_s, "requests.resend_period_s");
  if (options.max_attempts < 1)
    throw std::invalid_argument(
        fmt::format("link options: requests.max_attempts: expected an integer >= 1 (got {})",
                    options.max_attempts));
  if (options.first_request_id < 1)
    throw std::invalid_argument(
        "link options: requests.first_request_id: expected an integer >= 1 (got 0)");
}

std::uint32_t RequestSender::submit(UavRequest request) {
  request.request_id = next_id_++;
  queue_.push_back(std::move(request));
  return queue_.back().request_id;
}

std::optional<UavRequest> RequestSender::due() {
  const double now = clock_->now_s();
  while (!queue_.empty()) {
    if (attempts_ == 0) break;  // not sent yet: send it now
    if (now - last_sent_s_ < options_.resend_period_s - kClockSlack_s) return std::nullopt;
    if (attempts_ < options_.max_attempts) {
      ++resends_;
      break;
    }
    finish(RequestResult::Status::kGivenUp);  // and the next one goes at once
  }
  if (queue_.empty()) return std::nullopt;
  ++attempts_;
  last_sent_s_ = now;
  return queue_.front();
}

bool RequestSender::acknowledge(std::uint32_t request_id) {
  // attempts_ > 0: an ack can only answer a request that was sent.
  if (queue_.empty() || attempts_ == 0 || queue_.front().request_id != request_id) return false;
  finish(RequestResult::Status::kAcknowledged);
  return true;
}

void RequestSender::finish(RequestResult::Status status) {
  if (status == RequestResult::Status::kGivenUp) ++given_up_;
  results_.push_back({std::move(queue_.front()), status, attempts_});
  queue_.pop_front();
  attempts_ = 0;
}

std::vector<RequestResult> RequestSender::take_results() { return std::exchange(results_, {}); }

std::optional<std::uint32_t> RequestSender::in_flight() const {
  if (queue_.empty() || attempts_ == 0) return std::nullopt;
  return queue_.front().request_id;
}

bool RequestReceiver::accept(const UavRequest& request) {
  if (request.request_id <= last_delivered_) return false;
  last_delivered_ = request.request_id;
  return true;
}

// ------------------------------------------------------------------ sessions

LinkSession::LinkSession(const Clock& clock, double peer_timeout_s, std::uint32_t reorder_window)
    : clock_(clock),
      watchdog_(clock, peer_timeout_s),
      filters_{StateStreamFilter(reorder_window), StateStreamFilter(reorder_window),
               StateStreamFilter(reorder_window), StateStreamFilter(reorder_window)} {}

void LinkSession::receive(std::span<const std::uint8_t> datagram) {
  ++counters_.received;
  const DecodeResult result = decode(datagram);
  if (!result.ok()) {
    ++counters_.corrupted;
    ++counters_.rejected[static_cast<std::size_t>(result.rejection().reason)];
    return;
  }
  handle(result.frame());
}

std::vector<Datagram> LinkSession::take_outgoing() { return std::exchange(outbox_, {}); }

void LinkSession::queue(const Message& message) {
  outbox_.push_back(encode(numbering_.next(type_of(message)), message));
  ++counters_.sent;
}

bool LinkSession::accept_state(const Frame& frame) {
  switch (filters_[static_cast<std::size_t>(frame.type()) - 1].accept(frame.sequence)) {
    case StateStreamFilter::Verdict::kAccepted:
      break;
    case StateStreamFilter::Verdict::kRestarted:
      ++counters_.restarts;
      break;
    case StateStreamFilter::Verdict::kDuplicate:
      ++counters_.duplicates;
      return false;
    case StateStreamFilter::Verdict::kStale:
      ++counters_.stale;
      return false;
  }
  ++counters_.accepted;
  watchdog_.heard();
  return true;
}

UavLinkSession::UavLinkSession(const Clock& clock, UavLinkOptions options)
    : LinkSession(clock, require_positive(options.telemetry_timeout_s, "telemetry_timeout_s"),
                  options.reorder_window),
      options_(options),
      requests_(clock, options.requests) {
  require_positive(options.heartbeat_period_s, "heartbeat_period_s");
}

std::vector<Datagram> UavLinkSession::take_outgoing() {
  const double now = clock_.now_s();
  if (!last_heartbeat_s_ ||
      now - *last_heartbeat_s_ >= options_.heartbeat_period_s - kClockSlack_s) {
    queue(Heartbeat{now, telemetry_ ? telemetry_->t_s : 0.0});
    last_heartbeat_s_ = now;
  }
  const std::uint64_t resends_before = requests_.resends();
  if (auto request = requests_.due()) queue(*request);
  counters_.resent += requests_.resends() - resends_before;
  counters_.given_up = requests_.given_up();
  return LinkSession::take_outgoing();
}

void UavLinkSession::handle(const Frame& frame) {
  if (const auto* telemetry = std::get_if<UgvTelemetry>(&frame.message)) {
    if (accept_state(frame)) telemetry_ = *telemetry;
  } else if (const auto* ack = std::get_if<Ack>(&frame.message)) {
    // An ack is no news of where the miniUGV is: it does not feed the watchdog.
    if (requests_.acknowledge(ack->request_id))
      ++counters_.accepted;
    else
      ++counters_.duplicates;
  } else {
    ++counters_.unexpected;
  }
}

UgvLinkSession::UgvLinkSession(const Clock& clock, UgvLinkOptions options)
    : LinkSession(clock, require_positive(options.uav_timeout_s, "uav_timeout_s"),
                  options.reorder_window) {}

std::optional<UavRequest> UgvLinkSession::next_request() {
  if (delivered_.empty()) return std::nullopt;
  UavRequest next = std::move(delivered_.front());
  delivered_.pop_front();
  return next;
}

void UgvLinkSession::handle(const Frame& frame) {
  if (const auto* heartbeat = std::get_if<Heartbeat>(&frame.message)) {
    const auto restarts_before = counters_.restarts;
    if (accept_state(frame)) heartbeat_ = *heartbeat;
    // A restarted UAV numbers its requests from the start again.
    if (counters_.restarts > restarts_before) requests_.reset();
  } else if (const auto* request = std::get_if<UavRequest>(&frame.message)) {
    // Every copy is acknowledged: the ack of an earlier copy may have been lost.
    queue(Ack{request->request_id});
    if (requests_.accept(*request)) {
      ++counters_.accepted;
      watchdog_.heard();
      delivered_.push_back(*request);
    } else {
      ++counters_.duplicates;
    }
  } else {
    ++counters_.unexpected;
  }
}

}  // namespace ferret::link
