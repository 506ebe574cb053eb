// The miniUGV MCU protocol against fixed byte vectors (computed by hand with an
// independent CRC, in Python, not by the encoder under test), and the stream reader's
// resynchronisation after noise, bad CRCs, bad lengths and other versions.
#include "ferret/ugv/ugv_mcu_protocol.hpp"

#include <gtest/gtest.h>

#include <string_view>
#include <vector>

namespace ferret::ugv::mcu {
namespace {

using Bytes = std::vector<std::uint8_t>;
using Status = DecodeResult::Status;

// DRIVE, seq 7, left +250 mm/s, right -150 mm/s.
const Bytes kDrive = {0xA5, 0x5A, 0x01, 0x01, 0x07, 0x04, 0xFA, 0x00, 0x6A, 0xFF, 0x3C, 0x82};
// STATE, seq 200: t 123456 ms, ticks -5 / 70000, roll 1.50, pitch -2.00, yaw 90.00 deg,
// 7.4 V, 64 %, EPM on + contact, IR fault, ir_seq 9, ranges 500 mm, none, 1234 mm.
const Bytes kState = {0xA5, 0x5A, 0x01, 0x81, 0xC8, 0x20, 0x40, 0xE2, 0x01, 0x00,
                      0xFB, 0xFF, 0xFF, 0xFF, 0x70, 0x11, 0x01, 0x00, 0x96, 0x00,
                      0x38, 0xFF, 0x28, 0x23, 0xE8, 0x1C, 0x40, 0x03, 0x10, 0x00,
                      0x09, 0x03, 0xF4, 0x01, 0xFF, 0xFF, 0xD2, 0x04, 0x67, 0x0D};
// A version-2 frame (type 0x81, two payload bytes), CRC right.
const Bytes kVersion2 = {0xA5, 0x5A, 0x02, 0x81, 0x01, 0x02, 0x01, 0x02, 0x76, 0x06};

Bytes cat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

TEST(UgvMcuProtocol, CrcIsCcittFalse) {
  constexpr std::string_view kCheck = "123456789";
  const Bytes b(kCheck.begin(), kCheck.end());
  EXPECT_EQ(crc16_ccitt(b), 0x29B1);
}

TEST(UgvMcuProtocol, EncodesADriveFrameByteForByte) {
  EXPECT_EQ(encode_drive(7, {250, -150}), kDrive);
}

TEST(UgvMcuProtocol, EncodesAStateFrameByteForByte) {
  McuState s;
  s.mcu_time_ms = 123456;
  s.left_ticks = -5;
  s.right_ticks = 70000;
  s.roll_cdeg = 150;
  s.pitch_cdeg = -200;
  s.yaw_cdeg = 9000;
  s.battery_mv = 7400;
  s.battery_percent = 64;
  s.flags = flag::kEpmOn | flag::kContact;
  s.faults = fault::kIr;
  s.ir_seq = 9;
  s.ir_mm = {500, kIrNoReturn, 1234};
  EXPECT_EQ(encode_state(200, s), kState);
}

TEST(UgvMcuProtocol, DecodesAStateFrameFromFixedBytes) {
  const DecodeResult r = decode(kState);
  ASSERT_EQ(r.status, Status::kFrame);
  EXPECT_EQ(r.consumed, kState.size());
  EXPECT_EQ(r.frame.type, type::kState);
  EXPECT_EQ(r.frame.seq, 200);
  const auto s = decode_state(r.frame.payload);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->mcu_time_ms, 123456u);
  EXPECT_EQ(s->left_ticks, -5);
  EXPECT_EQ(s->right_ticks, 70000);
  EXPECT_EQ(s->roll_cdeg, 150);
  EXPECT_EQ(s->pitch_cdeg, -200);
  EXPECT_EQ(s->yaw_cdeg, 9000);
  EXPECT_EQ(s->battery_mv, 7400);
  EXPECT_EQ(s->battery_percent, 64);
  EXPECT_EQ(s->flags, flag::kEpmOn | flag::kContact);
  EXPECT_EQ(s->faults, fault::kIr);
  EXPECT_EQ(s->ir_seq, 9);
  EXPECT_EQ(s->ir_mm, (std::vector<std::uint16_t>{500, kIrNoReturn, 1234}));
  EXPECT_EQ(describe_faults(s->faults), "ir");
}

TEST(UgvMcuProtocol, DecodesADriveFrameFromFixedBytes) {
  const DecodeResult r = decode(kDrive);
  ASSERT_EQ(r.status, Status::kFrame);
  const auto d = decode_drive(r.frame.payload);
  ASSERT_TRUE(d);
  EXPECT_EQ(d->left_mmps, 250);
  EXPECT_EQ(d->right_mmps, -150);
}

TEST(UgvMcuProtocol, SkipsNoiseBeforeASyncPair) {
  const Bytes stream = cat({{0x00, 0x13, 0xA5, 0x77, 0x5A}, kDrive});
  const DecodeResult r = decode(stream);
  ASSERT_EQ(r.status, Status::kFrame);
  EXPECT_EQ(r.consumed, stream.size());
}

TEST(UgvMcuProtocol, IncompleteFramesWaitAndKeepAHalfSync) {
  for (std::size_t n = 1; n < kDrive.size(); ++n) {
    const Bytes part(kDrive.begin(), kDrive.begin() + static_cast<long>(n));
    const DecodeResult r = decode(part);
    EXPECT_EQ(r.status, Status::kIncomplete) << n;
    EXPECT_EQ(r.consumed, 0u) << n;  // nothing of a frame in progress is dropped
  }
  const DecodeResult half = decode(Bytes{0x01, 0x02, 0xA5});
  EXPECT_EQ(half.status, Status::kIncomplete);
  EXPECT_EQ(half.consumed, 2u);  // the A5 may start a sync pair
}

TEST(UgvMcuProtocol, ABadCrcDropsOnlyTheSyncByte) {
  Bytes bad = kDrive;
  bad[7] ^= 0x01;
  const DecodeResult r = decode(bad);
  EXPECT_EQ(r.status, Status::kBadCrc);
  EXPECT_EQ(r.consumed, 1u);
}

TEST(UgvMcuProtocol, ALengthBeyondTheMaximumIsRejectedBeforeTheCrc) {
  const Bytes header = {0xA5, 0x5A, 0x01, 0x81, 0x00, 0x41};  // 65 payload bytes
  const DecodeResult r = decode(header);
  EXPECT_EQ(r.status, Status::kBadLength);
  EXPECT_EQ(r.consumed, 1u);
}

TEST(UgvMcuProtocol, AnotherVersionIsReportedAsSuch) {
  const DecodeResult r = decode(kVersion2);
  EXPECT_EQ(r.status, Status::kBadVersion);
  EXPECT_EQ(r.frame.version, 2);
  EXPECT_EQ(r.consumed, kVersion2.size());
}

TEST(UgvMcuProtocol, PayloadsOfTheWrongLengthOrValueAreRefused) {
  EXPECT_FALSE(decode_drive(Bytes{1, 2, 3}));
  EXPECT_FALSE(decode_epm(Bytes{2}));
  EXPECT_FALSE(decode_epm(Bytes{}));
  EXPECT_TRUE(decode_epm(Bytes{1})->on);
  EXPECT_FALSE(decode_info(Bytes{1, 2, 3, 4, 5}));
  EXPECT_FALSE(decode_info(Bytes{1, 2, 17, 0, 1, 50}));  // 17 IR sensors: more than a STATE holds
  Bytes state(kState.begin() + kHeaderSize, kState.end() - kCrcSize);
  ASSERT_TRUE(decode_state(state));
  state.back() = 0;
  state.pop_back();  // one range byte short of the count
  EXPECT_FALSE(decode_state(state));
  Bytes wrong_count(kState.begin() + kHeaderSize, kState.end() - kCrcSize);
  wrong_count[25] = 4;  // says 4 ranges, carries 3
  EXPECT_FALSE(decode_state(wrong_count));
}

TEST(UgvMcuProtocol, ReaderResynchronisesAfterGarbageAndFalseSyncs) {
  // Noise, a false sync pair whose "frame" swallows the real DRIVE's first bytes (its
  // CRC fails), a bad length, a frame of another version, then two good frames.
  Bytes corrupt = kState;
  corrupt[20] ^= 0x40;
  const Bytes stream = cat({{0x11, 0xA5, 0x5A, 0x01, 0x01, 0x00, 0x03},
                            kDrive,
                            corrupt,
                            {0xA5, 0x5A, 0x01, 0x81, 0x00, 0xFF},
                            kVersion2,
                            kState,
                            kDrive});
  FrameReader reader;
  std::vector<DecodeResult> events;
  // Byte by byte, as a slow link delivers them: the same events as all at once.
  for (const std::uint8_t b : stream) {
    reader.push(std::span(&b, 1));
    while (auto ev = reader.next()) events.push_back(*ev);
  }
  ASSERT_EQ(events.size(), 4u);
  EXPECT_EQ(events[0].frame.type, type::kDrive);
  EXPECT_EQ(events[1].status, Status::kBadVersion);
  EXPECT_EQ(events[2].frame.type, type::kState);
  EXPECT_EQ(events[3].frame.type, type::kDrive);
  EXPECT_EQ(reader.stats().frames, 3u);
  EXPECT_EQ(reader.stats().bad_version, 1u);
  EXPECT_EQ(reader.stats().last_bad_version, 2);
  EXPECT_GE(reader.stats().bad_crc, 2u);  // the false sync and the corrupt STATE
  EXPECT_GE(reader.stats().bad_length, 1u);

  FrameReader at_once;
  at_once.push(stream);
  int frames = 0;
  while (auto ev = at_once.next()) frames += ev->status == Status::kFrame;
  EXPECT_EQ(frames, 3);
}

TEST(UgvMcuProtocol, EveryMessageRoundTrips) {
  McuInfo info{2, 7, 3, 300, 50};
  const DecodeResult r = decode(encode_info(3, info));
  ASSERT_EQ(r.status, Status::kFrame);
  const auto back = decode_info(r.frame.payload);
  ASSERT_TRUE(back);
  EXPECT_EQ(back->firmware_major, 2);
  EXPECT_EQ(back->watchdog_ms, 300);
  EXPECT_EQ(back->state_rate_hz, 50);
  EXPECT_EQ(decode(encode_hello(9)).frame.payload.size(), 0u);
  EXPECT_TRUE(decode_epm(decode(encode_epm(1, {true})).frame.payload)->on);
  EXPECT_EQ(type_name(type::kState), "STATE");
  EXPECT_EQ(type_name(0x44), "0x44");
  EXPECT_EQ(describe_faults(fault::kMotorLeft | fault::kEpm | 0x8000), "motor_left, epm, bit15");
}

}  // namespace
}  // namespace ferret::ugv::mcu
