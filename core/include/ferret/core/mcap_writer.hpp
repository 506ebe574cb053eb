#pragma once
// A writer of MCAP files (https://mcap.dev/spec), the log format Foxglove opens. No
// MCAP library is packaged for Debian, and the format is small: this writes what a
// log needs and nothing more — schemas and channels in the data section, messages in
// uncompressed chunks each followed by its message indexes, and a summary (schemas,
// channels, statistics, chunk indexes) with summary offsets, so readers can seek by
// time and topic. Every CRC is filled in. The file is built in memory and handed back
// whole: the caller writes it through an OutputSet (all or nothing).

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/core/crc32.hpp"  // every MCAP record group carries a CRC-32

namespace ferret {

class McapWriter {
 public:
  /// @param profile  the MCAP profile ("" for none; Foxglove's JSON messages need none)
  /// @param library  who wrote the file
  /// @param chunk_bytes  a chunk is closed once its records pass this size
  McapWriter(std::string profile, std::string library, std::size_t chunk_bytes = 1 << 20);

  /// Registers a schema; returns its id (from 1).
  std::uint16_t add_schema(const std::string& name, const std::string& encoding,
                           const std::string& data);
  /// Registers a channel on a schema (0: none); returns its id (from 1).
  std::uint16_t add_channel(std::uint16_t schema_id, const std::string& topic,
                            const std::string& message_encoding,
                            const std::map<std::string, std::string>& metadata = {});
  /// One message; times in nanoseconds (publish time = log time). Messages may come in
  /// any time order; each chunk and the statistics keep the earliest and latest.
  /// @throws std::invalid_argument for a channel that was not added
  void add_message(std::uint16_t channel_id, std::uint64_t log_time_ns, std::string_view data);

  [[nodiscard]] std::uint64_t message_count() const { return message_count_; }
  /// Closes the file and returns its bytes; the writer is spent afterwards.
  [[nodiscard]] std::string finish();

 private:
  struct ChunkIndex {
    std::uint64_t start_ns, end_ns, offset, length, index_length, size;
    std::map<std::uint16_t, std::uint64_t> index_offsets;
  };
  void close_chunk();

  std::string out_;                 ///< the file so far (magic, header, data section)
  std::string schemas_, channels_;  ///< their records, again for the summary
  std::uint16_t next_schema_ = 1, next_channel_ = 1;
  std::size_t chunk_bytes_;
  std::string chunk_;  ///< records of the open chunk
  std::map<std::uint16_t, std::vector<std::pair<std::uint64_t, std::uint64_t>>> chunk_index_;
  std::uint64_t chunk_start_ns_ = 0, chunk_end_ns_ = 0;
  std::vector<ChunkIndex> chunks_;
  std::map<std::uint16_t, std::uint64_t> channel_counts_;
  std::map<std::uint16_t, std::uint32_t> sequence_;
  std::uint64_t message_count_ = 0, start_ns_ = 0, end_ns_ = 0;
  bool finished_ = false;
};

}  // namespace ferret
