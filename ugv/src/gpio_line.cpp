#include "gpio_line.hpp"

#include <fmt/format.h>
#include <gpiod.h>

#include <cerrno>
#include <cstring>

#include "ferret/ugv/hw_ugv_base.hpp"

namespace ferret::ugv::internal {

GpioLine::GpioLine(const std::string& chip, unsigned line, bool active_low,
                   const std::string& consumer) {
  // A path opens as it is; a bare name through libgpiod's lookup (/dev/NAME).
  chip_ = chip.find('/') != std::string::npos ? gpiod_chip_open(chip.c_str())
                                              : gpiod_chip_open_by_name(chip.c_str());
  if (chip_ == nullptr)
    throw HwUgvError(HwUgvError::Kind::kGpio,
                     fmt::format("EPM gpio chip '{}': cannot open: {} (gpiodetect lists the "
                                 "chips; the user needs access to /dev/gpiochip*)",
                                 chip, std::strerror(errno)));
  line_ = gpiod_chip_get_line(chip_, line);
  if (line_ == nullptr) {
    const std::string why = std::strerror(errno);
    gpiod_chip_close(chip_);
    throw HwUgvError(HwUgvError::Kind::kGpio,
                     fmt::format("EPM gpio line {} on '{}': no such line: {} (gpioinfo {} "
                                 "lists them)",
                                 line, chip, why, chip));
  }
  const int flags = active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  if (gpiod_line_request_output_flags(line_, consumer.c_str(), flags, 0) != 0) {
    const std::string why = std::strerror(errno);
    gpiod_chip_close(chip_);
    throw HwUgvError(HwUgvError::Kind::kGpio,
                     fmt::format("EPM gpio line {} on '{}': cannot claim it as an output: {} "
                                 "(another program holds it? gpioinfo {} shows the consumer)",
                                 line, chip, why, chip));
  }
}

GpioLine::~GpioLine() {
  // Releasing leaves the pin as it is (the magnet keeps its state with no current).
  gpiod_line_release(line_);
  gpiod_chip_close(chip_);
}

bool GpioLine::set(bool on) { return gpiod_line_set_value(line_, on ? 1 : 0) == 0; }

}  // namespace ferret::ugv::internal
