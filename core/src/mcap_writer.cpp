#include "ferret/core/mcap_writer.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace ferret {
namespace {

constexpr std::string_view kMagic{"\x89MCAP0\r\n", 8};
enum Op : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

// Little-endian fields, the MCAP way.
template <class T>
void put(std::string& s, T v) {
  for (std::size_t i = 0; i < sizeof(T); ++i)
    s.push_back(static_cast<char>((static_cast<std::uint64_t>(v) >> (8 * i)) & 0xff));
}
void put_string(std::string& s, std::string_view v) {
  put<std::uint32_t>(s, static_cast<std::uint32_t>(v.size()));
  s.append(v);
}
void put_record(std::string& s, std::uint8_t op, std::string_view content) {
  put<std::uint8_t>(s, op);
  put<std::uint64_t>(s, content.size());
  s.append(content);
}

}  // namespace

McapWriter::McapWriter(std::string profile, std::string library, std::size_t chunk_bytes)
    : chunk_bytes_(std::max<std::size_t>(chunk_bytes, 1)) {
  out_.append(kMagic);
  std::string header;
  put_string(header, profile);
  put_string(header, library);
  put_record(out_, kHeader, header);
}

std::uint16_t McapWriter::add_schema(const std::string& name, const std::string& encoding,
                                     const std::string& data) {
  const std::uint16_t id = next_schema_++;
  std::string r;
  put<std::uint16_t>(r, id);
  put_string(r, name);
  put_string(r, encoding);
  put_string(r, data);  // uint32 length-prefixed bytes, as a string is
  put_record(out_, kSchema, r);
  put_record(schemas_, kSchema, r);
  return id;
}

std::uint16_t McapWriter::add_channel(std::uint16_t schema_id, const std::string& topic,
                                      const std::string& message_encoding,
                                      const std::map<std::string, std::string>& metadata) {
  const std::uint16_t id = next_channel_++;
  std::string r;
  put<std::uint16_t>(r, id);
  put<std::uint16_t>(r, schema_id);
  put_string(r, topic);
  put_string(r, message_encoding);
  std::string map;
  for (const auto& [k, v] : metadata) {
    put_string(map, k);
    put_string(map, v);
  }
  put<std::uint32_t>(r, static_cast<std::uint32_t>(map.size()));
  r += map;
  put_record(out_, kChannel, r);
  put_record(channels_, kChannel, r);
  channel_counts_[id];  // a channel without messages still counts with 0
  return id;
}

void McapWriter::add_message(std::uint16_t channel_id, std::uint64_t log_time_ns,
                             std::string_view data) {
  if (finished_) throw std::logic_error("McapWriter: add_message after finish");
  if (channel_id == 0 || channel_id >= next_channel_)
    throw std::invalid_argument("McapWriter: unknown channel " + std::to_string(channel_id));
  if (chunk_.empty()) chunk_start_ns_ = chunk_end_ns_ = log_time_ns;
  chunk_start_ns_ = std::min(chunk_start_ns_, log_time_ns);
  chunk_end_ns_ = std::max(chunk_end_ns_, log_time_ns);
  chunk_index_[channel_id].emplace_back(log_time_ns, chunk_.size());
  std::string r;
  put<std::uint16_t>(r, channel_id);
  put<std::uint32_t>(r, sequence_[channel_id]++);
  put<std::uint64_t>(r, log_time_ns);
  put<std::uint64_t>(r, log_time_ns);
  r.append(data);
  put_record(chunk_, kMessage, r);
  if (message_count_ == 0) start_ns_ = end_ns_ = log_time_ns;
  start_ns_ = std::min(start_ns_, log_time_ns);
  end_ns_ = std::max(end_ns_, log_time_ns);
  ++message_count_;
  ++channel_counts_[channel_id];
  if (chunk_.size() >= chunk_bytes_) close_chunk();
}

