#include "ferret/core/mcap_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "ferret/core/foxglove_log.hpp"

namespace ferret {
namespace {

// A minimal reader for the test: records as (opcode, offset of content, length).
template <class T>
T get(const std::string& s, std::size_t at) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < sizeof(T); ++i)
    v |= static_cast<std::uint64_t>(static_cast<std::uint8_t>(s.at(at + i))) << (8 * i);
  return static_cast<T>(v);
}
struct Record {
  std::uint8_t op;
  std::size_t at, length, start;
};
std::vector<Record> records(const std::string& s, std::size_t from, std::size_t to) {
  std::vector<Record> out;
  while (from < to) {
    const auto op = get<std::uint8_t>(s, from);
    const auto len = get<std::uint64_t>(s, from + 1);
    out.push_back({op, from + 9, static_cast<std::size_t>(len), from});
    from += 9 + len;
  }
  EXPECT_EQ(from, to);
  return out;
}

TEST(McapWriter, WritesChunksIndexesSummaryAndCrcsAReaderCanFollow) {
  McapWriter w("", "test", 64);  // small chunks: several of them
  const auto schema = w.add_schema("foo.Bar", "jsonschema", "{}");
  const auto a = w.add_channel(schema, "/a", "json", {{"k", "v"}});
  const auto b = w.add_channel(schema, "/b", "json");
  for (int k = 0; k < 10; ++k)
    w.add_message(k % 3 ? a : b, 1000u * (10 - k), "{\"k\":" + std::to_string(k) + "}");
  EXPECT_THROW(w.add_message(7, 0, "x"), std::invalid_argument);
  const std::string f = w.finish();

  const std::string magic("\x89MCAP0\r\n", 8);
  ASSERT_GT(f.size(), 16u);
  EXPECT_EQ(f.substr(0, 8), magic);
  EXPECT_EQ(f.substr(f.size() - 8), magic);
  const auto all = records(f, 8, f.size() - 8);
  EXPECT_EQ(all.front().op, 0x01);  // Header
  const Record footer = all.back();
  ASSERT_EQ(footer.op, 0x02);
  ASSERT_EQ(footer.length, 20u);
  const auto summary_start = get<std::uint64_t>(f, footer.at);
  const auto summary_offset_start = get<std::uint64_t>(f, footer.at + 8);
  // The footer's CRC: summary start through summary_offset_start.
  EXPECT_EQ(get<std::uint32_t>(f, footer.at + 16),
            crc32(std::string_view(f).substr(summary_start, footer.at + 16 - summary_start)));

  // Data End's CRC covers everything before it.
  const auto data_end =
      std::find_if(all.begin(), all.end(), [](const Record& r) { return r.op == 0x0F; });
  ASSERT_NE(data_end, all.end());
  EXPECT_EQ(get<std::uint32_t>(f, data_end->at),
            crc32(std::string_view(f).substr(0, data_end->start)));
  EXPECT_EQ(std::next(data_end)->start, summary_start);

  // Chunks: their CRC, and every message index entry points at a message of its channel
  // with its time.
  int chunks = 0, messages = 0;
  std::map<std::size_t, std::size_t> chunk_records_at;  // chunk start -> records offset
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (all[k].op != 0x06) continue;
    ++chunks;
    const Record& c = all[k];
    const auto size = get<std::uint64_t>(f, c.at + 16);
    const auto crc = get<std::uint32_t>(f, c.at + 24);
    const auto compression_len = get<std::uint32_t>(f, c.at + 28);
    EXPECT_EQ(compression_len, 0u);
    const std::size_t recs = c.at + 32 + 8;
    EXPECT_EQ(get<std::uint64_t>(f, c.at + 32), size);
    EXPECT_EQ(crc, crc32(std::string_view(f).substr(recs, size)));
    const auto inner = records(f, recs, recs + size);
    messages += static_cast<int>(inner.size());
    for (std::size_t m = k + 1; m < all.size() && all[m].op == 0x07; ++m) {
      const auto channel = get<std::uint16_t>(f, all[m].at);
      const auto bytes = get<std::uint32_t>(f, all[m].at + 2);
      for (std::size_t e = 0; e < bytes / 16; ++e) {
        const auto t = get<std::uint64_t>(f, all[m].at + 6 + 16 * e);
        const auto off = get<std::uint64_t>(f, all[m].at + 6 + 16 * e + 8);
        ASSERT_EQ(get<std::uint8_t>(f, recs + off), 0x05);
        EXPECT_EQ(get<std::uint16_t>(f, recs + off + 9), channel);
        EXPECT_EQ(get<std::uint64_t>(f, recs + off + 9 + 6), t);
      }
    }
  }
  EXPECT_GT(chunks, 1);
  EXPECT_EQ(messages, 10);

  // Summary: schema, channels, statistics, chunk indexes, grouped; offsets point at them.
  std::vector<std::uint8_t> ops;
  for (const auto& r : records(f, summary_start, summary_offset_start)) ops.push_back(r.op);
  ASSERT_FALSE(ops.empty());
  EXPECT_EQ(ops.front(), 0x03);
  // Grouped by opcode: each opcode in one run.
  std::vector<std::uint8_t> runs;
  for (const auto op : ops)
    if (runs.empty() || runs.back() != op) runs.push_back(op);
  std::vector<std::uint8_t> distinct(runs);
  std::sort(distinct.begin(), distinct.end());
  EXPECT_EQ(std::unique(distinct.begin(), distinct.end()), distinct.end());
  EXPECT_EQ(runs.size(), 4u);  // schemas, channels, statistics, chunk indexes
  const auto stats =
      std::find_if(all.begin(), all.end(), [](const Record& r) { return r.op == 0x0B; });
  ASSERT_NE(stats, all.end());
  EXPECT_EQ(get<std::uint64_t>(f, stats->at), 10u);      // messages
  EXPECT_EQ(get<std::uint16_t>(f, stats->at + 8), 1u);   // schemas
  EXPECT_EQ(get<std::uint32_t>(f, stats->at + 10), 2u);  // channels
  EXPECT_EQ(get<std::uint32_t>(f, stats->at + 22), static_cast<std::uint32_t>(chunks));
  EXPECT_EQ(get<std::uint64_t>(f, stats->at + 26), 1000u);   // earliest
  EXPECT_EQ(get<std::uint64_t>(f, stats->at + 34), 10000u);  // latest
  for (const auto& r : records(f, summary_offset_start, footer.start)) {
    ASSERT_EQ(r.op, 0x0E);
    const auto group = get<std::uint8_t>(f, r.at);
    const auto start = get<std::uint64_t>(f, r.at + 1);
    EXPECT_EQ(get<std::uint8_t>(f, start), group);
  }
}

TEST(FoxgloveLog, NamesTheFoxgloveSchemasAndRefusesAGridOfTheWrongSize) {
  FoxgloveLog log;
  log.transform(0.5, "map", "ugv", Pose2{1.0, 2.0, 0.3});
  log.log(1.0, "ugv", "explore -> track");
  EXPECT_THROW(log.grid(1.0, "/g", "map", 0, 0, 0.1, 3, 2, std::vector<std::uint8_t>(5), "v"),
               std::invalid_argument);
  EXPECT_EQ(log.message_count(), 2u);
  const std::string f = log.finish();
  EXPECT_NE(f.find("foxglove.FrameTransform"), std::string::npos);
  EXPECT_NE(f.find("foxglove.Log"), std::string::npos);
  EXPECT_NE(f.find("\"child_frame_id\":\"ugv\""), std::string::npos);
  EXPECT_EQ(to_nanoseconds(1.5), 1500000000u);
  EXPECT_EQ(to_nanoseconds(-1.0), 0u);
  EXPECT_EQ(to_nanoseconds(std::numeric_limits<double>::quiet_NaN()), 0u);
}

}  // namespace
}  // namespace ferret
