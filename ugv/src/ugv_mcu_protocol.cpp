#include "ferret/ugv/ugv_mcu_protocol.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>

#include "ferret/link/serial_framing.hpp"

namespace ferret::ugv::mcu {
namespace {

constexpr std::array<std::uint16_t, 256> make_crc_table() {
  std::array<std::uint16_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    auto crc = static_cast<std::uint16_t>(i << 8);
    for (int b = 0; b < 8; ++b)
      crc = static_cast<std::uint16_t>((crc & 0x8000) ? (crc << 1) ^ 0x1021 : crc << 1);
    table[i] = crc;
  }
  return table;
}
constexpr auto kCrcTable = make_crc_table();

// Little-endian writers and readers: every multi-byte field of the protocol is LE,
// the byte order of the MCUs that would run it (Cortex-M, AVR) and of the Pi.
void put_u8(std::vector<std::uint8_t>& out, std::uint8_t v) { out.push_back(v); }
void put_u16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v & 0xFF));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>((v >> (8 * i)) & 0xFF));
}
void put_i16(std::vector<std::uint8_t>& out, std::int16_t v) {
  put_u16(out, static_cast<std::uint16_t>(v));
}
void put_i32(std::vector<std::uint8_t>& out, std::int32_t v) {
  put_u32(out, static_cast<std::uint32_t>(v));
}

/// Reads fields in order; the decoders check the length first, so it never runs out.
class Cursor {
 public:
  explicit Cursor(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  std::uint8_t u8() { return bytes_[pos_++]; }
  std::uint16_t u16() {
    const auto v = static_cast<std::uint16_t>(bytes_[pos_] | (bytes_[pos_ + 1] << 8));
    pos_ += 2;
    return v;
  }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= static_cast<std::uint32_t>(bytes_[pos_ + i]) << (8 * i);
    pos_ += 4;
    return v;
  }
  std::int16_t i16() { return static_cast<std::int16_t>(u16()); }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t pos_ = 0;
};

constexpr std::size_t kStateFixedSize = 26;
constexpr std::size_t kInfoSize = 6;

std::vector<std::uint8_t> frame_of(std::uint8_t message_type, std::uint8_t seq,
                                   std::vector<std::uint8_t> payload) {
  return encode_frame(Frame{kProtocolVersion, message_type, seq, std::move(payload)});
}

}  // namespace

std::string type_name(std::uint8_t message_type) {
  switch (message_type) {
    case type::kDrive:
      return "DRIVE";
    case type::kEpm:
      return "EPM";
    case type::kHello:
      return "HELLO";
    case type::kState:
      return "STATE";
    case type::kInfo:
      return "INFO";
    default:
      return fmt::format("0x{:02X}", message_type);
  }
}

std::string describe_faults(std::uint16_t faults) {
  static constexpr std::array<const char*, 9> kNames = {
      "motor_left", "motor_right",      "encoder",  "imu",     "ir",
      "epm",        "battery_critical", "brownout", "host_crc"};
  if (faults == 0) return "none";
  std::string out;
  for (unsigned bit = 0; bit < 16; ++bit) {
    if (!(faults & (1u << bit))) continue;
    if (!out.empty()) out += ", ";
    out += bit < kNames.size() ? std::string(kNames[bit]) : fmt::format("bit{}", bit);
  }
  return out;
}

std::uint16_t crc16_ccitt(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
  for (const std::uint8_t b : bytes)
    crc = static_cast<std::uint16_t>((crc << 8) ^ kCrcTable[((crc >> 8) ^ b) & 0xFF]);
  return crc;
}

std::vector<std::uint8_t> encode_frame(const Frame& frame) {
  const std::size_t length = std::min<std::size_t>(frame.payload.size(), 255);
  std::vector<std::uint8_t> out;
  out.reserve(kHeaderSize + length + kCrcSize);
  for (const std::uint8_t b :
       {kSync0, kSync1, frame.version, frame.type, frame.seq, static_cast<std::uint8_t>(length)})
    out.push_back(b);
  for (std::size_t i = 0; i < length; ++i) out.push_back(frame.payload[i]);
  put_u16(out, crc16_ccitt(std::span(out).subspan(2)));
  return out;
}

const link::FrameFormat& frame_format() {
  static const link::FrameFormat kFormat{
      .sync = {kSync0, kSync1},
      .length_offset = 5,
      .length_bytes = 1,
      .overhead = kHeaderSize + kCrcSize,
      .checksum_from = 2,
      .checksum = [](std::span<const std::uint8_t> bytes) { return crc16_ccitt(bytes); },
      // Only version 1's lengths are known here; another version's frame is read whole.
      .length_ok =
          [](std::span<const std::uint8_t> header, std::size_t length) {
            return header[2] != kProtocolVersion || length <= kMaxPayloadSize;
          },
      // No stuffing: a false sync inside noise must not swallow a real frame after it.
      .after_bad_length = link::Resync::kNextByte,
      .after_bad_checksum = link::Resync::kNextByte,
  };
  return kFormat;
}

DecodeResult decode(std::span<const std::uint8_t> buffer) {
  using Scan = link::FrameScan::Status;
  DecodeResult r;
  const link::FrameScan scan = link::find_frame(buffer, frame_format());
  r.consumed = scan.consumed;
  switch (scan.status) {
    case Scan::kIncomplete:
      return r;
    case Scan::kBadLength:
      r.status = DecodeResult::Status::kBadLength;
      return r;
    case Scan::kBadChecksum:
      r.status = DecodeResult::Status::kBadCrc;
      return r;
    case Scan::kFrame:
      break;
  }
  const auto whole = buffer.subspan(scan.start, scan.size);
  r.frame.version = whole[2];
  r.frame.type = whole[3];
  r.frame.seq = whole[4];
  r.frame.payload.assign(whole.begin() + kHeaderSize, whole.end() - kCrcSize);
  r.status = r.frame.version == kProtocolVersion ? DecodeResult::Status::kFrame
                                                 : DecodeResult::Status::kBadVersion;
  return r;
}

