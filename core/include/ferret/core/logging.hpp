#pragma once
#include <string_view>

namespace ferret {

/// Configures spdlog's default logger to write to stderr at `level`
/// ("trace", "debug", "info", "warn", "error", "off"). Throws InputError for an
/// unknown level.
void setup_logging(std::string_view level);

}  // namespace ferret
