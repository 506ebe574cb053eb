#include "ferret/tether_model/dynamixel_bus.hpp"

#include <fmt/format.h>

#include <optional>

#include "ferret/link/serial_framing.hpp"

namespace ferret::tether {

DynamixelBus::DynamixelBus(std::unique_ptr<link::SerialPort> port, Options options)
    : port_(std::move(port)), options_(options) {
  if (!port_) throw SerialError("Dynamixel bus: no serial link");
}

dxl::Packet DynamixelBus::transact(std::uint8_t id, std::uint8_t instruction,
                                   const std::vector<std::uint8_t>& params,
                                   std::size_t expected_params) {
  const auto request = dxl::encode_instruction(id, instruction, params);
  std::string last_problem;
  DynamixelError::Kind last_kind = DynamixelError::Kind::kTimeout;
  for (int attempt = 0; attempt <= options_.retries; ++attempt) {
    if (attempt > 0) ++retried_;
    port_->discard_input();
    port_->write(request);
    link::FrameReader reader(dxl::frame_format());
    const auto deadline =
        link::FrameReader::Clock::now() + std::chrono::milliseconds(options_.timeout_ms);
    while (true) {
      const std::optional<link::FrameEvent> e = reader.read(*port_, deadline);
      if (!e) {
        last_kind = DynamixelError::Kind::kTimeout;
        last_problem = fmt::format("no reply within {} ms", options_.timeout_ms);
        break;
      }
      const dxl::DecodeResult d = e->status == link::FrameScan::Status::kFrame
                                      ? dxl::decode(e->bytes)
                                      : dxl::DecodeResult{};
      if (d.status != dxl::DecodeResult::Status::kPacket) {
        last_kind = DynamixelError::Kind::kCorrupt;
        last_problem = e->status == link::FrameScan::Status::kBadChecksum ? "a reply with a bad CRC"
                                                                          : "a malformed reply";
        break;
      }
      const dxl::Packet& p = d.packet;
      // Half-duplex adapters echo our own request; skip anything that is not a status.
      if (p.instruction != dxl::instruction::kStatus) continue;
      if (p.id != id)
        throw DynamixelError(
            DynamixelError::Kind::kWrongDevice, 0,
            fmt::format("Dynamixel on '{}': asked id {}, id {} answered", port(), id, p.id));
      if (p.error != 0)
        throw DynamixelError(DynamixelError::Kind::kStatus, p.error,
                             fmt::format("Dynamixel id {} on '{}': {} (instruction 0x{:02X})", id,
                                         port(), dxl::describe_status_error(p.error), instruction));
      if (p.params.size() != expected_params) {
        last_kind = DynamixelError::Kind::kCorrupt;
        last_problem = fmt::format("a reply with {} parameter bytes, expected {}", p.params.size(),
                                   expected_params);
        break;
      }
      return p;
    }
  }
  throw DynamixelError(
      last_kind, 0,
      fmt::format(
          "Dynamixel id {} on '{}': {} after {} attempts (instruction 0x{:02X}; check the id, "
          "baud rate, wiring and power)",
          id, port(), last_problem, options_.retries + 1, instruction));
}

PingReply DynamixelBus::ping(std::uint8_t id) {
  const auto p = transact(id, dxl::instruction::kPing, {}, 3);
  return {static_cast<std::uint16_t>(p.params[0] | (p.params[1] << 8)), p.params[2]};
}

std::vector<std::uint8_t> DynamixelBus::read(std::uint8_t id, std::uint16_t address,
                                             std::uint16_t length) {
  return transact(id, dxl::instruction::kRead, dxl::read_params(address, length), length).params;
}

void DynamixelBus::write(std::uint8_t id, std::uint16_t address,
                         const std::vector<std::uint8_t>& data) {
  (void)transact(id, dxl::instruction::kWrite, dxl::write_params(address, data), 0);
}

}  // namespace ferret::tether
