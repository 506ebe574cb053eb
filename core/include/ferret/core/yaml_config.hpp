#pragma once
// Typed, checked reading of YAML configuration. Every failure is an InputError
// naming the file, the dotted field path and the expected value, so a user can fix
// the file from one line of output.

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <initializer_list>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"

namespace ferret::yaml {

/// Loads a YAML document. Throws InputError for a missing/unreadable file or a
/// syntax error (with line and column).
[[nodiscard]] YAML::Node load_file(const std::filesystem::path& path);

/// Parses YAML text; `source` names it in errors.
[[nodiscard]] YAML::Node load_string(const std::string& text, const std::string& source);

namespace internal {
template <class T>
constexpr const char* type_description() {
  if constexpr (std::is_same_v<T, bool>)
    return "true or false";
  else if constexpr (std::is_integral_v<T>)
    return "an integer";
  else if constexpr (std::is_floating_point_v<T>)
    return "a number";
  else if constexpr (std::is_same_v<T, std::string>)
    return "a string";
  else
    return "a value of the right type";
}
std::string describe(const YAML::Node& node);
}  // namespace internal

/// Reads one YAML mapping. Field paths in errors are dotted from the document root.
class MapReader {
 public:
  /// @pre node is a map (checked: InputError otherwise, naming `path`).
  MapReader(YAML::Node node, std::string source, std::string path = {});

  [[nodiscard]] bool has(std::string_view key) const;
  [[nodiscard]] const std::string& source() const { return source_; }
  [[nodiscard]] std::string field_path(std::string_view key) const;
  [[nodiscard]] const YAML::Node& node() const { return node_; }

  /// Required scalar field.
  template <class T>
  [[nodiscard]] T get(std::string_view key) const {
    if (!has(key))
      fail(key, std::string(internal::type_description<T>()) + " (required field missing)");
    return convert<T>(node_[std::string(key)], field_path(key));
  }
  /// Optional scalar field with a default.
  template <class T>
  [[nodiscard]] T get_or(std::string_view key, T fallback) const {
    if (given_empty(key))
      fail(key, std::string(internal::type_description<T>()), "a key without a value");
    return has(key) ? convert<T>(node_[std::string(key)], field_path(key)) : fallback;
  }
  /// True when `key` is written with no value (`key:` or `key: null`): for a scalar
  /// with a default that is a mistake, not a request for the default.
  [[nodiscard]] bool given_empty(std::string_view key) const;
  /// Required number in [lo, hi].
  [[nodiscard]] double get_in_range(std::string_view key, double lo, double hi) const;
  /// Optional number in [lo, hi] with a default.
  [[nodiscard]] double get_in_range_or(std::string_view key, double lo, double hi,
                                       double fallback) const;
  /// Required sequence of scalars; `size` > 0 demands exactly that many entries.
  template <class T>
  [[nodiscard]] std::vector<T> get_list(std::string_view key, std::size_t size = 0) const {
    if (!has(key)) fail(key, "a list (required field missing)");
    const YAML::Node list = node_[std::string(key)];
    const std::string path = field_path(key);
    if (!list.IsSequence() || (size > 0 && list.size() != size)) {
      const std::string what =
          size > 0 ? "a list of " + std::to_string(size) + " values" : "a list";
      throw InputError(source_, path, what, internal::describe(list));
    }
    std::vector<T> out;
    for (std::size_t i = 0; i < list.size(); ++i)
      out.push_back(convert<T>(list[i], path + "[" + std::to_string(i) + "]"));
    return out;
  }
  /// Required nested mapping.
  [[nodiscard]] MapReader child(std::string_view key) const;
  /// Nested mapping if present.
  [[nodiscard]] std::optional<MapReader> optional_child(std::string_view key) const;
  /// Required sequence of mappings.
  [[nodiscard]] std::vector<MapReader> child_list(std::string_view key) const;

  /// Throws InputError naming the first key not in `allowed`, or a key given
  /// twice: catches typos that would otherwise silently fall back to defaults.
  void allow_only(std::initializer_list<std::string_view> allowed) const {
    allow_only(std::span<const std::string_view>(allowed.begin(), allowed.size()));
  }
  /// The same for a list built at run time (a section whose keys two modules read).
  void allow_only(std::span<const std::string_view> allowed) const;

  /// Throws InputError for `key` with the given expectation.
  [[noreturn]] void fail(std::string_view key, const std::string& expected,
                         const std::string& got = {}) const;

  template <class T>
  [[nodiscard]] T convert(const YAML::Node& value, const std::string& path) const {
    if constexpr (!std::is_same_v<T, std::string>) {
      if (!value.IsScalar())
        throw InputError(source_, path, internal::type_description<T>(), internal::describe(value));
    }
    // Numbers through ferret's one number parser: finite, whole text, no wrapping.
    if constexpr (std::is_floating_point_v<T>) {
      return static_cast<T>(parse_number(value.Scalar(), NumberRange::finite(), source_, path));
    } else if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
      if constexpr (std::is_unsigned_v<T>)
        return static_cast<T>(
            parse_unsigned(value.Scalar(), source_, path, std::numeric_limits<T>::max()));
      else
        return static_cast<T>(parse_integer(value.Scalar(), std::numeric_limits<T>::min(),
                                            std::numeric_limits<T>::max(), source_, path));
    }
    try {
      return value.as<T>();
    } catch (const YAML::Exception&) {
      throw InputError(source_, path, internal::type_description<T>(), internal::describe(value));
    }
  }

 private:
  YAML::Node node_;
  std::string source_;
  std::string path_;
};

}  // namespace ferret::yaml
