// A robot link datagram (any bytes off the network) -> decode(). A frame that decodes
// must encode back to exactly the bytes it came from: the decoder accepts nothing the
// encoder would not write, so no two byte strings mean the same frame, and a decoded
// message is always one the sender could have sent. A rejection must name a field.
// Mutated bytes almost never keep a valid CRC, so each input is decoded a second time
// with its last four bytes replaced by the CRC of the rest: that is what reaches the
// payload's checks (lengths, ranges, enums, the reason's UTF-8). The same bytes are also
// read as a blob of datagrams the simulated world relays (link::unpack_datagrams).
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "ferret/core/crc32.hpp"
#include "ferret/link/codec.hpp"
#include "ferret/link/message_stream.hpp"

namespace fl = ferret::link;

namespace {

void check(std::span<const std::uint8_t> bytes) {
  const fl::DecodeResult r = fl::decode(bytes);
  if (!r.ok()) {
    if (r.rejection().field.empty() || r.rejection().expected.empty()) std::abort();
    return;
  }
  if (fl::validate(r.frame().message).has_value()) std::abort();  // encode() would refuse it
  const auto again = fl::encode(r.frame().sequence, r.frame().message);
  if (again.size() != bytes.size() || !std::equal(again.begin(), again.end(), bytes.begin()))
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  check(std::span(data, size));
  // The same bytes as a blob of relayed datagrams: unpacked, each is checked as one and
  // packing them again gives the blob back; otherwise only StreamError.
  try {
    const std::vector<std::uint8_t> blob(data, data + size);
    const auto datagrams = fl::unpack_datagrams(blob, 4096);
    if (fl::pack_datagrams(datagrams) != blob) std::abort();
    for (const auto& d : datagrams) check(d);
  } catch (const fl::StreamError&) {
  }
  if (size >= fl::kHeaderBytes + fl::kCrcBytes) {
    std::vector<std::uint8_t> sealed(data, data + size);
    const std::uint32_t crc = ferret::crc32(std::span(sealed).first(size - fl::kCrcBytes));
    for (std::size_t i = 0; i < fl::kCrcBytes; ++i)
      sealed[size - fl::kCrcBytes + i] = static_cast<std::uint8_t>(crc >> (8 * i));
    check(sealed);
  }
  return 0;
}
