#include "ferret/link/serial_framing.hpp"

#include <algorithm>
#include <array>

#include "ferret/link/serial_port.hpp"

namespace ferret::link {
namespace {

std::size_t skip(Resync resync, const FrameScan& s, const FrameFormat& f) {
  switch (resync) {
    case Resync::kNextByte:
      return s.start + 1;
    case Resync::kPastSync:
      return s.start + f.sync.size();
    case Resync::kPastFrame:
      // A bad length gives no frame to skip: past the sync instead.
      return s.start + (s.size > 0 ? s.size : f.sync.size());
  }
  return s.start + 1;
}

}  // namespace

FrameScan find_frame(std::span<const std::uint8_t> buffer, const FrameFormat& format) {
  FrameScan r;
  const std::span<const std::uint8_t> sync(format.sync);
  std::size_t start = 0;
  while (start + sync.size() <= buffer.size() &&
         !std::equal(sync.begin(), sync.end(), buffer.begin() + static_cast<long>(start)))
    ++start;
  if (start + sync.size() > buffer.size()) {
    // No whole sync: keep a tail that may be the start of one.
    std::size_t keep = 0;
    for (std::size_t k = std::min(sync.size() - 1, buffer.size()); k > 0; --k) {
      if (std::equal(buffer.end() - static_cast<long>(k), buffer.end(), sync.begin())) {
        keep = k;
        break;
      }
    }
    r.consumed = buffer.size() - keep;
    return r;
  }
  r.start = start;
  r.consumed = start;  // the noise before the sync
  const std::size_t header_size = format.header_size();
  if (buffer.size() < start + header_size) return r;
  const auto header = buffer.subspan(start, header_size);
  std::size_t length = 0;
  for (std::size_t i = 0; i < format.length_bytes; ++i)
    length |= static_cast<std::size_t>(header[format.length_offset + i]) << (8 * i);
  if (format.length_ok && !format.length_ok(header, length)) {
    r.status = FrameScan::Status::kBadLength;
    r.consumed = skip(format.after_bad_length, r, format);
    return r;
  }
  const std::size_t total = format.overhead + length;
  if (buffer.size() < start + total) return r;
  const auto frame = buffer.subspan(start, total);
  const std::uint16_t expected =
      format.checksum(frame.subspan(format.checksum_from, total - 2 - format.checksum_from));
  const auto got = static_cast<std::uint16_t>(frame[total - 2] | (frame[total - 1] << 8));
  r.size = total;
  if (expected != got) {
    r.status = FrameScan::Status::kBadChecksum;
    r.consumed = skip(format.after_bad_checksum, r, format);
    return r;
  }
  r.status = FrameScan::Status::kFrame;
  r.consumed = start + total;
  return r;
}

void FrameReader::push(std::span<const std::uint8_t> bytes) {
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
  stats_.bytes += bytes.size();
}

std::optional<FrameEvent> FrameReader::next() {
  using Status = FrameScan::Status;
  while (!buffer_.empty()) {
    const FrameScan s = find_frame(buffer_, format_);
    FrameEvent e{s.status, {}};
    if (s.status == Status::kFrame) {
      stats_.noise_bytes += s.start;
      ++stats_.frames;
      e.bytes.assign(buffer_.begin() + static_cast<long>(s.start),
                     buffer_.begin() + static_cast<long>(s.start + s.size));
    } else {
      stats_.noise_bytes += s.consumed;
      if (s.status == Status::kBadChecksum) ++stats_.bad_checksum;
      if (s.status == Status::kBadLength) ++stats_.bad_length;
    }
    buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<long>(s.consumed));
    if (s.status != Status::kIncomplete) return e;
    // Whatever is left is the start of a frame: it waits for more bytes.
    return std::nullopt;
  }
  return std::nullopt;
}

std::size_t FrameReader::receive(SerialPort& port, int timeout_ms) {
  std::array<std::uint8_t, 512> chunk{};
  const std::size_t n = port.read_some(chunk, timeout_ms);
  push(std::span(chunk).first(n));
  return n;
}

std::optional<FrameEvent> FrameReader::read(SerialPort& port, Clock::time_point deadline) {
  while (true) {
    if (auto e = next()) return e;
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(deadline - Clock::now());
    if (left.count() <= 0) return std::nullopt;
    (void)receive(port, static_cast<int>(left.count()));
  }
}

}  // namespace ferret::link
