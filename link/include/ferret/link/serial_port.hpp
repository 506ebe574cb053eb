#pragma once
// Byte I/O with timeouts for the robots' serial devices: the winch's Dynamixel bus
// (USB2Dynamixel, U2D2: /dev/ttyUSB*, /dev/ttyACM*) and the miniUGV's MCU (/dev/serial0).
// Serial devices go through libserialport (kept out of this header). Pseudo-terminals
// (/dev/pts/*, used by the fake servo and fake MCU in the tests and by bus emulators)
// are opened with termios directly: libserialport 0.1.1 (Debian bookworm) refuses
// them, since its port lookup needs a sysfs tty entry and sp_open fails on TIOCMGET
// (ENOTTY). Frames on top of the bytes: serial_framing.hpp.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>

namespace ferret::link {

/// A serial-port or bus failure, with the port name in the message.
class SerialError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An open serial port (an interface, so tests can script one).
class SerialPort {
 public:
  virtual ~SerialPort() = default;
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
[[nodiscard]] std::unique_ptr<SerialPort> open_serial_port(const std::string& port, int baud_rate);

}  // namespace ferret::link
