#include "ferret/link/codec.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "ferret/core/crc32.hpp"
#include "link/random_messages.hpp"

namespace ferret::link {
namespace {

using Bytes = std::vector<std::uint8_t>;
using Reason = Rejection::Reason;

// The frames below are written out byte by byte (docs/link.md's tables); their CRCs
// come from Python's zlib.crc32, not from ferret. If the wire format changes, these
// tests fail: change the version and the docs with it.

UgvTelemetry fixed_telemetry() {
  UgvTelemetry t;
  t.t_s = 2.0;
  t.x_m = 1.0;
  t.y_m = -1.0;
  t.yaw_rad = 0.5;
  t.vx_mps = 0.5f;
  t.vy_mps = -0.5f;
  t.ax_mps2 = 0.25f;
  t.ay_mps2 = 0.0f;
  t.mode = UgvMode::kExplore;
  t.outcome = UgvOutcome::kNone;
  t.epm_on = true;
  t.object_held = false;
  t.wants_retraction = true;
  t.battery_fraction = 0.75f;
  t.tether_anchor_x_m = 0.5;
  t.tether_anchor_y_m = 0.25;
  t.tether_to_anchor_m = 1.0;
  t.tether_uncertainty_m = 0.25f;
  t.roll_rad = 0.0f;
  t.pitch_rad = 0.0f;
  t.last_request_id = 9;
  t.plan = {{0.0625f, 1.0f, 0.5f, 0.5f, 0.0f}};
  return t;
}

const Bytes kTelemetryFrame = {
    0x46, 0x4c,                                      // magic "FL"
    0x03,                                            // version 3
    0x01,                                            // type: telemetry
    0x02,                                            // sender: ugv
    0x04, 0x03, 0x02, 0x01,                          // sequence 0x01020304
    0x74, 0x00,                                      // payload length 116
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x40,  // t_s 2.0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf0, 0x3f,  // x_m 1.0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf0, 0xbf,  // y_m -1.0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xe0, 0x3f,  // yaw_rad 0.5
    0x00, 0x00, 0x00, 0x3f,                          // vx_mps 0.5f
    0x00, 0x00, 0x00, 0xbf,                          // vy_mps -0.5f
    0x00, 0x00, 0x80, 0x3e,                          // ax_mps2 0.25f
    0x00, 0x00, 0x00, 0x00,                          // ay_mps2 0
    0x01,                                            // mode: explore
    0x00,                                            // outcome: none
    0x05,                                            // flags: epm_on | wants_retraction
    0x00, 0x00, 0x40, 0x3f,                          // battery_fraction 0.75f
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xe0, 0x3f,  // tether_anchor_x_m 0.5
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xd0, 0x3f,  // tether_anchor_y_m 0.25
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf0, 0x3f,  // tether_to_anchor_m 1.0
    0x00, 0x00, 0x80, 0x3e,                          // tether_uncertainty_m 0.25f
    0x00, 0x00, 0x00, 0x00,                          // roll_rad 0
    0x00, 0x00, 0x00, 0x00,                          // pitch_rad 0
    0x09, 0x00, 0x00, 0x00,                          // last_request_id 9
    0x01,                                            // plan_count 1
    0x00, 0x00, 0x80, 0x3d,                          // plan[0].dt_s 0.0625f
    0x00, 0x00, 0x80, 0x3f,                          // plan[0].x_m 1.0f
    0x00, 0x00, 0x00, 0x3f,                          // plan[0].y_m 0.5f
    0x00, 0x00, 0x00, 0x3f,                          // plan[0].vx_mps 0.5f
    0x00, 0x00, 0x00, 0x00,                          // plan[0].vy_mps 0
    0x75, 0xfd, 0xb7, 0x6f,                          // CRC-32
};

UavRequest fixed_request() {
  UavRequest r;
  r.request_id = 1;
  r.kind = UavRequest::Kind::kStartSearch;
  r.entry_x_m = 2.0;
  r.entry_y_m = -1.0;
  r.entry_z_m = 0.5;
  r.entry_yaw_rad = 0.25;
  r.reason = "go";
  return r;
}

const Bytes kRequestFrame = {
    0x46, 0x4c, 0x03,
    0x02,                                            // type: request
    0x01,                                            // sender: uav
    0x01, 0x00, 0x00, 0x00,                          // sequence 1
    0x28, 0x00,                                      // payload length 40
    0x01, 0x00, 0x00, 0x00,                          // request_id 1
    0x01,                                            // kind: start_search
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x40,  // entry_x_m 2.0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf0, 0xbf,  // entry_y_m -1.0
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xe0, 0x3f,  // entry_z_m 0.5
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xd0, 0x3f,  // entry_yaw_rad 0.25
    0x02, 'g',  'o',                                 // reason: length, bytes
    0x79, 0x6e, 0xec, 0x24,                          // CRC-32
};

const Bytes kAckFrame = {
    0x46, 0x4c, 0x03,
    0x03,                    // type: ack
    0x02,                    // sender: ugv
    0x02, 0x00, 0x00, 0x00,  // sequence 2
    0x04, 0x00,              // payload length 4
    0x03, 0x00, 0x00, 0x00,  // request_id 3
    0x8e, 0xf0, 0x77, 0x4b,  // CRC-32
};

const Bytes kHeartbeatFrame = {
    0x46, 0x4c, 0x03,
    0x04,                                            // type: heartbeat
    0x01,                                            // sender: uav
    0x07, 0x00, 0x00, 0x00,                          // sequence 7
    0x10, 0x00,                                      // payload length 16
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf8, 0x3f,  // t_s 1.5
    0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xf4, 0x3f,  // ugv_telemetry_t_s 1.25
    0x4a, 0x12, 0xa0, 0x07,                          // CRC-32
};

TEST(LinkCodec, EncodesEachMessageToItsDocumentedBytes) {
  EXPECT_EQ(encode(0x01020304, fixed_telemetry()), kTelemetryFrame);
  EXPECT_EQ(encode(1, fixed_request()), kRequestFrame);
  EXPECT_EQ(encode(2, Ack{3}), kAckFrame);
  EXPECT_EQ(encode(7, Heartbeat{1.5, 1.25}), kHeartbeatFrame);
}

TEST(LinkCodec, DecodesTheDocumentedBytes) {
  const auto expect_frame = [](const Bytes& bytes, std::uint32_t sequence, const Message& message) {
    const DecodeResult r = decode(bytes);
    ASSERT_TRUE(r.ok()) << r.rejection().message();
    EXPECT_EQ(r.frame().sequence, sequence);
    EXPECT_EQ(r.frame().message, message);
    EXPECT_EQ(r.frame().sender(), sender_of(type_of(message)));
  };
  expect_frame(kTelemetryFrame, 0x01020304, fixed_telemetry());
  expect_frame(kRequestFrame, 1, fixed_request());
  expect_frame(kAckFrame, 2, Ack{3});
  expect_frame(kHeartbeatFrame, 7, Heartbeat{1.5, 1.25});
}

TEST(LinkCodec, FrameSizesAreTheBandwidthTablesBytes) {
  UgvTelemetry t;
  EXPECT_EQ(encoded_size(t), 111u);
  t.plan.assign(UgvTelemetry::kMaxPlanSamples, PlanSample{});
  for (std::size_t i = 0; i < t.plan.size(); ++i)
    t.plan[i].dt_s = 0.05f * static_cast<float>(i + 1);
  EXPECT_EQ(encoded_size(t), 311u);
  EXPECT_EQ(encode(0, t).size(), 311u);
  UavRequest r;
  r.request_id = 1;
  EXPECT_EQ(encoded_size(r), 53u);
  r.reason = std::string(200, 'x');
  EXPECT_EQ(encoded_size(r), 53u + UavRequest::kMaxReasonBytes);
  EXPECT_EQ(encoded_size(Ack{1}), 19u);
  EXPECT_EQ(encoded_size(Heartbeat{}), 31u);
}

TEST(LinkCodec, EveryMessageRoundTripsExactly) {
  Rng rng(42);
  for (int i = 0; i < 2000; ++i) {
    const Message m = testing::random_message(rng);
    const auto sequence = static_cast<std::uint32_t>(rng.next_u64());
    const DecodeResult r = decode(encode(sequence, m));
    ASSERT_TRUE(r.ok()) << r.rejection().message();
    EXPECT_EQ(r.frame().sequence, sequence);
    EXPECT_EQ(r.frame().message, m);
  }
}

TEST(LinkCodec, AFullPlanPreviewAndTheRangeEdgesRoundTrip) {
  UgvTelemetry t = fixed_telemetry();
  t.plan.clear();
  for (std::size_t i = 0; i < UgvTelemetry::kMaxPlanSamples; ++i)
    t.plan.push_back(
        {0.05f * static_cast<float>(i + 1), 0.1f * static_cast<float>(i), -0.3f, 1.25f, -2.0f});
  // The ends of the ranges are in them; -0 stays -0 (the bytes are the bits).
  t.x_m = -1e5;
  t.y_m = -0.0;
  t.battery_fraction = 0.0f;
  t.yaw_rad = -2 * 3.141592653589793;
  t.mode = UgvMode::kDone;
  t.outcome = UgvOutcome::kRecalled;
  t.epm_on = t.object_held = t.wants_retraction = true;
  const DecodeResult r = decode(encode(9, t));
  ASSERT_TRUE(r.ok()) << r.rejection().message();
  const auto& back = std::get<UgvTelemetry>(r.frame().message);
  EXPECT_EQ(back, t);
  EXPECT_TRUE(std::signbit(back.y_m));
  ASSERT_EQ(back.plan.size(), 10u);
  EXPECT_EQ(back.plan[9].dt_s, 0.5f);
}

TEST(LinkCodec, TheReasonIsCutAtACharacterBoundaryAndAtBadBytes) {
  UavRequest r;
  r.request_id = 5;
  r.kind = UavRequest::Kind::kAbort;
  // 62 ASCII bytes, then a 3-byte character that would end at byte 65: it is left out
  // whole rather than cut into an invalid sequence.
  r.reason = std::string(62, 'a') + "\xe2\x82\xac" + "tail";
  auto back = std::get<UavRequest>(decode(encode(1, r)).frame().message);
  EXPECT_EQ(back.reason, std::string(62, 'a'));
  r.reason = std::string(60, 'a') + "\xe2\x82\xac" + "tail";  // the character fits: 63 bytes
  back = std::get<UavRequest>(decode(encode(1, r)).frame().message);
  EXPECT_EQ(back.reason, std::string(60, 'a') + "\xe2\x82\xac");
  r.reason = "low battery \xff then more";
  back = std::get<UavRequest>(decode(encode(1, r)).frame().message);
  EXPECT_EQ(back.reason, "low battery ");
  EXPECT_EQ(wire_reason(""), "");
}

TEST(LinkCodec, EncodeRefusesWhatAReceiverWouldDropNamingTheField) {
  UgvTelemetry t;
  t.vx_mps = std::numeric_limits<float>::quiet_NaN();
  try {
    (void)encode(1, t);
    FAIL() << "a NaN velocity was encoded";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("telemetry.vx_mps: expected a finite number"),
              std::string::npos)
        << e.what();
  }
  t = UgvTelemetry{};
  t.plan.assign(11, PlanSample{});
  EXPECT_THROW((void)encode(1, t), std::invalid_argument);
  EXPECT_THROW((void)encode(1, Ack{0}), std::invalid_argument);  // ids start at 1
  const auto rejection = validate(UavRequest{});                 // request_id 0
  ASSERT_TRUE(rejection.has_value());
  EXPECT_EQ(rejection->field, "request.request_id");
  EXPECT_FALSE(validate(fixed_telemetry()).has_value());
}

// ------------------------------------------------------------------ rejections

// Recomputes the CRC of a frame whose payload a test changed on purpose, so that the
// field check, not the checksum, is what refuses it.
Bytes reseal(Bytes frame) {
  frame.resize(frame.size() - kCrcBytes);
  const std::uint32_t crc = crc32(frame);
  for (int i = 0; i < 4; ++i) frame.push_back(static_cast<std::uint8_t>(crc >> (8 * i)));
  return frame;
}
template <class F>
Bytes put_float(Bytes frame, std::size_t at, F value) {
  const auto bits =
      std::bit_cast<std::conditional_t<sizeof(F) == 8, std::uint64_t, std::uint32_t>>(value);
  for (std::size_t i = 0; i < sizeof(F); ++i)
    frame[at + i] = static_cast<std::uint8_t>(bits >> (8 * i));
  return reseal(frame);
}
Bytes with_byte(Bytes frame, std::size_t at, std::uint8_t value, bool seal = true) {
  frame[at] = value;
  return seal ? reseal(frame) : frame;
}

// Offsets in the telemetry frame (header 11 bytes + the payload offset in docs/link.md).
constexpr std::size_t kTelX = 11 + 8, kTelVx = 11 + 32, kTelMode = 11 + 48, kTelOutcome = 11 + 49,
                      kTelFlags = 11 + 50, kTelBattery = 11 + 51, kTelRoll = 11 + 83,
                      kTelPlanCount = 11 + 95, kTelPlan0Dt = 11 + 96;

void expect_rejected(const Bytes& bytes, Reason reason, const std::string& field,
                     const std::string& in_message = {}) {
  const DecodeResult r = decode(bytes);
  ASSERT_FALSE(r.ok()) << "accepted, expected " << to_string(reason) << " at " << field;
  EXPECT_EQ(to_string(r.rejection().reason), to_string(reason)) << r.rejection().message();
  EXPECT_EQ(r.rejection().field, field) << r.rejection().message();
  if (!in_message.empty()) {
    EXPECT_NE(r.rejection().message().find(in_message), std::string::npos)
        << r.rejection().message();
  }
}

TEST(LinkCodecRejects, ShortBuffersAsTruncated) {
  expect_rejected({}, Reason::kTruncated, "frame");
  expect_rejected(Bytes(kHeartbeatFrame.begin(), kHeartbeatFrame.begin() + 14), Reason::kTruncated,
                  "frame", "at least 15 bytes");
  // Every proper prefix of a frame is refused, and none is read past (ASan builds check).
  for (const Bytes* frame : {&kTelemetryFrame, &kRequestFrame, &kAckFrame, &kHeartbeatFrame})
    for (std::size_t n = 0; n < frame->size(); ++n) {
      const DecodeResult r = decode(std::span(frame->data(), n));
      ASSERT_FALSE(r.ok()) << n;
      EXPECT_EQ(r.rejection().reason, Reason::kTruncated) << n << ": " << r.rejection().message();
    }
}

TEST(LinkCodecRejects, AnotherProtocolAsBadMagic) {
  expect_rejected(with_byte(kAckFrame, 0, 'G'), Reason::kBadMagic, "header.magic", "(got 47 4c)");
  expect_rejected(with_byte(kAckFrame, 1, 0x00), Reason::kBadMagic, "header.magic");
  expect_rejected(Bytes{'x'}, Reason::kBadMagic, "header.magic");  // even one byte says so
}

TEST(LinkCodecRejects, OtherVersionsNamingTheVersion) {
  expect_rejected(with_byte(kHeartbeatFrame, 2, 1), Reason::kUnknownVersion, "header.version",
                  "header.version: expected protocol version 3 (got version 1)");
  expect_rejected(with_byte(kHeartbeatFrame, 2, 0), Reason::kUnknownVersion, "header.version",
                  "(got version 0)");
  expect_rejected(Bytes{'F', 'L', 9}, Reason::kUnknownVersion, "header.version");
}

TEST(LinkCodecRejects, UnknownTypesAndSendersThatDoNotSendTheType) {
  expect_rejected(with_byte(kAckFrame, 3, 0), Reason::kUnknownType, "header.type");
  expect_rejected(with_byte(kAckFrame, 3, 5), Reason::kUnknownType, "header.type");
  expect_rejected(with_byte(kAckFrame, 4, 1), Reason::kBadSender, "header.sender",
                  "2 (ugv), the sender of ack");
  expect_rejected(with_byte(kHeartbeatFrame, 4, 2), Reason::kBadSender, "header.sender");
  expect_rejected(with_byte(kHeartbeatFrame, 4, 0), Reason::kBadSender, "header.sender");
}

TEST(LinkCodecRejects, LengthsThatDoNotAddUp) {
  Bytes longer = kAckFrame;
  longer.push_back(0);
  expect_rejected(longer, Reason::kLengthMismatch, "frame", "19 bytes");
  // A payload length that promises fewer bytes than the fields need, resealed: the
  // fields do not fit.
  Bytes short_payload = {0x46, 0x4c, 0x03, 0x03, 0x02, 0x02, 0x00, 0x00, 0x00,
                         0x02, 0x00, 0x03, 0x00, 0,    0,    0,    0};
  expect_rejected(reseal(short_payload), Reason::kLengthMismatch, "header.payload_length",
                  "room for ack.request_id");
  // One that promises more than the fields: a byte left over.
  Bytes long_payload = {0x46, 0x4c, 0x03, 0x03, 0x02, 0x02, 0x00, 0x00, 0x00, 0x05,
                        0x00, 0x03, 0x00, 0x00, 0x00, 0x00, 0,    0,    0,    0};
  expect_rejected(reseal(long_payload), Reason::kLengthMismatch, "header.payload_length",
                  "4 bytes for this ack");
  // A heartbeat as version 2 had it (the UAV's time alone), under this version's
  // number: the echo of the telemetry is missing.
  Bytes old_heartbeat(kHeartbeatFrame.begin(), kHeartbeatFrame.begin() + 19);
  old_heartbeat[9] = 0x08;
  old_heartbeat.insert(old_heartbeat.end(), {0, 0, 0, 0});
  expect_rejected(reseal(old_heartbeat), Reason::kLengthMismatch, "header.payload_length",
                  "room for heartbeat.ugv_telemetry_t_s");
  // A plan count above what the payload holds.
  expect_rejected(with_byte(kTelemetryFrame, kTelPlanCount, 2), Reason::kLengthMismatch,
                  "header.payload_length", "telemetry.plan[1].dt_s");
}

TEST(LinkCodecRejects, DamagedBytesByTheirCrc) {
  expect_rejected(with_byte(kTelemetryFrame, kTelX, 0x01, /*seal=*/false), Reason::kCrcMismatch,
                  "crc");
  // The CRC's last byte 4b -> ab.
  expect_rejected(with_byte(kAckFrame, 18, 0xab, /*seal=*/false), Reason::kCrcMismatch, "crc",
                  "(got 0xab77f08e)");
}

TEST(LinkCodecRejects, NanAndInfinityNamingTheField) {
  expect_rejected(put_float(kTelemetryFrame, kTelVx, std::numeric_limits<float>::quiet_NaN()),
                  Reason::kNotFinite, "telemetry.vx_mps",
                  "telemetry.vx_mps: expected a finite number (got nan)");
  expect_rejected(put_float(kTelemetryFrame, kTelX, std::numeric_limits<double>::infinity()),
                  Reason::kNotFinite, "telemetry.x_m", "(got inf)");
  expect_rejected(put_float(kHeartbeatFrame, 11, -std::numeric_limits<double>::infinity()),
                  Reason::kNotFinite, "heartbeat.t_s");
  expect_rejected(put_float(kHeartbeatFrame, 19, std::numeric_limits<double>::quiet_NaN()),
                  Reason::kNotFinite, "heartbeat.ugv_telemetry_t_s");
  expect_rejected(put_float(kTelemetryFrame, kTelPlan0Dt, std::numeric_limits<float>::quiet_NaN()),
                  Reason::kNotFinite, "telemetry.plan[0].dt_s");
}

TEST(LinkCodecRejects, NumbersOutsideTheirRange) {
  expect_rejected(put_float(kTelemetryFrame, kTelBattery, 1.5f), Reason::kOutOfRange,
                  "telemetry.battery_fraction", "expected a number in [0, 1] (got 1.5)");
  expect_rejected(put_float(kTelemetryFrame, kTelX, 2e5), Reason::kOutOfRange, "telemetry.x_m");
  expect_rejected(put_float(kTelemetryFrame, kTelRoll, 4.0f), Reason::kOutOfRange,
                  "telemetry.roll_rad");
  expect_rejected(put_float(kHeartbeatFrame, 11, -1.0), Reason::kOutOfRange, "heartbeat.t_s");
  expect_rejected(put_float(kHeartbeatFrame, 19, -1.0), Reason::kOutOfRange,
                  "heartbeat.ugv_telemetry_t_s", "expected a number in [0, 1e9] s (got -1)");
  expect_rejected(put_float(kHeartbeatFrame, 19, 2e9), Reason::kOutOfRange,
                  "heartbeat.ugv_telemetry_t_s");
  expect_rejected(with_byte(kTelemetryFrame, kTelPlanCount, 11), Reason::kOutOfRange,
                  "telemetry.plan_count", "at most 10 plan samples (got 11)");
  Bytes zero_id = kAckFrame;
  zero_id[11] = 0;
  expect_rejected(reseal(zero_id), Reason::kOutOfRange, "ack.request_id");
  // Two plan samples out of time order.
  UgvTelemetry t = fixed_telemetry();
  t.plan.push_back(t.plan[0]);
  Bytes two = kTelemetryFrame;
  two.resize(two.size() - kCrcBytes);
  two[kTelPlanCount] = 2;
  two[9] = static_cast<std::uint8_t>(two[9] + 20);  // payload length
  two.insert(two.end(), two.begin() + kTelPlan0Dt, two.begin() + kTelPlan0Dt + 20);
  two.resize(two.size() + kCrcBytes);
  expect_rejected(reseal(two), Reason::kOutOfRange, "telemetry.plan[1].dt_s",
                  "samples in time order");
  EXPECT_EQ(validate(t)->field, "telemetry.plan[1].dt_s");  // the sender's check agrees
}

TEST(LinkCodecRejects, EnumAndFlagValuesNotDefined) {
  expect_rejected(with_byte(kTelemetryFrame, kTelMode, 8), Reason::kBadEnum, "telemetry.mode",
                  "expected 0 (idle) to 7 (done) (got 8)");
  expect_rejected(with_byte(kTelemetryFrame, kTelOutcome, 11), Reason::kBadEnum,
                  "telemetry.outcome");
  expect_rejected(with_byte(kTelemetryFrame, kTelFlags, 0x08), Reason::kBadEnum, "telemetry.flags",
                  "(got 0x08)");
  expect_rejected(with_byte(kRequestFrame, 15, 0), Reason::kBadEnum, "request.kind",
                  "1 (start_search) to 5 (abort)");
  expect_rejected(with_byte(kRequestFrame, 15, 6), Reason::kBadEnum, "request.kind");
}

TEST(LinkCodecRejects, ReasonsTooLongOrNotUtf8) {
  Bytes bad_utf8 = kRequestFrame;
  bad_utf8[49] = 0xc3;  // 'g' -> a lead byte followed by 'o': not UTF-8
  expect_rejected(reseal(bad_utf8), Reason::kBadText, "request.reason", "UTF-8 text");
  // A length byte of 64 with 64 bytes there: longer than any sender writes.
  Bytes long_reason(kRequestFrame.begin(), kRequestFrame.begin() + 48);
  long_reason.push_back(64);
  long_reason.insert(long_reason.end(), 64, 'r');
  long_reason[9] = 38 + 64;
  long_reason.resize(long_reason.size() + kCrcBytes);
  expect_rejected(reseal(long_reason), Reason::kBadText, "request.reason",
                  "at most 63 bytes (got 64 bytes)");
}

TEST(LinkCodecRejects, TheMessageIsOnePrintableLine) {
  Bytes bad_utf8 = kRequestFrame;
  bad_utf8[49] = 0xc3;
  const DecodeResult r = decode(reseal(bad_utf8));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.rejection().message(), "request.reason: expected UTF-8 text (got \\xc3o)");
}

// ------------------------------------------------------------------ corruption

TEST(LinkCodecCorruption, NoneOfAHundredThousandDamagedFramesIsAccepted) {
  // The 10^6 figure in docs/link.md comes from bench/link_corruption_bench.cpp with the
  // same campaign; this smaller one runs in every build.
  const auto c = testing::run_corruption_campaign(100'000, 2024);
  EXPECT_EQ(c.trials, 100'000u);
  EXPECT_EQ(c.accepted, 0u);
  for (std::size_t k = 0; k < kCorruptionKinds; ++k)
    EXPECT_GT(c.by_kind[k], 20'000u)
        << to_string(static_cast<Corruption>(k));  // each kind is exercised
  EXPECT_GT(c.by_reason[static_cast<std::size_t>(Reason::kCrcMismatch)], 0u);
  EXPECT_GT(c.by_reason[static_cast<std::size_t>(Reason::kTruncated)], 0u);
  EXPECT_GT(c.by_reason[static_cast<std::size_t>(Reason::kLengthMismatch)], 0u);
}

}  // namespace
}  // namespace ferret::link
