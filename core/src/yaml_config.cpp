#include "ferret/core/yaml_config.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace ferret::yaml {

namespace internal {
std::string describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a list of " + std::to_string(node.size());
  if (node.IsMap()) return "a mapping";
  return "an unknown node";
}
}  // namespace internal

YAML::Node load_string(const std::string& text, const std::string& source) {
  // YAML is Unicode text; yaml-cpp passes other bytes through into keys and strings,
  // where they would reach messages and JSON outputs.
  if (const auto bad = first_invalid_utf8(text); bad != std::string::npos) {
    const auto line =
        1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(bad), '\n');
    const auto line_start = text.rfind('\n', bad == 0 ? 0 : bad - 1);
    const auto column =
        bad - (line_start == std::string::npos || bad == 0 ? 0 : line_start + 1) + 1;
    throw InputError(source, fmt::format("line {} column {}", line, column), "UTF-8 text",
                     fmt::format("the byte 0x{:02x}", static_cast<unsigned char>(text[bad])));
  }
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(
        source,
        "line " + std::to_string(e.mark.line + 1) + " column " + std::to_string(e.mark.column + 1),
        "valid YAML", e.msg);
  }
}

YAML::Node load_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in || std::filesystem::is_directory(path))
    throw InputError(path.string(), "", "a readable YAML file", "cannot open");
  std::stringstream text;
  text << in.rdbuf();
  return load_string(text.str(), path.string());
}

MapReader::MapReader(YAML::Node node, std::string source, std::string path)
    : node_(std::move(node)), source_(std::move(source)), path_(std::move(path)) {
  if (!node_.IsMap())
    throw InputError(source_, path_.empty() ? "(document)" : path_, "a mapping of keys to values",
                     internal::describe(node_));
}

bool MapReader::has(std::string_view key) const {
  const YAML::Node value = node_[std::string(key)];
  return value.IsDefined() && !value.IsNull();
}

std::string MapReader::field_path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void MapReader::fail(std::string_view key, const std::string& expected,
                     const std::string& got) const {
  throw InputError(source_, field_path(key), expected, got);
}

bool MapReader::given_empty(std::string_view key) const {
  const YAML::Node value = node_[std::string(key)];
  return value.IsDefined() && value.IsNull();
}

double MapReader::get_in_range(std::string_view key, double lo, double hi) const {
  if (!has(key)) fail(key, "a number (required field missing)");
  const YAML::Node value = node_[std::string(key)];
  if (!value.IsScalar())
    fail(key, NumberRange::closed(lo, hi).describe(), internal::describe(value));
  return parse_number(value.Scalar(), NumberRange::closed(lo, hi), source_, field_path(key));
}

double MapReader::get_in_range_or(std::string_view key, double lo, double hi,
                                  double fallback) const {
  if (given_empty(key)) fail(key, NumberRange::closed(lo, hi).describe(), "a key without a value");
  return has(key) ? get_in_range(key, lo, hi) : fallback;
}

MapReader MapReader::child(std::string_view key) const {
  if (!has(key)) fail(key, "a mapping (required field missing)");
  return MapReader(node_[std::string(key)], source_, field_path(key));
}

std::optional<MapReader> MapReader::optional_child(std::string_view key) const {
  if (!has(key)) return std::nullopt;
  return child(key);
}

std::vector<MapReader> MapReader::child_list(std::string_view key) const {
  if (!has(key)) fail(key, "a list of mappings (required field missing)");
  const YAML::Node list = node_[std::string(key)];
  if (!list.IsSequence()) fail(key, "a list of mappings", internal::describe(list));
  std::vector<MapReader> out;
  for (std::size_t i = 0; i < list.size(); ++i)
    out.emplace_back(list[i], source_, field_path(key) + "[" + std::to_string(i) + "]");
  return out;
}

void MapReader::allow_only(std::span<const std::string_view> allowed) const {
  std::vector<std::string> seen;
  for (const auto& entry : node_) {
    // YAML allows a list or a mapping as a key (`? [a, b]`); as<std::string> would
    // throw yaml-cpp's own exception (found by fuzz/mission_fuzz.cpp).
    if (!entry.first.IsScalar())
      throw InputError(source_, path_.empty() ? "(document)" : path_, "keys that are names",
                       "a key that is " + internal::describe(entry.first));
    const auto key = entry.first.as<std::string>();
    // yaml-cpp keeps both entries of a repeated key and looks up the first, so the
    // second would be silently ignored.
    if (std::find(seen.begin(), seen.end(), key) != seen.end())
      throw InputError(source_, field_path(key), "each key once", "a repeated key");
    seen.push_back(key);
    bool known = false;
    for (const auto a : allowed) known = known || a == key;
    if (!known) {
      std::string list;
      for (const auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      throw InputError(source_, field_path(key), "a known key (one of: " + list + ")",
                       "unknown key");
    }
  }
}

}  // namespace ferret::yaml
