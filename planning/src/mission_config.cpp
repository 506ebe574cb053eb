#include "ferret/planning/mission_config.hpp"

#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "ferret/core/yaml_config.hpp"

namespace ferret {
namespace {

/// Records the keys of a section the file gave.
void note(const yaml::MapReader& r, const std::string& section, std::set<std::string>& given) {
  for (const auto& entry : r.node()) {
    // Runs before the section's allow_only: a list or mapping as a key is caught here.
    if (!entry.first.IsScalar())
      throw InputError(r.source(), section, "keys that are names",
                       "a key that is " + yaml::internal::describe(entry.first));
    given.insert(section + "." + entry.first.as<std::string>());
  }
}

/// The numeric sections and their keys, in the order they are read and emitted.
const std::vector<std::pair<const char*, std::span<const std::string_view>>>& sections() {
  static const std::vector<std::pair<const char*, std::span<const std::string_view>>> list{
      {"curiosity", CuriosityParams::kKeys}, {"object_search", ObjectSearchParams::kKeys},
      {"tether", TetherParams::kKeys},       {"ugv_limits", MotionLimits::kKeys},
      {"uav_limits", MotionLimits::kKeys},
  };
  return list;
}

}  // namespace

MissionConfig mission_config_from_yaml(const YAML::Node& node, const std::string& source) {
  MissionConfig c;
  if (!node.IsDefined() || node.IsNull()) return c;  // an empty file means all defaults
  const yaml::MapReader root(node, source);
  // `ugv` and `uav` choose and configure the robots' hardware backends and the UAV
  // mission, `faults` what a simulated run breaks on purpose: their owners read those
  // sections (mission/mission_document.hpp).
  root.allow_only({"curiosity", "object_search", "tether", "ugv_limits", "uav_limits", "roles",
                   "ugv", "uav", "faults"});
  c.source = source;
  for (const auto& [section, keys] : sections())
    if (const auto r = root.optional_child(section)) note(*r, section, c.given);
  if (const auto r = root.optional_child("roles")) read_mission_roles(*r, c.roles);
  if (const auto r = root.optional_child("curiosity")) read_curiosity_params(*r, c.curiosity);
  if (const auto r = root.optional_child("object_search"))
    read_object_search_params(*r, c.object_search);
  if (const auto r = root.optional_child("tether")) read_tether_params(*r, c.tether);
  if (const auto r = root.optional_child("ugv_limits")) read_motion_limits(*r, c.ugv_limits);
  if (const auto r = root.optional_child("uav_limits")) read_motion_limits(*r, c.uav_limits);
  return c;
}

std::string mission_provenance_to_yaml(const MissionConfig& c) {
  YAML::Emitter e;
  e << YAML::BeginMap;
  for (const auto& [section, names] : sections())
    for (const std::string_view name : names) {
      const std::string key = std::string(section) + "." + std::string(name);
      e << YAML::Key << key << YAML::Value << c.provenance(key);
    }
  e << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

MissionConfig load_mission_config(const std::filesystem::path& path) {
  return mission_config_from_yaml(yaml::load_file(path), path.string());
}

std::string mission_config_to_yaml(const MissionConfig& c) {
  YAML::Emitter e;
  e << YAML::BeginMap;
  emit_curiosity_params(e, "curiosity", c.curiosity);
  emit_object_search_params(e, "object_search", c.object_search);
  emit_tether_params(e, "tether", c.tether);
  emit_motion_limits(e, "ugv_limits", c.ugv_limits);
  emit_motion_limits(e, "uav_limits", c.uav_limits);
  emit_mission_roles(e, c.roles);
  e << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

}  // namespace ferret
