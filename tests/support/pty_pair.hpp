#pragma once
// A pseudo-terminal pair for the fake serial devices of the tests (the Dynamixel servo,
// the miniUGV's MCU): the fake owns the master side, the code under test opens the
// slave's path (/dev/pts/N) as it would open a real serial port.

#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <stdexcept>
#include <string>

namespace ferret::test {

class PtyPair {
 public:
  PtyPair() {
    master_ = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master_ < 0 || ::grantpt(master_) != 0 || ::unlockpt(master_) != 0)
      throw std::runtime_error("no pty");
    slave_name_ = ::ptsname(master_);
    // Keep the slave open so the master never sees a hang-up between sessions of the
    // code under test.
    keep_open_ = ::open(slave_name_.c_str(), O_RDWR | O_NOCTTY);
  }
  ~PtyPair() {
    ::close(keep_open_);
    ::close(master_);
  }
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;

  /// The fake's end.
  [[nodiscard]] int master() const { return master_; }
  /// The path the code under test opens.
  [[nodiscard]] const std::string& slave_name() const { return slave_name_; }

 private:
  int master_ = -1, keep_open_ = -1;
  std::string slave_name_;
};

}  // namespace ferret::test
