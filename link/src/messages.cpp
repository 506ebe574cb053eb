#include "ferret/link/messages.hpp"

namespace ferret::link {

std::string_view to_string(UgvMode mode) {
  switch (mode) {
    case UgvMode::kIdle:
      return "idle";
    case UgvMode::kExplore:
      return "explore";
    case UgvMode::kTrack:
      return "track";
    case UgvMode::kTurn:
      return "turn";
    case UgvMode::kGrasp:
      return "grasp";
    case UgvMode::kReturn:
      return "return";
    case UgvMode::kAwaitRetract:
      return "await_retract";
    case UgvMode::kDone:
      return "done";
  }
  return "unknown";
}

std::string_view to_string(UgvOutcome outcome) {
  switch (outcome) {
    case UgvOutcome::kNone:
      return "none";
    case UgvOutcome::kObjectRetrieved:
      return "object_retrieved";
    case UgvOutcome::kNoObject:
      return "no_object";
    case UgvOutcome::kGraspFailed:
      return "grasp_failed";
    case UgvOutcome::kTrackLost:
      return "track_lost";
    case UgvOutcome::kBatteryLow:
      return "battery_low";
    case UgvOutcome::kSearchTimeout:
      return "search_timeout";
    case UgvOutcome::kReturnFailed:
      return "return_failed";
    case UgvOutcome::kRetractTimeout:
      return "retract_timeout";
    case UgvOutcome::kAborted:
      return "aborted";
    case UgvOutcome::kRecalled:
      return "recalled";
  }
  return "unknown";
}

std::string_view to_string(Sender sender) {
  switch (sender) {
    case Sender::kUav:
      return "uav";
    case Sender::kUgv:
      return "ugv";
  }
  return "unknown";
}

std::string_view to_string(UavRequest::Kind kind) {
  switch (kind) {
    case UavRequest::Kind::kStartSearch:
      return "start_search";
    case UavRequest::Kind::kRecall:
      return "recall";
    case UavRequest::Kind::kRetracted:
      return "retracted";
    case UavRequest::Kind::kReleaseObject:
      return "release_object";
    case UavRequest::Kind::kAbort:
      return "abort";
  }
  return "unknown";
}

std::string_view to_string(MessageType type) {
  switch (type) {
    case MessageType::kTelemetry:
      return "telemetry";
    case MessageType::kRequest:
      return "request";
    case MessageType::kAck:
      return "ack";
    case MessageType::kHeartbeat:
      return "heartbeat";
  }
  return "unknown";
}

// The type byte is the variant's index + 1: the order of Message is the wire's order.
static_assert(std::is_same_v<std::variant_alternative_t<0, Message>, UgvTelemetry>);
static_assert(std::is_same_v<std::variant_alternative_t<1, Message>, UavRequest>);
static_assert(std::is_same_v<std::variant_alternative_t<2, Message>, Ack>);
static_assert(std::is_same_v<std::variant_alternative_t<3, Message>, Heartbeat>);

MessageType type_of(const Message& message) {
  return static_cast<MessageType>(message.index() + 1);
}

Sender sender_of(MessageType type) {
  return type == MessageType::kTelemetry || type == MessageType::kAck ? Sender::kUgv : Sender::kUav;
}

}  // namespace ferret::link
