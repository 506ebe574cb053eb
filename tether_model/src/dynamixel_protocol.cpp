#include "ferret/tether_model/dynamixel_protocol.hpp"

#include <array>

#include "ferret/link/serial_framing.hpp"

namespace ferret::tether::dxl {

namespace {
constexpr std::array<std::uint8_t, 4> kHeader = {0xFF, 0xFF, 0xFD, 0x00};
constexpr std::size_t kPrefixSize = 7;  // header, id, length

constexpr std::array<std::uint16_t, 256> make_crc_table() {
  std::array<std::uint16_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint16_t crc = static_cast<std::uint16_t>(i << 8);
    for (int b = 0; b < 8; ++b)
      crc = static_cast<std::uint16_t>((crc & 0x8000) ? (crc << 1) ^ 0x8005 : crc << 1);
    table[i] = crc;
  }
  return table;
}
constexpr auto kCrcTable = make_crc_table();

std::vector<std::uint8_t> encode(std::uint8_t id, std::span<const std::uint8_t> payload) {
  const std::vector<std::uint8_t> body = stuff(payload);
  const std::size_t length = body.size() + 2;
  std::vector<std::uint8_t> out(kHeader.begin(), kHeader.end());
  out.push_back(id);
  out.push_back(static_cast<std::uint8_t>(length & 0xFF));
  out.push_back(static_cast<std::uint8_t>(length >> 8));
  out.insert(out.end(), body.begin(), body.end());
  const std::uint16_t crc = crc16(out);
  out.push_back(static_cast<std::uint8_t>(crc & 0xFF));
  out.push_back(static_cast<std::uint8_t>(crc >> 8));
  return out;
}
}  // namespace

std::uint16_t crc16(std::span<const std::uint8_t> bytes, std::uint16_t crc) {
  for (const std::uint8_t b : bytes)
    crc = static_cast<std::uint16_t>((crc << 8) ^ kCrcTable[((crc >> 8) ^ b) & 0xFF]);
  return crc;
}

std::vector<std::uint8_t> stuff(std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> out;
  out.reserve(payload.size() + 4);
  for (std::size_t i = 0; i < payload.size(); ++i) {
    out.push_back(payload[i]);
    if (i >= 2 && payload[i] == 0xFD && payload[i - 1] == 0xFF && payload[i - 2] == 0xFF)
      out.push_back(0xFD);
  }
  return out;
}

std::vector<std::uint8_t> unstuff(std::span<const std::uint8_t> payload) {
  std::vector<std::uint8_t> out;
  out.reserve(payload.size());
  for (std::size_t i = 0; i < payload.size(); ++i) {
    out.push_back(payload[i]);
    if (i >= 2 && payload[i] == 0xFD && payload[i - 1] == 0xFF && payload[i - 2] == 0xFF &&
        i + 1 < payload.size() && payload[i + 1] == 0xFD)
      ++i;  // skip the stuffing byte
  }
  return out;
}

std::vector<std::uint8_t> encode_instruction(std::uint8_t id, std::uint8_t instr,
                                             std::span<const std::uint8_t> params) {
  std::vector<std::uint8_t> payload{instr};
  payload.insert(payload.end(), params.begin(), params.end());
  return encode(id, payload);
}

std::vector<std::uint8_t> encode_status(std::uint8_t id, std::uint8_t error,
                                        std::span<const std::uint8_t> params) {
  std::vector<std::uint8_t> payload{instruction::kStatus, error};
  payload.insert(payload.end(), params.begin(), params.end());
  return encode(id, payload);
}

const link::FrameFormat& frame_format() {
  static const link::FrameFormat kFormat{
      .sync = {kHeader.begin(), kHeader.end()},
      .length_offset = 5,
      .length_bytes = 2,
      .overhead = kPrefixSize,
      .checksum_from = 0,
      .checksum = [](std::span<const std::uint8_t> bytes) { return crc16(bytes); },
      // At least an instruction byte and the CRC.
      .length_ok = [](std::span<const std::uint8_t>, std::size_t length) { return length >= 3; },
      .after_bad_length = link::Resync::kPastSync,
      // Stuffing keeps a header out of a packet: none can start inside a bad one.
      .after_bad_checksum = link::Resync::kPastFrame,
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
      r.status = DecodeResult::Status::kMalformed;
      return r;
    case Scan::kBadChecksum:
      r.status = DecodeResult::Status::kBadCrc;
      return r;
    case Scan::kFrame:
      break;
  }
  const auto packet = buffer.subspan(scan.start, scan.size);
  const std::vector<std::uint8_t> body =
      unstuff(packet.subspan(kPrefixSize, scan.size - kPrefixSize - 2));
  r.packet.id = packet[4];
  r.packet.instruction = body[0];
  std::size_t first_param = 1;
  if (body[0] == instruction::kStatus) {
    if (body.size() < 2) {
      r.status = DecodeResult::Status::kMalformed;
      return r;
    }
    r.packet.error = body[1];
    first_param = 2;
  }
  r.packet.params.assign(body.begin() + static_cast<long>(first_param), body.end());
  r.status = DecodeResult::Status::kPacket;
  return r;
}

std::vector<std::uint8_t> to_le(std::uint32_t value, std::size_t size) {
  std::vector<std::uint8_t> out;
  for (std::size_t i = 0; i < size; ++i)
    out.push_back(static_cast<std::uint8_t>((value >> (8 * i)) & 0xFF));
  return out;
}

std::uint32_t from_le(std::span<const std::uint8_t> bytes) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < bytes.size() && i < 4; ++i)
    v |= static_cast<std::uint32_t>(bytes[i]) << (8 * i);
  return v;
}

std::vector<std::uint8_t> read_params(std::uint16_t address, std::uint16_t length) {
  auto p = to_le(address, 2);
  const auto l = to_le(length, 2);
  p.insert(p.end(), l.begin(), l.end());
  return p;
}

std::vector<std::uint8_t> write_params(std::uint16_t address, std::span<const std::uint8_t> data) {
  auto p = to_le(address, 2);
  p.insert(p.end(), data.begin(), data.end());
  return p;
}

std::string describe_status_error(std::uint8_t error) {
  static const char* const kNames[] = {"no error",         "result fail",      "instruction error",
                                       "CRC error",        "data range error", "data length error",
                                       "data limit error", "access error"};
  const std::uint8_t number = error & 0x7F;
  std::string text = number < 8 ? kNames[number] : "unknown error " + std::to_string(number);
  if (error & 0x80) text += " (hardware alert: read Hardware Error Status)";
  return text;
}

}  // namespace ferret::tether::dxl
