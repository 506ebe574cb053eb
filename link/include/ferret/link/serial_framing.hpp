#pragma once
// Frames on a serial byte stream, for the protocols whose frames start with sync bytes,
// carry their length in a header field and end in a 16-bit checksum (the winch's
// Dynamixel Protocol 2.0, the miniUGV's MCU protocol). What they share is here: find
// the first sync, wait for the header and then for the whole frame, reject an
// impossible length before the checksum, check the checksum, resync after garbage, and
// read from a SerialPort until a verdict or a deadline. What the bytes of a frame mean
// (fields, stuffing, versions, payloads) stays with each protocol.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

namespace ferret::link {

class SerialPort;

/// How far to skip after a frame that fails its length or checksum.
enum class Resync {
  kNextByte,   ///< to the byte after the first sync byte: a sync inside noise may be false
  kPastSync,   ///< past the sync bytes
  kPastFrame,  ///< past the whole frame: a protocol whose stuffing keeps sync out of frames
};

/// Where a protocol's frames start, how long they are and how they are checked. The
/// checksum is the frame's last two bytes, little endian.
struct FrameFormat {
  std::vector<std::uint8_t> sync;  ///< the bytes every frame starts with (at least one)
  std::size_t length_offset = 0;   ///< the length field's first byte, from the frame's start
  std::size_t length_bytes = 1;    ///< 1 or 2, little endian
  std::size_t overhead = 0;        ///< a frame's size minus its length field's value
  std::size_t checksum_from = 0;   ///< the first byte the checksum covers (it ends before itself)
  std::function<std::uint16_t(std::span<const std::uint8_t>)> checksum;
  /// Whether the length field's value can be right, given the header up to and including
  /// the field (a version byte may decide); empty: any length.
  std::function<bool(std::span<const std::uint8_t> header, std::size_t length)> length_ok;
  Resync after_bad_length = Resync::kNextByte;
  Resync after_bad_checksum = Resync::kNextByte;

  /// The bytes up to and including the length field.
  [[nodiscard]] std::size_t header_size() const { return length_offset + length_bytes; }
};

/// The verdict on the start of a receive buffer.
struct FrameScan {
  enum class Status {
    kIncomplete,   ///< wait for more bytes (consumed: noise skipped before a sync)
    kFrame,        ///< a frame at [start, start + size) whose checksum is right
    kBadLength,    ///< a header whose length field length_ok refuses
    kBadChecksum,  ///< a whole frame at [start, start + size) whose checksum is wrong
  };
  Status status = Status::kIncomplete;
  std::size_t start = 0;     ///< where the frame (or the candidate) starts
  std::size_t size = 0;      ///< kFrame, kBadChecksum: the frame's size
  std::size_t consumed = 0;  ///< bytes to drop before looking again; never more than given
};

/// Finds and checks the first frame in `buffer` (bytes before a sync are skipped; a
/// trailing partial sync is kept). Never reads past the buffer.
[[nodiscard]] FrameScan find_frame(std::span<const std::uint8_t> buffer, const FrameFormat& format);

/// What a FrameReader dropped and found.
struct FrameStats {
  std::uint64_t bytes = 0;         ///< every byte pushed
  std::uint64_t frames = 0;        ///< frames with a right checksum
  std::uint64_t bad_checksum = 0;  ///< candidate frames with a wrong one
  std::uint64_t bad_length = 0;    ///< headers with an impossible length
  std::uint64_t noise_bytes = 0;   ///< bytes outside any frame with a right checksum
};

/// A verdict of a FrameReader: a frame, or one that failed (already dropped).
struct FrameEvent {
  FrameScan::Status status = FrameScan::Status::kFrame;  ///< never kIncomplete
  std::vector<std::uint8_t> bytes;                       ///< kFrame: the whole frame
};

/// A receive buffer over find_frame(): push bytes as they arrive, take verdicts until
/// there is none. Keeps at most one frame's worth of bytes.
class FrameReader {
 public:
  using Clock = std::chrono::steady_clock;

  explicit FrameReader(FrameFormat format) : format_(std::move(format)) {}

  /// Appends received bytes.
  void push(std::span<const std::uint8_t> bytes);
  /// The next frame or failed frame; nullopt: nothing more until more bytes.
  [[nodiscard]] std::optional<FrameEvent> next();
  /// Waits up to `timeout_ms` for bytes from `port` and pushes them; how many came.
  /// Throws the port's SerialError.
  std::size_t receive(SerialPort& port, int timeout_ms);
  /// next(), reading from `port` while there is none, until `deadline`; nullopt: the
  /// deadline passed first. Throws the port's SerialError.
  [[nodiscard]] std::optional<FrameEvent> read(SerialPort& port, Clock::time_point deadline);

  [[nodiscard]] const FrameStats& stats() const { return stats_; }
  [[nodiscard]] const FrameFormat& format() const { return format_; }
  /// Forgets buffered bytes (a new exchange, a reconnect).
  void clear() { buffer_.clear(); }

 private:
  FrameFormat format_;
  std::vector<std::uint8_t> buffer_;
  FrameStats stats_;
};

}  // namespace ferret::link