FrameReader::FrameReader() : reader_(frame_format()) {}

void FrameReader::push(std::span<const std::uint8_t> bytes) { reader_.push(bytes); }

std::size_t FrameReader::receive(link::SerialPort& port, int timeout_ms) {
  return reader_.receive(port, timeout_ms);
}

std::optional<DecodeResult> FrameReader::next() {
  std::optional<DecodeResult> out;
  // Noise, bad CRCs and bad lengths are only counted.
  while (const std::optional<link::FrameEvent> e = reader_.next()) {
    if (e->status != link::FrameScan::Status::kFrame) continue;
    out = decode(e->bytes);
    if (out->status == DecodeResult::Status::kBadVersion) {
      ++stats_.bad_version;
      stats_.last_bad_version = out->frame.version;
    }
    break;
  }
  const link::FrameStats& s = reader_.stats();
  stats_.frames = s.frames - stats_.bad_version;
  stats_.bad_crc = s.bad_checksum;
  stats_.bad_length = s.bad_length;
  stats_.noise_bytes = s.noise_bytes;
  return out;
}

// ---------------------------------------------------------------- payloads

std::vector<std::uint8_t> encode_payload(const DriveCommand& c) {
  std::vector<std::uint8_t> out;
  put_i16(out, c.left_mmps);
  put_i16(out, c.right_mmps);
  return out;
}

std::vector<std::uint8_t> encode_payload(const EpmCommand& c) {
  return {static_cast<std::uint8_t>(c.on ? 1 : 0)};
}

std::vector<std::uint8_t> encode_payload(const McuInfo& info) {
  std::vector<std::uint8_t> out;
  put_u8(out, info.firmware_major);
  put_u8(out, info.firmware_minor);
  put_u8(out, info.ir_count);
  put_u16(out, info.watchdog_ms);
  put_u8(out, info.state_rate_hz);
  return out;
}

std::vector<std::uint8_t> encode_payload(const McuState& s) {
  std::vector<std::uint8_t> out;
  put_u32(out, s.mcu_time_ms);
  put_i32(out, s.left_ticks);
  put_i32(out, s.right_ticks);
  put_i16(out, s.roll_cdeg);
  put_i16(out, s.pitch_cdeg);
  put_i16(out, s.yaw_cdeg);
  put_u16(out, s.battery_mv);
  put_u8(out, s.battery_percent);
  put_u8(out, s.flags);
  put_u16(out, s.faults);
  put_u8(out, s.ir_seq);
  const std::size_t n = std::min(s.ir_mm.size(), kMaxIrSensors);
  put_u8(out, static_cast<std::uint8_t>(n));
  for (std::size_t i = 0; i < n; ++i) put_u16(out, s.ir_mm[i]);
  return out;
}

std::optional<DriveCommand> decode_drive(std::span<const std::uint8_t> payload) {
  if (payload.size() != 4) return std::nullopt;
  Cursor c(payload);
  DriveCommand d;
  d.left_mmps = c.i16();
  d.right_mmps = c.i16();
  return d;
}

std::optional<EpmCommand> decode_epm(std::span<const std::uint8_t> payload) {
  if (payload.size() != 1 || payload[0] > 1) return std::nullopt;
  return EpmCommand{payload[0] == 1};
}

std::optional<McuInfo> decode_info(std::span<const std::uint8_t> payload) {
  if (payload.size() != kInfoSize) return std::nullopt;
  Cursor c(payload);
  McuInfo i;
  i.firmware_major = c.u8();
  i.firmware_minor = c.u8();
  i.ir_count = c.u8();
  i.watchdog_ms = c.u16();
  i.state_rate_hz = c.u8();
  if (i.ir_count > kMaxIrSensors) return std::nullopt;
  return i;
}

std::optional<McuState> decode_state(std::span<const std::uint8_t> payload) {
  if (payload.size() < kStateFixedSize) return std::nullopt;
  const std::size_t n = payload[kStateFixedSize - 1];
  if (n > kMaxIrSensors || payload.size() != kStateFixedSize + 2 * n) return std::nullopt;
  Cursor c(payload);
  McuState s;
  s.mcu_time_ms = c.u32();
  s.left_ticks = c.i32();
  s.right_ticks = c.i32();
  s.roll_cdeg = c.i16();
  s.pitch_cdeg = c.i16();
  s.yaw_cdeg = c.i16();
  s.battery_mv = c.u16();
  s.battery_percent = c.u8();
  s.flags = c.u8();
  s.faults = c.u16();
  s.ir_seq = c.u8();
  (void)c.u8();  // the count, read above
  s.ir_mm.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.ir_mm[i] = c.u16();
  return s;
}

std::vector<std::uint8_t> encode_drive(std::uint8_t seq, const DriveCommand& c) {
  return frame_of(type::kDrive, seq, encode_payload(c));
}
std::vector<std::uint8_t> encode_epm(std::uint8_t seq, const EpmCommand& c) {
  return frame_of(type::kEpm, seq, encode_payload(c));
}
std::vector<std::uint8_t> encode_hello(std::uint8_t seq) { return frame_of(type::kHello, seq, {}); }
std::vector<std::uint8_t> encode_info(std::uint8_t seq, const McuInfo& info) {
  return frame_of(type::kInfo, seq, encode_payload(info));
}
std::vector<std::uint8_t> encode_state(std::uint8_t seq, const McuState& state) {
  return frame_of(type::kState, seq, encode_payload(state));
}

}  // namespace ferret::ugv::mcu
