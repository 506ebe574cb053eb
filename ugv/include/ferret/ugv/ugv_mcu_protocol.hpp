#pragma once
// The serial protocol between the miniUGV's computer (host, the Raspberry Pi) and its
// motor/sensor microcontroller (MCU), version 1 (docs/robots.md, "Serial protocol").
//
// A frame, every field little endian:
//
//   A5 5A | version | type | seq | length | payload (length bytes) | CRC-16 (2 bytes)
//
// The CRC is CRC-16/CCITT-FALSE (poly 0x1021, init 0xFFFF, no reflection, no final
// xor; check value 0x29B1 for "123456789") over version .. the last payload byte. The
// header (sync pair, version, type, seq, length) and the CRC's place are the same in
// every version, so a host can always find a frame's end and tell "another version"
// from noise; only types and payloads may change with the version.
//
// Why this framing and not COBS: the MCU can parse it as it arrives, byte by byte,
// with a fixed 6-byte header and no pass over the whole frame; the length byte bounds
// the wait for the rest, and a frame is rejected on its length before any CRC. The
// CRC-16 detects every error of up to 3 bits and every burst of up to 16 bits in
// frames this short (at most 72 bytes). After a bad CRC or length the parser drops
// only the first sync byte and searches again, so a false sync inside noise never
// swallows a real frame that follows.
//
// Pure functions and a stream reader over link's framing (link/serial_framing.hpp), which
// also finds the Dynamixel's packets; HwUgvBase (hw_ugv_base.hpp) drives the port.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "ferret/link/serial_framing.hpp"

namespace ferret::link {
class SerialPort;
}

