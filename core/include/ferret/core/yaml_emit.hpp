#pragma once
// Emitting numbers to YAML in their shortest round-trip form: yaml-cpp 0.7 prints
// 0.1 as 0.10000000000000001, which makes dumps hard to read and compare by eye.

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>

namespace ferret::internal {

[[nodiscard]] inline std::string yaml_number(double v) {
  if (std::isnan(v)) return ".nan";
  if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
  if (v == 0.0) return "0";  // also folds -0
  return fmt::format("{}", v);
}

inline void emit_number(YAML::Emitter& e, double v) { e << yaml_number(v); }

inline void emit_key_number(YAML::Emitter& e, const char* key, double v) {
  e << YAML::Key << key << YAML::Value << yaml_number(v);
}

/// A block mapping of numbers under `key`, in the order given.
inline void emit_key_number_map(YAML::Emitter& e, const char* key,
                                std::initializer_list<std::pair<const char*, double>> entries) {
  e << YAML::Key << key << YAML::Value << YAML::BeginMap;
  for (const auto& [name, v] : entries) emit_key_number(e, name, v);
  e << YAML::EndMap;
}

/// A flow list of numbers: [x, y, z].
template <class Range>
void emit_key_numbers(YAML::Emitter& e, const char* key, const Range& values) {
  e << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
  for (const double v : values) e << yaml_number(v);
  e << YAML::EndSeq;
}

inline void emit_key_numbers(YAML::Emitter& e, const char* key,
                             std::initializer_list<double> values) {
  emit_key_numbers<std::initializer_list<double>>(e, key, values);
}

}  // namespace ferret::internal
