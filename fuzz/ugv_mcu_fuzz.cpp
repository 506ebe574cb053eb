// A receive stream from the miniUGV's MCU (or the host, as the MCU sees it) -> frames,
// as HwUgvBase consumes it: decode() in a loop, dropping `consumed` bytes, and the same
// bytes through a FrameReader fed in chunks whose sizes the input's first byte picks.
// Invariants: decode never consumes past the buffer and always consumes on a verdict;
// both paths find the same frames; every frame re-encodes to its own bytes; every
// payload that decodes encodes back to the same bytes.
#include <cstdint>
#include <cstdlib>
#include <span>
#include <vector>

#include "ferret/ugv/ugv_mcu_protocol.hpp"

namespace mcu = ferret::ugv::mcu;

namespace {

void check_payload(const mcu::Frame& f) {
  const std::vector<std::uint8_t>& p = f.payload;
  std::vector<std::uint8_t> again;
  bool decoded = true;
  switch (f.type) {
    case mcu::type::kDrive:
      if (const auto d = mcu::decode_drive(p))
        again = mcu::encode_payload(*d);
      else
        decoded = false;
      break;
    case mcu::type::kEpm:
      if (const auto e = mcu::decode_epm(p))
        again = mcu::encode_payload(*e);
      else
        decoded = false;
      break;
    case mcu::type::kInfo:
      if (const auto i = mcu::decode_info(p))
        again = mcu::encode_payload(*i);
      else
        decoded = false;
      break;
    case mcu::type::kState:
      if (const auto s = mcu::decode_state(p))
        again = mcu::encode_payload(*s);
      else
        decoded = false;
      break;
    default:
      decoded = false;
  }
  if (decoded && again != p) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t chunk = 1 + data[0] % 32;
  const std::span<const std::uint8_t> stream(data + 1, size - 1);

  std::vector<mcu::Frame> direct;
  std::span<const std::uint8_t> rest = stream;
  while (!rest.empty()) {
    const mcu::DecodeResult r = mcu::decode(rest);
    if (r.consumed > rest.size()) std::abort();  // would read past the buffer
    if (r.status == mcu::DecodeResult::Status::kIncomplete) break;
    if (r.consumed == 0) std::abort();  // a verdict always consumes bytes
    if (r.status == mcu::DecodeResult::Status::kFrame ||
        r.status == mcu::DecodeResult::Status::kBadVersion) {
      const auto bytes = mcu::encode_frame(r.frame);
      if (bytes.size() > r.consumed ||
          !std::equal(bytes.begin(), bytes.end(), rest.begin() + (r.consumed - bytes.size())))
        std::abort();  // a frame is exactly the bytes it was decoded from
      if (r.status == mcu::DecodeResult::Status::kFrame) {
        if (r.frame.payload.size() > mcu::kMaxPayloadSize) std::abort();
        check_payload(r.frame);
        direct.push_back(r.frame);
      }
    }
    rest = rest.subspan(r.consumed);
  }

  mcu::FrameReader reader;
  std::vector<mcu::Frame> streamed;
  for (std::size_t at = 0; at < stream.size(); at += chunk) {
    reader.push(stream.subspan(at, std::min(chunk, stream.size() - at)));
    while (const auto ev = reader.next())
      if (ev->status == mcu::DecodeResult::Status::kFrame) streamed.push_back(ev->frame);
  }
  if (streamed.size() != direct.size()) std::abort();
  for (std::size_t i = 0; i < direct.size(); ++i)
    if (streamed[i].type != direct[i].type || streamed[i].seq != direct[i].seq ||
        streamed[i].payload != direct[i].payload)
      std::abort();
  if (reader.stats().frames != direct.size()) std::abort();
  return 0;
}