namespace ferret::ugv::mcu {

inline constexpr std::uint8_t kSync0 = 0xA5;
inline constexpr std::uint8_t kSync1 = 0x5A;
inline constexpr std::uint8_t kProtocolVersion = 1;
/// Sync pair, version, type, seq, length.
inline constexpr std::size_t kHeaderSize = 6;
inline constexpr std::size_t kCrcSize = 2;
/// The longest payload of version 1 (a longer length is rejected before the CRC).
inline constexpr std::size_t kMaxPayloadSize = 64;
inline constexpr std::size_t kMaxFrameSize = kHeaderSize + kMaxPayloadSize + kCrcSize;
/// IR sensors a STATE frame can carry (its payload must fit kMaxPayloadSize).
inline constexpr std::size_t kMaxIrSensors = 16;
/// An IR range that saw nothing within the sensor's range; the MCU reports any reading
/// it cannot trust (below the sensor's minimum, a sensor error) the same way.
inline constexpr std::uint16_t kIrNoReturn = 0xFFFF;

/// Message types. Host -> MCU below 0x80, MCU -> host from 0x80.
namespace type {
inline constexpr std::uint8_t kDrive = 0x01;  ///< wheel set-points; also the keepalive
inline constexpr std::uint8_t kEpm = 0x02;    ///< the EPM's wanted state
inline constexpr std::uint8_t kHello = 0x03;  ///< asks for INFO (identification)
inline constexpr std::uint8_t kState = 0x81;  ///< telemetry, streamed at the MCU's rate
inline constexpr std::uint8_t kInfo = 0x82;   ///< the reply to HELLO
}  // namespace type
/// "DRIVE", "STATE", ... or "0xNN" for a type this version does not know.
[[nodiscard]] std::string type_name(std::uint8_t message_type);

/// STATE flag bits.
namespace flag {
inline constexpr std::uint8_t kEpmOn = 1u << 0;    ///< the magnet is on (its last pulse)
inline constexpr std::uint8_t kContact = 1u << 1;  ///< the EPM face touches a ferromagnetic body
/// The MCU stopped the wheels itself: no valid frame from the host for its watchdog
/// time. Cleared by the next DRIVE frame.
inline constexpr std::uint8_t kWatchdogStop = 1u << 2;
}  // namespace flag

/// STATE fault bits (what the MCU knows is wrong; 0 = healthy).
namespace fault {
inline constexpr std::uint16_t kMotorLeft = 1u << 0;   ///< left motor driver fault / stall
inline constexpr std::uint16_t kMotorRight = 1u << 1;  ///< right motor driver fault / stall
inline constexpr std::uint16_t kEncoder = 1u << 2;     ///< an encoder gives no counts while driven
inline constexpr std::uint16_t kImu = 1u << 3;         ///< the IMU does not answer
inline constexpr std::uint16_t kIr = 1u << 4;          ///< an IR sensor does not answer
inline constexpr std::uint16_t kEpm = 1u << 5;         ///< a pulse did not switch the magnet
/// The battery is below the MCU's cut-off: it keeps the motors off.
inline constexpr std::uint16_t kBatteryCritical = 1u << 6;
inline constexpr std::uint16_t kBrownout = 1u << 7;  ///< the MCU restarted on a brownout
inline constexpr std::uint16_t kHostCrc = 1u << 8;   ///< it received frames with a bad CRC
}  // namespace fault
/// "motor_left, imu" for the set bits (unknown bits as "bit12"); "none" for 0.
[[nodiscard]] std::string describe_faults(std::uint16_t faults);

/// One frame as it travels: the header fields and the raw payload.
struct Frame {
  std::uint8_t version = kProtocolVersion;
  std::uint8_t type = 0;
  std::uint8_t seq = 0;  ///< per sender, +1 a frame, wraps; lets the receiver count losses
  std::vector<std::uint8_t> payload;
};

/// CRC-16/CCITT-FALSE.
[[nodiscard]] std::uint16_t crc16_ccitt(std::span<const std::uint8_t> bytes,
                                        std::uint16_t crc = 0xFFFF);

/// The bytes of a frame. @pre payload.size() <= 255 (kMaxPayloadSize for version 1).
[[nodiscard]] std::vector<std::uint8_t> encode_frame(const Frame& frame);

struct DecodeResult {
  enum class Status {
    kIncomplete,  ///< wait for more bytes (consumed: noise skipped before a sync pair)
    kFrame,       ///< `frame` is valid (version 1, CRC right)
    kBadCrc,      ///< a sync pair whose frame fails its CRC: drop `consumed` and look again
    kBadLength,   ///< a version-1 header with length > kMaxPayloadSize
    kBadVersion,  ///< a whole frame, CRC right, of another version (`frame.version`)
  };
  Status status = Status::kIncomplete;
  std::size_t consumed = 0;  ///< bytes of the buffer used up; never more than its size
  Frame frame;               ///< kFrame; kBadVersion: the header fields and payload
};

/// The framing for link::FrameReader: the sync pair, the length at byte 5, the CRC over
/// version .. payload, a version-1 length checked before it, resync one byte later.
[[nodiscard]] const link::FrameFormat& frame_format();

/// Finds and checks the first frame in `buffer` (a receive stream: bytes before a
/// sync pair are skipped). Never reads past the buffer, never throws on its bytes.
/// A bad CRC or length consumes only up to the first sync byte, so the search
/// resumes one byte later.
[[nodiscard]] DecodeResult decode(std::span<const std::uint8_t> buffer);

/// Counts of what a FrameReader dropped.
struct ReaderStats {
  std::uint64_t frames = 0;       ///< valid frames
  std::uint64_t bad_crc = 0;      ///< candidate frames with a bad CRC
  std::uint64_t bad_length = 0;   ///< version-1 headers with an impossible length
  std::uint64_t bad_version = 0;  ///< whole frames of another protocol version
  std::uint64_t noise_bytes = 0;  ///< bytes outside any valid frame
  std::uint8_t last_bad_version = 0;
};

/// A byte-stream reader over link::FrameReader: push bytes as they arrive, then take
/// frames until there is none. Keeps at most one frame's worth of bytes.
class FrameReader {
 public:
  FrameReader();
  /// Appends received bytes.
  void push(std::span<const std::uint8_t> bytes);
  /// Waits up to `timeout_ms` for bytes from `port` and appends them; how many came.
  /// Throws the port's link::SerialError.
  std::size_t receive(link::SerialPort& port, int timeout_ms);
  /// The next event: a valid frame or a frame of another version (kBadVersion); noise,
  /// bad CRCs and bad lengths are only counted. nullopt: nothing more until more bytes.
  [[nodiscard]] std::optional<DecodeResult> next();
  [[nodiscard]] const ReaderStats& stats() const { return stats_; }
  /// Forgets buffered bytes (after a reconnect).
  void clear() { reader_.clear(); }

