#include "ferret/link/serial_port.hpp"

#include <fcntl.h>
#include <libserialport.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>

namespace ferret::link {
namespace {

class LibSerialPort final : public SerialPort {
 public:
  LibSerialPort(const std::string& name, int baud) : name_(name) {
    if (sp_get_port_by_name(name.c_str(), &port_) != SP_OK)
      throw SerialError("serial port '" + name + "': not found (is the adapter plugged in?)");
    if (sp_open(port_, SP_MODE_READ_WRITE) != SP_OK) {
      const std::string why = sp_last_error_message();
      sp_free_port(port_);
      throw SerialError("serial port '" + name + "': cannot open: " + why);
    }
    if (sp_set_baudrate(port_, baud) != SP_OK || sp_set_bits(port_, 8) != SP_OK ||
        sp_set_parity(port_, SP_PARITY_NONE) != SP_OK || sp_set_stopbits(port_, 1) != SP_OK ||
        sp_set_flowcontrol(port_, SP_FLOWCONTROL_NONE) != SP_OK) {
      const std::string why = sp_last_error_message();
      sp_close(port_);
      sp_free_port(port_);
      throw SerialError("serial port '" + name + "': cannot set " + std::to_string(baud) +
                        " baud 8N1: " + why);
    }
  }
  ~LibSerialPort() override {
    sp_close(port_);
    sp_free_port(port_);
  }
  void write(std::span<const std::uint8_t> bytes) override {
    const int n = sp_blocking_write(port_, bytes.data(), bytes.size(), 1000);
    if (n < 0 || static_cast<std::size_t>(n) != bytes.size())
      throw SerialError("serial port '" + name_ + "': write failed");
  }
  std::size_t read_some(std::span<std::uint8_t> buffer, int timeout_ms) override {
    const int n = sp_blocking_read_next(port_, buffer.data(), buffer.size(),
                                        static_cast<unsigned>(std::max(timeout_ms, 1)));
    if (n < 0) throw SerialError("serial port '" + name_ + "': read failed");
    return static_cast<std::size_t>(n);
  }
  void discard_input() override { sp_flush(port_, SP_BUF_INPUT); }
  const std::string& name() const override { return name_; }

 private:
  std::string name_;
  sp_port* port_ = nullptr;
};

speed_t termios_speed(int baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 1000000:
      return B1000000;
    case 2000000:
      return B2000000;
    case 3000000:
      return B3000000;
    case 4000000:
      return B4000000;
    default:
      return B0;
  }
}

class TermiosPort final : public SerialPort {
 public:
  TermiosPort(const std::string& name, int baud) : name_(name) {
    fd_ = ::open(name.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK);
    if (fd_ < 0)
      throw SerialError("serial port '" + name + "': cannot open: " + std::strerror(errno));
    termios tio{};
    if (::tcgetattr(fd_, &tio) != 0) fail("not a terminal");
    ::cfmakeraw(&tio);
    tio.c_cflag |= CLOCAL | CREAD;
    const speed_t speed = termios_speed(baud);
    if (speed == B0) fail("unsupported baud rate " + std::to_string(baud));
    ::cfsetispeed(&tio, speed);
    ::cfsetospeed(&tio, speed);
    tio.c_cc[VMIN] = 0;
    tio.c_cc[VTIME] = 0;
    if (::tcsetattr(fd_, TCSANOW, &tio) != 0) fail(std::strerror(errno));
  }
  ~TermiosPort() override { ::close(fd_); }
  void write(std::span<const std::uint8_t> bytes) override {
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno != EAGAIN && errno != EINTR)
        throw SerialError("serial port '" + name_ + "': write failed: " + std::strerror(errno));
      if (n > 0)
        done += static_cast<std::size_t>(n);
      else
        wait(POLLOUT, 100);
    }
  }
  std::size_t read_some(std::span<std::uint8_t> buffer, int timeout_ms) override {
    if (!wait(POLLIN, timeout_ms)) return 0;
    const ssize_t n = ::read(fd_, buffer.data(), buffer.size());
    if (n < 0) {
      if (errno == EAGAIN || errno == EINTR) return 0;
      throw SerialError("serial port '" + name_ + "': read failed: " + std::strerror(errno));
    }
    return static_cast<std::size_t>(n);
  }
  void discard_input() override { ::tcflush(fd_, TCIFLUSH); }
  const std::string& name() const override { return name_; }

 private:
  [[noreturn]] void fail(const std::string& why) {
    ::close(fd_);
    throw SerialError("serial port '" + name_ + "': " + why);
  }
  bool wait(short events, int timeout_ms) {
    pollfd p{fd_, events, 0};
    const int r = ::poll(&p, 1, timeout_ms);
    return r > 0 && (p.revents & events);
  }
  std::string name_;
  int fd_ = -1;
};

bool is_pseudo_terminal(const std::string& name) {
  std::error_code ec;
  const auto real = std::filesystem::canonical(name, ec);
  return !ec && real.string().rfind("/dev/pts/", 0) == 0;
}

}  // namespace

std::unique_ptr<SerialPort> open_serial_port(const std::string& port, int baud_rate) {
  if (baud_rate <= 0) throw SerialError("serial port '" + port + "': baud rate must be > 0");
  if (is_pseudo_terminal(port)) return std::make_unique<TermiosPort>(port, baud_rate);
  return std::make_unique<LibSerialPort>(port, baud_rate);
}

}  // namespace ferret::link
