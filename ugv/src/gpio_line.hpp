#pragma once
// One GPIO output line through libgpiod 1.6 (Debian bookworm's), for the EPM's driver
// when the configuration says `epm: {via: gpio}` (internal to ugv/; no libgpiod type
// leaks out).

#include <string>

struct gpiod_chip;
struct gpiod_line;

namespace ferret::ugv::internal {

class GpioLine {
 public:
  /// Opens `chip` (a name such as gpiochip0, or a /dev path), requests `line` as an
  /// output at logical 0 (off) for `consumer`. Throws HwUgvError kGpio naming the chip
  /// and line.
  GpioLine(const std::string& chip, unsigned line, bool active_low, const std::string& consumer);
  ~GpioLine();
  GpioLine(const GpioLine&) = delete;
  GpioLine& operator=(const GpioLine&) = delete;

  /// Sets the logical value (active_low inverts it at the pin). False if the write failed.
  [[nodiscard]] bool set(bool on);

 private:
  gpiod_chip* chip_ = nullptr;
  gpiod_line* line_ = nullptr;
};

}  // namespace ferret::ugv::internal
