#include "ferret/core/crc32.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace ferret {
namespace {

TEST(Crc32, MatchesTheStandardCheckValueAndContinues) {
  EXPECT_EQ(crc32("123456789"), 0xCBF43926u);  // the CRC-32/IEEE check value
  EXPECT_EQ(crc32(""), 0u);
  EXPECT_EQ(crc32("6789", crc32("12345")), crc32("123456789"));
}

TEST(Crc32, BytesAndTextGiveTheSameChecksum) {
  const std::vector<std::uint8_t> bytes{'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  EXPECT_EQ(crc32(bytes), 0xCBF43926u);
  // Bytes above 0x7f must not be sign-extended on the way into the table.
  const std::vector<std::uint8_t> high{0xff, 0x80};
  EXPECT_EQ(crc32(high), crc32(std::string_view("\xff\x80", 2)));
  EXPECT_EQ(crc32(high), 0x3F456CADu);  // zlib.crc32(b"\xff\x80")
}

}  // namespace
}  // namespace ferret
