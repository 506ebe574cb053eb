#pragma once
// CRC-32 (IEEE 802.3: polynomial 0x04C11DB7 reflected, initial and final XOR
// 0xFFFFFFFF), the checksum zlib, PNG, MCAP and the robot link use. Its own header
// so that a user of the checksum does not depend on the MCAP writer.

#include <cstdint>
#include <span>
#include <string_view>

namespace ferret {

/// CRC-32 of `bytes`, continued from `crc` (0 to start): crc32(b, crc32(a)) is the CRC
/// of a followed by b.
[[nodiscard]] std::uint32_t crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0);
[[nodiscard]] inline std::uint32_t crc32(std::string_view bytes, std::uint32_t crc = 0) {
  return crc32(std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), crc);
}

}  // namespace ferret