 private:
  link::FrameReader reader_;
  ReaderStats stats_;
};

// ---------------------------------------------------------------- payloads

/// DRIVE (host -> MCU), 4 bytes: int16 left, int16 right wheel surface speed, mm/s
/// (+ drives the robot forward). The MCU holds each wheel at its speed with its own
/// encoder loop; the host's kinematics (track width) stay on the host, beside the
/// odometry that uses the same numbers. Every DRIVE also resets the MCU's watchdog.
struct DriveCommand {
  std::int16_t left_mmps = 0;
  std::int16_t right_mmps = 0;
};

/// EPM (host -> MCU), 1 byte: 0 off, 1 on. A wanted state, not a toggle: the MCU fires
/// the magnet's switching pulse only when the state differs from its own, so the host
/// may repeat it until STATE reports the state.
struct EpmCommand {
  bool on = false;
};

/// INFO (MCU -> host, the reply to HELLO), 6 bytes.
struct McuInfo {
  std::uint8_t firmware_major = 0;
  std::uint8_t firmware_minor = 0;
  std::uint8_t ir_count = 0;       ///< IR sensors in every STATE
  std::uint16_t watchdog_ms = 0;   ///< the MCU stops the wheels after this long without a frame
  std::uint8_t state_rate_hz = 0;  ///< how often it sends STATE
};

/// STATE (MCU -> host), 26 + 2 n bytes: one snapshot of every sensor at mcu_time_ms.
struct McuState {
  std::uint32_t mcu_time_ms = 0;  ///< ms since the MCU started (wraps after 49 days)
  std::int32_t left_ticks = 0;    ///< cumulative encoder counts, + forward; wrap at 2^32
  std::int32_t right_ticks = 0;
  std::int16_t roll_cdeg = 0;  ///< IMU attitude, centidegrees, URDF rpy (R = Rz Ry Rx)
  std::int16_t pitch_cdeg = 0;
  std::int16_t yaw_cdeg = 0;
  std::uint16_t battery_mv = 0;
  std::uint8_t battery_percent = 0;  ///< the MCU's estimate of the charge left, 0..100
  std::uint8_t flags = 0;            ///< flag::*
  std::uint16_t faults = 0;          ///< fault::*
  /// +1 whenever the IR ranges are a new reading (the IR sensors are slower than the
  /// STATE stream): the host uses each reading once.
  std::uint8_t ir_seq = 0;
  std::vector<std::uint16_t> ir_mm;  ///< one range per IR sensor, mm; kIrNoReturn: none
};

[[nodiscard]] std::vector<std::uint8_t> encode_payload(const DriveCommand& c);
[[nodiscard]] std::vector<std::uint8_t> encode_payload(const EpmCommand& c);
[[nodiscard]] std::vector<std::uint8_t> encode_payload(const McuInfo& info);
/// @pre state.ir_mm.size() <= kMaxIrSensors
[[nodiscard]] std::vector<std::uint8_t> encode_payload(const McuState& state);

/// Payload decoders: nullopt for a payload of the wrong length or a value the
/// version does not define (an EPM byte other than 0 or 1, more than kMaxIrSensors
/// ranges, a length that disagrees with the IR count).
[[nodiscard]] std::optional<DriveCommand> decode_drive(std::span<const std::uint8_t> payload);
[[nodiscard]] std::optional<EpmCommand> decode_epm(std::span<const std::uint8_t> payload);
[[nodiscard]] std::optional<McuInfo> decode_info(std::span<const std::uint8_t> payload);
[[nodiscard]] std::optional<McuState> decode_state(std::span<const std::uint8_t> payload);

/// A whole frame of a message (version 1).
[[nodiscard]] std::vector<std::uint8_t> encode_drive(std::uint8_t seq, const DriveCommand& c);
[[nodiscard]] std::vector<std::uint8_t> encode_epm(std::uint8_t seq, const EpmCommand& c);
[[nodiscard]] std::vector<std::uint8_t> encode_hello(std::uint8_t seq);
[[nodiscard]] std::vector<std::uint8_t> encode_info(std::uint8_t seq, const McuInfo& info);
[[nodiscard]] std::vector<std::uint8_t> encode_state(std::uint8_t seq, const McuState& state);

}  // namespace ferret::ugv::mcu