void McapWriter::close_chunk() {
  if (chunk_.empty()) return;
  ChunkIndex index{chunk_start_ns_, chunk_end_ns_, out_.size(), 0, 0, chunk_.size(), {}};
  std::string r;
  put<std::uint64_t>(r, chunk_start_ns_);
  put<std::uint64_t>(r, chunk_end_ns_);
  put<std::uint64_t>(r, chunk_.size());
  put<std::uint32_t>(r, crc32(chunk_));
  put_string(r, "");  // no compression
  put<std::uint64_t>(r, chunk_.size());
  r += chunk_;
  put_record(out_, kChunk, r);
  index.length = out_.size() - index.offset;
  const std::size_t indexes_start = out_.size();
  for (const auto& [channel, entries] : chunk_index_) {
    index.index_offsets[channel] = out_.size();
    std::string m;
    put<std::uint16_t>(m, channel);
    put<std::uint32_t>(m, static_cast<std::uint32_t>(entries.size() * 16));
    for (const auto& [t, offset] : entries) {
      put<std::uint64_t>(m, t);
      put<std::uint64_t>(m, offset);
    }
    put_record(out_, kMessageIndex, m);
  }
  index.index_length = out_.size() - indexes_start;
  chunks_.push_back(std::move(index));
  chunk_.clear();
  chunk_index_.clear();
}

std::string McapWriter::finish() {
  if (finished_) throw std::logic_error("McapWriter: finish twice");
  close_chunk();
  finished_ = true;
  std::string data_end;
  put<std::uint32_t>(data_end, crc32(out_));  // everything before the Data End record
  put_record(out_, kDataEnd, data_end);

  // Summary: grouped by opcode, each group's place kept for the summary offsets.
  const std::uint64_t summary_start = out_.size();
  std::vector<std::tuple<std::uint8_t, std::uint64_t, std::uint64_t>> groups;
  auto group = [&](std::uint8_t op, const std::string& records) {
    if (records.empty()) return;
    groups.emplace_back(op, out_.size(), records.size());
    out_ += records;
  };
  group(kSchema, schemas_);
  group(kChannel, channels_);
  std::string stats;
  {
    std::string r;
    put<std::uint64_t>(r, message_count_);
    put<std::uint16_t>(r, static_cast<std::uint16_t>(next_schema_ - 1));
    put<std::uint32_t>(r, static_cast<std::uint32_t>(next_channel_ - 1));
    put<std::uint32_t>(r, 0);  // attachments
    put<std::uint32_t>(r, 0);  // metadata
    put<std::uint32_t>(r, static_cast<std::uint32_t>(chunks_.size()));
    put<std::uint64_t>(r, start_ns_);
    put<std::uint64_t>(r, end_ns_);
    put<std::uint32_t>(r, static_cast<std::uint32_t>(channel_counts_.size() * 10));
    for (const auto& [channel, count] : channel_counts_) {
      put<std::uint16_t>(r, channel);
      put<std::uint64_t>(r, count);
    }
    put_record(stats, kStatistics, r);
  }
  group(kStatistics, stats);
  std::string chunk_indexes;
  for (const ChunkIndex& c : chunks_) {
    std::string r;
    put<std::uint64_t>(r, c.start_ns);
    put<std::uint64_t>(r, c.end_ns);
    put<std::uint64_t>(r, c.offset);
    put<std::uint64_t>(r, c.length);
    put<std::uint32_t>(r, static_cast<std::uint32_t>(c.index_offsets.size() * 10));
    for (const auto& [channel, offset] : c.index_offsets) {
      put<std::uint16_t>(r, channel);
      put<std::uint64_t>(r, offset);
    }
    put<std::uint64_t>(r, c.index_length);
    put_string(r, "");
    put<std::uint64_t>(r, c.size);  // compressed = uncompressed: no compression
    put<std::uint64_t>(r, c.size);
    put_record(chunk_indexes, kChunkIndex, r);
  }
  group(kChunkIndex, chunk_indexes);

  const std::uint64_t summary_offset_start = out_.size();
  for (const auto& [op, start, length] : groups) {
    std::string r;
    put<std::uint8_t>(r, op);
    put<std::uint64_t>(r, start);
    put<std::uint64_t>(r, length);
    put_record(out_, kSummaryOffset, r);
  }
  // Footer: the CRC covers the summary through the footer's summary_offset_start.
  std::string footer;
  put<std::uint8_t>(footer, kFooter);
  put<std::uint64_t>(footer, 20);
  put<std::uint64_t>(footer, summary_start);
  put<std::uint64_t>(footer, summary_offset_start);
  const std::string_view summary(out_.data() + summary_start, out_.size() - summary_start);
  put<std::uint32_t>(footer, crc32(footer, crc32(summary)));
  out_ += footer;
  out_.append(kMagic);
  return std::move(out_);
}

}  // namespace ferret
