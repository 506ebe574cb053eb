#include "ferret/tether_model/dynamixel_protocol.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace ferret::tether::dxl {
namespace {

using Bytes = std::vector<std::uint8_t>;

// Packets from the ROBOTIS e-Manual's Protocol 2.0 page (Ping, Read, Write examples).
const Bytes kPing = {0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x03, 0x00, 0x01, 0x19, 0x4E};
const Bytes kPingStatus = {0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00,
                           0x55, 0x00, 0x06, 0x04, 0x26, 0x65, 0x5D};
const Bytes kReadPosition = {0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x07, 0x00,
                             0x02, 0x84, 0x00, 0x04, 0x00, 0x1D, 0x15};
const Bytes kReadStatus = {0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x08, 0x00, 0x55,
                           0x00, 0xA6, 0x00, 0x00, 0x00, 0x8C, 0xC0};
const Bytes kWriteGoal = {0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x09, 0x00, 0x03,
                          0x74, 0x00, 0x00, 0x02, 0x00, 0x00, 0xCA, 0x89};
const Bytes kWriteStatus = {0xFF, 0xFF, 0xFD, 0x00, 0x01, 0x04, 0x00, 0x55, 0x00, 0xA1, 0x0C};

TEST(DynamixelProtocol, CrcMatchesThePublishedPingExample) {
  EXPECT_EQ(crc16(std::span(kPing).first(8)), 0x4E19);
  EXPECT_EQ(crc16(std::span(kPingStatus).first(12)), 0x5D65);
  // CRC-16/BUYPASS check value: "123456789" -> 0xFEE8.
  const std::string check = "123456789";
  EXPECT_EQ(crc16(std::span(reinterpret_cast<const std::uint8_t*>(check.data()), check.size())),
            0xFEE8);
}

TEST(DynamixelProtocol, EncodesThePublishedInstructionPackets) {
  EXPECT_EQ(encode_instruction(1, instruction::kPing), kPing);
  EXPECT_EQ(encode_instruction(1, instruction::kRead, read_params(132, 4)), kReadPosition);
  EXPECT_EQ(encode_instruction(1, instruction::kWrite, write_params(116, to_le(512, 4))),
            kWriteGoal);
  EXPECT_EQ(encode_status(1, 0, Bytes{0x06, 0x04, 0x26}), kPingStatus);
  EXPECT_EQ(encode_status(1, 0), kWriteStatus);
}

TEST(DynamixelProtocol, DecodesThePublishedStatusPackets) {
  auto d = decode(kPingStatus);
  ASSERT_EQ(d.status, DecodeResult::Status::kPacket);
  EXPECT_EQ(d.consumed, kPingStatus.size());
  EXPECT_EQ(d.packet.id, 1);
  EXPECT_EQ(d.packet.instruction, instruction::kStatus);
  EXPECT_EQ(d.packet.error, 0);
  EXPECT_EQ(from_le(std::span(d.packet.params).first(2)), 1030u);  // XM430-W210
  EXPECT_EQ(d.packet.params[2], 0x26);
  d = decode(kReadStatus);
  ASSERT_EQ(d.status, DecodeResult::Status::kPacket);
  EXPECT_EQ(from_le(d.packet.params), 166u);
  d = decode(kWriteGoal);  // instruction packets decode too (the fake servo uses this)
  ASSERT_EQ(d.status, DecodeResult::Status::kPacket);
  EXPECT_EQ(d.packet.instruction, instruction::kWrite);
  EXPECT_EQ(d.packet.params, (Bytes{0x74, 0x00, 0x00, 0x02, 0x00, 0x00}));
}

TEST(DynamixelProtocol, ByteStuffingInsertsFdAfterAHeaderPatternAndRoundTrips) {
  const Bytes payload = {0x03, 0xFF, 0xFF, 0xFD, 0x01, 0xFF, 0xFF, 0xFD};
  const Bytes stuffed = stuff(payload);
  EXPECT_EQ(stuffed, (Bytes{0x03, 0xFF, 0xFF, 0xFD, 0xFD, 0x01, 0xFF, 0xFF, 0xFD, 0xFD}));
  EXPECT_EQ(unstuff(stuffed), payload);
  // The length field counts the stuffed bytes; decoding restores the parameters.
  const Bytes data = {0xFF, 0xFF, 0xFD, 0x00};
  const Bytes packet = encode_instruction(7, instruction::kWrite, write_params(0xFDFF, data));
  EXPECT_EQ(packet[5] | (packet[6] << 8),
            1 + 2 + 4 + 1 + 2);  // instruction, address, data, stuffing, CRC
  const auto d = decode(packet);
  ASSERT_EQ(d.status, DecodeResult::Status::kPacket);
  EXPECT_EQ(d.packet.params, write_params(0xFDFF, data));
}

TEST(DynamixelProtocol, StreamDecodingSkipsNoiseWaitsForMoreAndRejectsBadCrc) {
  Bytes stream = {0x00, 0x12, 0xFF};
  stream.insert(stream.end(), kPingStatus.begin(), kPingStatus.begin() + 9);
  auto d = decode(stream);
  EXPECT_EQ(d.status, DecodeResult::Status::kIncomplete);
  EXPECT_EQ(d.consumed, 3u);  // the noise before the header
  stream.insert(stream.end(), kPingStatus.begin() + 9, kPingStatus.end());
  d = decode(stream);
  ASSERT_EQ(d.status, DecodeResult::Status::kPacket);
  EXPECT_EQ(d.consumed, stream.size());

  Bytes bad = kReadStatus;
  bad[9] ^= 0x40;  // corrupt the data
  d = decode(bad);
  EXPECT_EQ(d.status, DecodeResult::Status::kBadCrc);
  EXPECT_EQ(d.consumed, bad.size());

  // A trailing partial header is kept for the next read.
  d = decode(Bytes{0x01, 0x02, 0xFF, 0xFF});
  EXPECT_EQ(d.status, DecodeResult::Status::kIncomplete);
  EXPECT_EQ(d.consumed, 2u);
}

TEST(DynamixelProtocol, DescribesStatusErrorBits) {
  EXPECT_EQ(describe_status_error(0x00), "no error");
  EXPECT_EQ(describe_status_error(0x07), "access error");
  EXPECT_EQ(describe_status_error(0x03), "CRC error");
  EXPECT_THAT(describe_status_error(0x84), ::testing::HasSubstr("data range error"));
  EXPECT_THAT(describe_status_error(0x84), ::testing::HasSubstr("hardware alert"));
}

TEST(DynamixelProtocol, LittleEndianHelpers) {
  EXPECT_EQ(to_le(0x12345678, 4), (Bytes{0x78, 0x56, 0x34, 0x12}));
  EXPECT_EQ(from_le(Bytes{0x78, 0x56, 0x34, 0x12}), 0x12345678u);
  EXPECT_EQ(static_cast<std::int32_t>(from_le(to_le(static_cast<std::uint32_t>(-300), 4))), -300);
}

}  // namespace
}  // namespace ferret::tether::dxl
