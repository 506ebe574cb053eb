#include "ferret/link/serial_framing.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <deque>
#include <string>
#include <thread>
#include <vector>

#include "ferret/link/serial_port.hpp"

namespace ferret::link {
namespace {

using Bytes = std::vector<std::uint8_t>;
using Status = FrameScan::Status;

// A toy protocol: sync AA 55, a length byte (payload bytes), the payload, and a checksum
// that is the byte sum over length .. payload, little endian.
std::uint16_t sum16(std::span<const std::uint8_t> bytes) {
  std::uint16_t s = 0;
  for (const std::uint8_t b : bytes) s = static_cast<std::uint16_t>(s + b);
  return s;
}

FrameFormat toy_format(Resync after_bad_checksum = Resync::kNextByte) {
  FrameFormat f;
  f.sync = {0xAA, 0x55};
  f.length_offset = 2;
  f.length_bytes = 1;
  f.overhead = 5;  // sync, length, checksum
  f.checksum_from = 2;
  f.checksum = sum16;
  f.length_ok = [](std::span<const std::uint8_t>, std::size_t length) { return length <= 8; };
  f.after_bad_checksum = after_bad_checksum;
  return f;
}

Bytes toy_frame(const Bytes& payload) {
  Bytes out;
  out.reserve(payload.size() + 5);
  for (const std::uint8_t b : {std::uint8_t{0xAA}, std::uint8_t{0x55}}) out.push_back(b);
  out.push_back(static_cast<std::uint8_t>(payload.size()));
  for (const std::uint8_t b : payload) out.push_back(b);
  const std::uint16_t sum = sum16(std::span(out).subspan(2));
  out.push_back(static_cast<std::uint8_t>(sum & 0xFF));
  out.push_back(static_cast<std::uint8_t>(sum >> 8));
  return out;
}

Bytes cat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const Bytes& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// A port that hands out scripted reads, one chunk a call, then times out.
class ScriptedPort final : public SerialPort {
 public:
  explicit ScriptedPort(std::deque<Bytes> chunks) : chunks_(std::move(chunks)) {}
  void write(std::span<const std::uint8_t>) override {}
  std::size_t read_some(std::span<std::uint8_t> buffer, int timeout_ms) override {
    ++reads;
    if (chunks_.empty()) {
      waited_ms += timeout_ms;
      std::this_thread::sleep_for(std::chrono::milliseconds(timeout_ms));
      return 0;
    }
    Bytes& c = chunks_.front();
    const std::size_t n = std::min(buffer.size(), c.size());
    std::copy_n(c.begin(), n, buffer.begin());
    c.erase(c.begin(), c.begin() + static_cast<long>(n));
    if (c.empty()) chunks_.pop_front();
    return n;
  }
  void discard_input() override { chunks_.clear(); }
  const std::string& name() const override { return name_; }

  int reads = 0;
  int waited_ms = 0;

