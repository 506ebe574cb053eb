#include "ferret/core/backend.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <string>

namespace ferret {

std::string read_backend(const yaml::MapReader& section, const std::vector<std::string>& names) {
  const std::string expected = fmt::format("one of {}", fmt::join(names, ", "));
  if (section.given_empty("backend")) section.fail("backend", expected, "a key without a value");
  if (!section.has("backend")) return std::string(kSimBackend);
  auto name = section.get<std::string>("backend");
  if (std::find(names.begin(), names.end(), name) != names.end()) return name;
  section.fail("backend", expected, yaml::internal::describe(section.node()["backend"]));
}

bool has_device_settings(const yaml::MapReader& section,
                         std::initializer_list<const char*> common) {
  std::size_t shared = section.node()["backend"].IsDefined() ? 1u : 0u;
  for (const char* key : common) shared += section.node()[key].IsDefined() ? 1u : 0u;
  return section.node().size() > shared;
}

}  // namespace ferret
