#pragma once
// The robot link's wire format, version 3 (docs/link.md has it byte by byte): a fixed
// little-endian header, the message's payload, and a CRC-32 over both. decode() never
// throws on bad bytes and never reads past the buffer: it returns the frame, or why
// the bytes were refused, naming the field and what was expected.

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "ferret/link/messages.hpp"

namespace ferret::link {

/// A receiver refuses every other version (it cannot know another version's layout).
inline constexpr std::uint8_t kProtocolVersion = 3;
/// "FL": the first two bytes of every frame.
inline constexpr std::array<std::uint8_t, 2> kMagic{0x46, 0x4C};
/// magic 2, version 1, type 1, sender 1, sequence 4, payload length 2.
inline constexpr std::size_t kHeaderBytes = 11;
inline constexpr std::size_t kCrcBytes = 4;

/// A message with the sequence number its sender gave it on its stream (one stream a
/// message type: the sender follows from the type).
struct Frame {
  std::uint32_t sequence = 0;
  Message message;
  [[nodiscard]] MessageType type() const { return type_of(message); }
  [[nodiscard]] Sender sender() const { return sender_of(type()); }
  bool operator==(const Frame&) const = default;
};

/// Why bytes were not a frame, or why a message cannot be sent.
struct Rejection {
  enum class Reason : std::uint8_t {
    kTruncated,       ///< fewer bytes than a header, or than the header announces
    kBadMagic,        ///< not "FL"
    kUnknownVersion,  ///< another protocol version
    kUnknownType,     ///< a message type this version does not define
    kBadSender,       ///< a sender id that is not the sender of this message type
    kLengthMismatch,  ///< more bytes than announced, or a payload that does not fit its fields
    kCrcMismatch,     ///< the checksum does not match: damaged in transit
    kNotFinite,       ///< NaN or an infinity in a number field
    kOutOfRange,      ///< a number outside its field's range
    kBadEnum,         ///< an enum or flag value the field does not define
    kBadText,         ///< the reason string: too long, or not UTF-8
  };
  static constexpr std::size_t kReasonCount = 11;

  Reason reason = Reason::kTruncated;
  std::string field;     ///< "header.version", "telemetry.vx_mps", "request.reason"
  std::string expected;  ///< "1", "a number in [0, 1]"
  std::string got;       ///< what was found ("2", "nan"); may be empty

  /// One line: "telemetry.vx_mps: expected a finite number (got nan)".
  [[nodiscard]] std::string message() const;
};
[[nodiscard]] std::string_view to_string(Rejection::Reason reason);

/// A frame or the reason the bytes were refused.
class DecodeResult {
 public:
  DecodeResult(Frame frame) : value_(std::move(frame)) {}              // NOLINT: implicit
  DecodeResult(Rejection rejection) : value_(std::move(rejection)) {}  // NOLINT: implicit
  [[nodiscard]] bool ok() const { return std::holds_alternative<Frame>(value_); }
  /// @pre ok()
  [[nodiscard]] const Frame& frame() const { return std::get<Frame>(value_); }
  /// @pre !ok()
  [[nodiscard]] const Rejection& rejection() const { return std::get<Rejection>(value_); }

 private:
  std::variant<Frame, Rejection> value_;
};

/// Decodes one datagram: exactly one frame, no bytes before or after it.
[[nodiscard]] DecodeResult decode(std::span<const std::uint8_t> datagram);

/// The frame's bytes. The reason is cut to UavRequest::kMaxReasonBytes at a character
/// boundary (and at the first byte that is not UTF-8); everything else is sent as is.
/// @throws std::invalid_argument naming the field when validate() refuses the message:
///         a receiver would drop it, so sending it is the caller's bug
[[nodiscard]] std::vector<std::uint8_t> encode(std::uint32_t sequence, const Message& message);

/// What decode() would say about this message's fields (finite, in range, enums
/// defined, at most kMaxPlanSamples samples in increasing dt_s); nullopt when it is
/// valid. The reason string is not checked: encode() cuts it.
[[nodiscard]] std::optional<Rejection> validate(const Message& message);

/// Bytes of encode(sequence, message): header, payload and CRC.
[[nodiscard]] std::size_t encoded_size(const Message& message);

/// The reason as encode() sends it: the longest prefix of at most `max_bytes` bytes
/// that is whole, well-formed UTF-8.
[[nodiscard]] std::string_view wire_reason(std::string_view reason,
                                           std::size_t max_bytes = UavRequest::kMaxReasonBytes);

}  // namespace ferret::link
