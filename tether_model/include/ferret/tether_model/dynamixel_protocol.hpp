#pragma once
// Dynamixel Protocol 2.0 packets (ROBOTIS e-Manual, "Protocol 2.0"): header
// FF FF FD 00, id, length (LE, counts instruction + parameters + CRC), instruction,
// parameters, CRC-16 (polynomial 0x8005, LE). Inside instruction and parameters,
// every FF FF FD is followed by a stuffing byte FD so that a header never appears
// within a packet. Pure functions, no I/O: the bus (dynamixel_bus.hpp) does the I/O.

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace ferret::link {
struct FrameFormat;
}

namespace ferret::tether::dxl {

namespace instruction {
inline constexpr std::uint8_t kPing = 0x01;
inline constexpr std::uint8_t kRead = 0x02;
inline constexpr std::uint8_t kWrite = 0x03;
inline constexpr std::uint8_t kReboot = 0x08;
inline constexpr std::uint8_t kClear = 0x10;
inline constexpr std::uint8_t kStatus = 0x55;
}  // namespace instruction

inline constexpr std::uint8_t kBroadcastId = 0xFE;

/// CRC-16 of Protocol 2.0 (CRC-16/BUYPASS: poly 0x8005, init 0, no reflection),
/// over the header through the last parameter byte (after stuffing).
[[nodiscard]] std::uint16_t crc16(std::span<const std::uint8_t> bytes, std::uint16_t crc = 0);

/// Inserts the stuffing byte FD after every FF FF FD in `payload` (instruction + parameters).
[[nodiscard]] std::vector<std::uint8_t> stuff(std::span<const std::uint8_t> payload);
/// Removes stuffing bytes (the FD following FF FF FD).
[[nodiscard]] std::vector<std::uint8_t> unstuff(std::span<const std::uint8_t> payload);

/// A whole packet: for an instruction packet, `instruction` and its parameters; for
/// a status packet, instruction = 0x55, `error` and the returned parameters.
struct Packet {
  std::uint8_t id = 0;
  std::uint8_t instruction = 0;
  std::uint8_t error = 0;  ///< status packets only
  std::vector<std::uint8_t> params;
};

/// Encodes an instruction packet.
[[nodiscard]] std::vector<std::uint8_t> encode_instruction(
    std::uint8_t id, std::uint8_t instruction, std::span<const std::uint8_t> params = {});
/// Encodes a status packet (what a servo sends back).
[[nodiscard]] std::vector<std::uint8_t> encode_status(std::uint8_t id, std::uint8_t error,
                                                      std::span<const std::uint8_t> params = {});

struct DecodeResult {
  enum class Status { kIncomplete, kPacket, kBadCrc, kMalformed };
  Status status = Status::kIncomplete;
  std::size_t consumed = 0;  ///< bytes of the buffer used (noise before the header included)
  Packet packet;             ///< valid when status == kPacket
};

/// Protocol 2.0's framing for link::FrameReader: the header, the length at bytes 5-6,
/// the CRC over everything before it; after a bad CRC the search resumes past the packet.
[[nodiscard]] const link::FrameFormat& frame_format();

/// Finds and decodes the first packet in `buffer` (a receive stream: bytes before a
/// header are skipped). kIncomplete: wait for more bytes (consumed = noise skipped);
/// kBadCrc / kMalformed: drop `consumed` bytes and look again.
[[nodiscard]] DecodeResult decode(std::span<const std::uint8_t> buffer);

/// Parameters of Read: address and length, little endian.
[[nodiscard]] std::vector<std::uint8_t> read_params(std::uint16_t address, std::uint16_t length);
/// Parameters of Write: address then data.
[[nodiscard]] std::vector<std::uint8_t> write_params(std::uint16_t address,
                                                     std::span<const std::uint8_t> data);

/// Little-endian encoding of the low `size` bytes of value.
[[nodiscard]] std::vector<std::uint8_t> to_le(std::uint32_t value, std::size_t size);
/// Little-endian decoding of up to 4 bytes.
[[nodiscard]] std::uint32_t from_le(std::span<const std::uint8_t> bytes);

/// Protocol 2.0 status error byte: bit 7 is the hardware alert, bits 0-6 the error number.
[[nodiscard]] std::string describe_status_error(std::uint8_t error);

}  // namespace ferret::tether::dxl
