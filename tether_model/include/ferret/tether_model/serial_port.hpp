#pragma once
// Byte I/O with timeouts for the Dynamixel bus. Serial devices (USB2Dynamixel,
// U2D2: /dev/ttyUSB*, /dev/ttyACM*) go through libserialport. Pseudo-terminals
// (/dev/pts/*, used by the fake servo in the tests and by bus emulators) are opened
// with termios directly: libserialport 0.1.1 (Debian bookworm) refuses them, since
// its port lookup needs a sysfs tty entry and sp_open fails on TIOCMGET (ENOTTY).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>

namespace ferret::tether {

/// A serial-port or bus failure, with the port name in the message.
class SerialError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class SerialLink {
 public:
  virtual ~SerialLink() = default;
  /// Writes all bytes or throws SerialError.
  virtual void write(std::span<const std::uint8_t> bytes) = 0;
  /// Waits up to timeout_ms for at least one byte; returns how many were read (0 on timeout).
  [[nodiscard]] virtual std::size_t read_some(std::span<std::uint8_t> buffer, int timeout_ms) = 0;
  /// Drops unread input (stale bytes from an earlier, timed-out exchange).
  virtual void discard_input() = 0;
  [[nodiscard]] virtual const std::string& name() const = 0;
};

/// Opens `port` at `baud_rate` 8N1 without flow control. Throws SerialError naming
/// the port for a missing device, a busy one, or a rate the port refuses.
[[nodiscard]] std::unique_ptr<SerialLink> open_serial_port(const std::string& port, int baud_rate);

}  // namespace ferret::tether