 private:
  std::deque<Bytes> chunks_;
  std::string name_ = "scripted";
};

TEST(SerialFraming, FindsAFrameAfterGarbage) {
  const Bytes frame = toy_frame({1, 2, 3});
  const Bytes stream = cat({{0x00, 0x55, 0xAA, 0x13}, frame});
  const FrameScan s = find_frame(stream, toy_format());
  ASSERT_EQ(s.status, Status::kFrame);
  EXPECT_EQ(s.start, 4u);
  EXPECT_EQ(s.size, frame.size());
  EXPECT_EQ(s.consumed, stream.size());
}

TEST(SerialFraming, KeepsAPartialSyncAndAnIncompleteFrame) {
  // Garbage then the first sync byte: the garbage goes, the AA stays.
  FrameScan s = find_frame(Bytes{0x01, 0x02, 0xAA}, toy_format());
  EXPECT_EQ(s.status, Status::kIncomplete);
  EXPECT_EQ(s.consumed, 2u);
  // A header without its payload: nothing of it is dropped.
  const Bytes frame = toy_frame({9, 9, 9, 9});
  s = find_frame(std::span(frame).first(frame.size() - 1), toy_format());
  EXPECT_EQ(s.status, Status::kIncomplete);
  EXPECT_EQ(s.consumed, 0u);
}

TEST(SerialFraming, RejectsAnImpossibleLengthBeforeTheChecksum) {
  const FrameScan s = find_frame(Bytes{0xAA, 0x55, 200}, toy_format());
  EXPECT_EQ(s.status, Status::kBadLength);
  EXPECT_EQ(s.consumed, 1u);  // kNextByte
}

TEST(SerialFraming, ResyncAfterABadChecksumSkipsAsTheFormatSays) {
  Bytes bad = toy_frame({4, 5});
  bad[3] ^= 0x01;
  FrameScan s = find_frame(bad, toy_format(Resync::kNextByte));
  EXPECT_EQ(s.status, Status::kBadChecksum);
  EXPECT_EQ(s.consumed, 1u);
  s = find_frame(bad, toy_format(Resync::kPastSync));
  EXPECT_EQ(s.consumed, 2u);
  s = find_frame(bad, toy_format(Resync::kPastFrame));
  EXPECT_EQ(s.consumed, bad.size());
}

TEST(SerialFraming, AFalseSyncInNoiseDoesNotSwallowTheFrameAfterIt) {
  // AA 55 03 in the noise claims the next 5 bytes: the real frame's start. Its checksum
  // fails, the search resumes one byte later and finds the real frame.
  const Bytes frame = toy_frame({7});
  FrameReader reader(toy_format());
  reader.push(cat({{0xAA, 0x55, 0x03}, frame}));
  auto e = reader.next();
  ASSERT_TRUE(e);
  EXPECT_EQ(e->status, Status::kBadChecksum);
  e = reader.next();
  ASSERT_TRUE(e);
  ASSERT_EQ(e->status, Status::kFrame);
  EXPECT_EQ(e->bytes, frame);
  EXPECT_FALSE(reader.next());
  EXPECT_EQ(reader.stats().frames, 1u);
  EXPECT_EQ(reader.stats().bad_checksum, 1u);
  EXPECT_EQ(reader.stats().noise_bytes, 3u);
}

TEST(SerialFraming, ABadChecksumThenAGoodFrame) {
  Bytes bad = toy_frame({1, 2, 3});
  bad[4] ^= 0x80;
  const Bytes good = toy_frame({1, 2, 3});
  ScriptedPort port({cat({bad, good})});
  FrameReader reader(toy_format());
  const auto deadline = FrameReader::Clock::now() + std::chrono::seconds(5);
  auto e = reader.read(port, deadline);
  ASSERT_TRUE(e);
  EXPECT_EQ(e->status, Status::kBadChecksum);
  e = reader.read(port, deadline);
  ASSERT_TRUE(e);
  ASSERT_EQ(e->status, Status::kFrame);
  EXPECT_EQ(e->bytes, good);
}

TEST(SerialFraming, AFrameSplitAcrossReadsComesWhole) {
  const Bytes frame = toy_frame({10, 20, 30, 40, 50});
  // Garbage, then the frame in three reads: the sync split, then the payload split.
  ScriptedPort port({{0x42, 0x43, 0xAA}, {0x55, 5, 10, 20}, {30, 40, 50, frame[8], frame[9]}});
  FrameReader reader(toy_format());
  const auto e = reader.read(port, FrameReader::Clock::now() + std::chrono::seconds(5));
  ASSERT_TRUE(e);
  ASSERT_EQ(e->status, Status::kFrame);
  EXPECT_EQ(e->bytes, frame);
  EXPECT_EQ(port.reads, 3);
  EXPECT_EQ(reader.stats().bytes, 2u + frame.size());
  EXPECT_EQ(reader.stats().noise_bytes, 2u);
}

TEST(SerialFraming, ReadStopsAtTheDeadline) {
  // Half a frame, then silence: no verdict, and the reader gives up at the deadline.
  const Bytes frame = toy_frame({1, 2, 3});
  ScriptedPort port({Bytes(frame.begin(), frame.begin() + 4)});
  FrameReader reader(toy_format());
  const auto t0 = FrameReader::Clock::now();
  const auto e = reader.read(port, t0 + std::chrono::milliseconds(30));
  const auto took = FrameReader::Clock::now() - t0;
  EXPECT_FALSE(e);
  EXPECT_GE(took, std::chrono::milliseconds(30));
  EXPECT_LT(took, std::chrono::seconds(2));
  EXPECT_GE(port.waited_ms, 29);
  // The half frame waits for its rest.
  reader.push(std::span(frame).subspan(4));
  const auto rest = reader.next();
  ASSERT_TRUE(rest);
  EXPECT_EQ(rest->bytes, frame);
}

TEST(SerialFraming, ADeadlineInThePastReadsNothing) {
  ScriptedPort port({toy_frame({1})});
  FrameReader reader(toy_format());
  EXPECT_FALSE(reader.read(port, FrameReader::Clock::now() - std::chrono::milliseconds(1)));
  EXPECT_EQ(port.reads, 0);
}

TEST(SerialFraming, TwoByteLittleEndianLength) {
  // A Dynamixel-like layout: a 2-byte length at offset 3 that counts the checksum.
  FrameFormat f;
  f.sync = {0xFF, 0xFD};
  f.length_offset = 3;
  f.length_bytes = 2;
  f.overhead = 5;
  f.checksum_from = 0;
  f.checksum = sum16;
  Bytes frame{0xFF, 0xFD, 0x07, 0x03, 0x01, 0x33};  // id 7, length 259 = 0x0103
  frame.resize(5 + 259 - 2, 0x11);
  const std::uint16_t sum = sum16(frame);
  frame.push_back(static_cast<std::uint8_t>(sum & 0xFF));
  frame.push_back(static_cast<std::uint8_t>(sum >> 8));
  const FrameScan s = find_frame(frame, f);
  ASSERT_EQ(s.status, Status::kFrame);
  EXPECT_EQ(s.size, 5u + 259u);
}

TEST(SerialPort, AMissingDeviceIsNamed) {
  try {
    (void)open_serial_port("/dev/ttyUSB_ferret_missing", 57600);
    FAIL() << "expected SerialError";
  } catch (const SerialError& e) {
    EXPECT_NE(std::string(e.what()).find("/dev/ttyUSB_ferret_missing"), std::string::npos);
  }
  EXPECT_THROW((void)open_serial_port("/dev/ttyUSB_ferret_missing", 0), SerialError);
}

}  // namespace
}  // namespace ferret::link
