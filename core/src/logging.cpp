#include "ferret/core/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <string>

#include "ferret/core/error.hpp"

namespace ferret {

void setup_logging(std::string_view level) {
  const auto parsed = spdlog::level::from_str(std::string(level));
  // from_str maps anything unknown to "off"; only accept "off" when asked for.
  if (parsed == spdlog::level::off && level != "off")
    throw InputError("--log-level", "", "one of trace, debug, info, warn, error, off",
                     std::string(level));
  auto logger = spdlog::get("ferret");
  if (!logger) logger = spdlog::stderr_color_mt("ferret");
  logger->set_pattern("[%l] %v");
  logger->set_level(parsed);
  spdlog::set_default_logger(logger);
}

}  // namespace ferret
