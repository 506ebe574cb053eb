#include "ferret/core/backend.hpp"

#include <string>

namespace ferret {

std::string_view to_string(Backend backend) { return backend == Backend::kHw ? "hw" : "sim"; }

Backend read_backend(const yaml::MapReader& section) {
  constexpr const char* kExpected = "one of sim, hw";
  if (section.given_empty("backend")) section.fail("backend", kExpected, "a key without a value");
  if (!section.has("backend")) return Backend::kSim;
  const auto name = section.get<std::string>("backend");
  if (name == "sim") return Backend::kSim;
  if (name == "hw") return Backend::kHw;
  section.fail("backend", kExpected, yaml::internal::describe(section.node()["backend"]));
}

bool has_device_settings(const yaml::MapReader& section,
                         std::initializer_list<const char*> common) {
  std::size_t shared = section.node()["backend"].IsDefined() ? 1u : 0u;
  for (const char* key : common) shared += section.node()[key].IsDefined() ? 1u : 0u;
  return section.node().size() > shared;
}

}  // namespace ferret
