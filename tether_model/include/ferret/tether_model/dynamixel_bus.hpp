#pragma once
// A Dynamixel Protocol 2.0 bus master: request/response with a timeout, retries on
// a timeout or a corrupted reply, and errors that say what went wrong (no reply,
// CRC, a status error from the servo, a reply from the wrong id).

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ferret/link/serial_port.hpp"
#include "ferret/tether_model/dynamixel_protocol.hpp"

namespace ferret::tether {

// The bus runs over link's serial port; its error and opener are part of the driver's
// interface (a DynamixelError is a SerialError).
using link::open_serial_port;
using link::SerialError;

/// A failed exchange with a servo.
class DynamixelError : public SerialError {
 public:
  enum class Kind { kTimeout, kCorrupt, kStatus, kWrongDevice };
  DynamixelError(Kind kind, std::uint8_t status_error, const std::string& message)
      : SerialError(message), kind_(kind), status_error_(status_error) {}
  [[nodiscard]] Kind kind() const { return kind_; }
  /// The servo's error byte for kStatus.
  [[nodiscard]] std::uint8_t status_error() const { return status_error_; }

 private:
  Kind kind_;
  std::uint8_t status_error_;
};

struct PingReply {
  std::uint16_t model_number = 0;
  std::uint8_t firmware_version = 0;
};

class DynamixelBus {
 public:
  struct Options {
    int timeout_ms = 30;  ///< per attempt; a reply at 57600 baud takes ~2 ms
    int retries = 2;      ///< extra attempts after a timeout or a corrupted reply
  };

  DynamixelBus(std::unique_ptr<link::SerialPort> port, Options options);

  [[nodiscard]] PingReply ping(std::uint8_t id);
  [[nodiscard]] std::vector<std::uint8_t> read(std::uint8_t id, std::uint16_t address,
                                               std::uint16_t length);
  void write(std::uint8_t id, std::uint16_t address, const std::vector<std::uint8_t>& data);

  [[nodiscard]] std::uint32_t read_u32(std::uint8_t id, std::uint16_t address) {
    return dxl::from_le(read(id, address, 4));
  }
  [[nodiscard]] std::uint16_t read_u16(std::uint8_t id, std::uint16_t address) {
    return static_cast<std::uint16_t>(dxl::from_le(read(id, address, 2)));
  }
  [[nodiscard]] std::uint8_t read_u8(std::uint8_t id, std::uint16_t address) {
    return read(id, address, 1).at(0);
  }
  void write_u8(std::uint8_t id, std::uint16_t address, std::uint8_t v) { write(id, address, {v}); }
  void write_u32(std::uint8_t id, std::uint16_t address, std::uint32_t v) {
    write(id, address, dxl::to_le(v, 4));
  }

  /// Attempts that were repeated after a timeout or corrupted reply (for diagnostics).
  [[nodiscard]] int retried() const { return retried_; }
  [[nodiscard]] const std::string& port() const { return port_->name(); }

 private:
  dxl::Packet transact(std::uint8_t id, std::uint8_t instruction,
                       const std::vector<std::uint8_t>& params, std::size_t expected_params);

  std::unique_ptr<link::SerialPort> port_;
  Options options_;
  int retried_ = 0;
};

}  // namespace ferret::tether
