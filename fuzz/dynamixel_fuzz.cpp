// A Dynamixel Protocol 2.0 receive stream -> packets, as the bus consumes it: decode,
// drop `consumed` bytes, decode again, until the decoder waits for more bytes. Each
// decoded packet must encode back to bytes that decode to the same packet.
#include <cstdint>
#include <cstdlib>
#include <span>

#include "ferret/tether_model/dynamixel_protocol.hpp"

namespace dxl = ferret::tether::dxl;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::span<const std::uint8_t> rest(data, size);
  while (!rest.empty()) {
    const dxl::DecodeResult r = dxl::decode(rest);
    if (r.consumed > rest.size()) std::abort();  // would read past the buffer
    if (r.status == dxl::DecodeResult::Status::kIncomplete) break;
    if (r.consumed == 0) std::abort();  // a packet or an error always consumes bytes
    if (r.status == dxl::DecodeResult::Status::kPacket) {
      const dxl::Packet& p = r.packet;
      const auto bytes = p.instruction == dxl::instruction::kStatus
                             ? dxl::encode_status(p.id, p.error, p.params)
                             : dxl::encode_instruction(p.id, p.instruction, p.params);
      const dxl::DecodeResult again = dxl::decode(bytes);
      if (again.status != dxl::DecodeResult::Status::kPacket || again.consumed != bytes.size() ||
          again.packet.id != p.id || again.packet.instruction != p.instruction ||
          again.packet.error != p.error || again.packet.params != p.params)
        std::abort();
    }
    rest = rest.subspan(r.consumed);
  }
  return 0;
}
