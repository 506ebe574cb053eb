#include "ferret/urdf/mission_config.hpp"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

#include "ferret/core/yaml_config.hpp"
#include "ferret/core/yaml_emit.hpp"

namespace ferret {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

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

const std::vector<std::string>& known_roles() {
  static const std::vector<std::string> roles{
      "object_camera", "ir",  "marker_camera", "depth_camera",
      "epm",           "imu", "winch_spool",   "tether_attachment"};
  return roles;
}

void read_roles(const yaml::MapReader& r, MissionConfig& c) {
  for (const auto& robot : r.node()) {
    // A list or mapping as a key (`? [a]`) is not a name (found by fuzz/mission_fuzz.cpp).
    if (!robot.first.IsScalar())
      throw InputError(r.source(), "roles", "robot names as keys",
                       "a key that is " + yaml::internal::describe(robot.first));
    const auto robot_name = robot.first.as<std::string>();
    if (!robot.second.IsMap() || robot.second.size() == 0)
      r.fail(robot_name, "a mapping of roles to sensor or link names for the robot '" + robot_name +
                             "' (e.g. {object_camera: cam, ir: [ir_l, ir_r]})");
    const yaml::MapReader rr(robot.second, r.source(), r.field_path(robot_name));
    auto& out = c.roles[robot_name];
    for (const auto& entry : robot.second) {
      if (!entry.first.IsScalar())
        throw InputError(r.source(), r.field_path(robot_name), "role names as keys",
                         "a key that is " + yaml::internal::describe(entry.first));
      const auto role = entry.first.as<std::string>();
      if (std::find(known_roles().begin(), known_roles().end(), role) == known_roles().end()) {
        std::string list;
        for (const auto& k : known_roles()) list += (list.empty() ? "" : ", ") + k;
        rr.fail(role, "a role: one of " + list, role);
      }
      std::vector<std::string> names;
      if (entry.second.IsScalar())
        names.push_back(rr.get<std::string>(role));
      else
        names = rr.get_list<std::string>(role);
      if (names.empty()) rr.fail(role, "a sensor or link name, or a non-empty list of them");
      for (const auto& n : names)
        if (n.empty()) rr.fail(role, "non-empty sensor or link names");
      out[role] = names;
    }
  }
}

void read_limits(const yaml::MapReader& r, MotionLimits& l) {
  r.allow_only({"max_velocity_mps", "max_acceleration_mps2", "max_yaw_rate_radps"});
  l.max_velocity_mps = r.get_in_range_or("max_velocity_mps", 1e-6, kInf, l.max_velocity_mps);
  l.max_acceleration_mps2 =
      r.get_in_range_or("max_acceleration_mps2", 1e-6, kInf, l.max_acceleration_mps2);
  l.max_yaw_rate_radps = r.get_in_range_or("max_yaw_rate_radps", 1e-6, kInf, l.max_yaw_rate_radps);
}

void emit_limits(YAML::Emitter& e, const char* name, const MotionLimits& l) {
  e << YAML::Key << name << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "max_velocity_mps" << YAML::Value << internal::yaml_number(l.max_velocity_mps);
  e << YAML::Key << "max_acceleration_mps2" << YAML::Value
    << internal::yaml_number(l.max_acceleration_mps2);
  e << YAML::Key << "max_yaw_rate_radps" << YAML::Value
    << internal::yaml_number(l.max_yaw_rate_radps);
  e << YAML::EndMap;
}
}  // namespace

MissionConfig mission_config_from_yaml(const YAML::Node& node, const std::string& source) {
  MissionConfig c;
  if (!node.IsDefined() || node.IsNull()) return c;  // an empty file means all defaults
  const yaml::MapReader root(node, source);
  // `ugv` and `uav` choose and configure the robots' hardware backends: the modules that
  // build them read those sections (sim/robot_backends.hpp), this layer knows none of them.
  root.allow_only(
      {"curiosity", "object_search", "tether", "ugv_limits", "uav_limits", "roles", "ugv", "uav"});
  c.source = source;
  for (const char* section : {"curiosity", "object_search", "tether", "ugv_limits", "uav_limits"})
    if (const auto r = root.optional_child(section)) note(*r, section, c.given);
  if (const auto r = root.optional_child("roles")) read_roles(*r, c);
  if (const auto r = root.optional_child("curiosity")) {
    r->allow_only({"a", "b", "K"});
    c.curiosity.a = r->get_or("a", c.curiosity.a);
    c.curiosity.b = r->get_in_range_or("b", 1e-9, kInf, c.curiosity.b);
    c.curiosity.K = r->get_or("K", c.curiosity.K);
  }
  if (const auto r = root.optional_child("object_search")) {
    auto& o = c.object_search;
    r->allow_only({"lambda1", "lambda2", "eta_m", "conf_floor", "conf_cap", "miss_likelihood"});
    o.lambda1 = r->get_in_range_or("lambda1", 0.0, 0.5, o.lambda1);
    o.lambda2 = r->get_in_range_or("lambda2", 0.5, 1.0, o.lambda2);
    o.eta_m = r->get_in_range_or("eta_m", 1e-6, kInf, o.eta_m);
    o.conf_floor = r->get_in_range_or("conf_floor", 0.5, 1.0, o.conf_floor);
    o.conf_cap = r->get_in_range_or("conf_cap", 0.5, 1.0, o.conf_cap);
    o.miss_likelihood = r->get_in_range_or("miss_likelihood", 0.0, 0.5, o.miss_likelihood);
    if (o.conf_floor > o.conf_cap) r->fail("conf_floor", "a value <= conf_cap");
  }
  if (const auto r = root.optional_child("tether")) {
    r->allow_only({"total_length_m", "entry_offset_m", "catch_speed_limit"});
    c.tether.total_length_m =
        r->get_in_range_or("total_length_m", 1e-3, kInf, c.tether.total_length_m);
    c.tether.entry_offset_m =
        r->get_in_range_or("entry_offset_m", 0.0, kInf, c.tether.entry_offset_m);
    if (c.tether.entry_offset_m >= c.tether.total_length_m)
      r->fail("entry_offset_m", "a value below tether.total_length_m");
    c.tether.catch_speed_limit = r->get_or("catch_speed_limit", c.tether.catch_speed_limit);
  }
  if (const auto r = root.optional_child("ugv_limits")) read_limits(*r, c.ugv_limits);
  if (const auto r = root.optional_child("uav_limits")) read_limits(*r, c.uav_limits);
  return c;
}

std::string MissionConfig::provenance(const std::string& key) const {
  return given.count(key) > 0 ? "mission:" + source : "default";
}

std::string mission_provenance_to_yaml(const MissionConfig& c) {
  static const std::vector<std::pair<const char*, std::vector<const char*>>> keys{
      {"curiosity", {"a", "b", "K"}},
      {"object_search",
       {"lambda1", "lambda2", "eta_m", "conf_floor", "conf_cap", "miss_likelihood"}},
      {"tether", {"total_length_m", "entry_offset_m", "catch_speed_limit"}},
      {"ugv_limits", {"max_velocity_mps", "max_acceleration_mps2", "max_yaw_rate_radps"}},
      {"uav_limits", {"max_velocity_mps", "max_acceleration_mps2", "max_yaw_rate_radps"}},
  };
  YAML::Emitter e;
  e << YAML::BeginMap;
  for (const auto& [section, names] : keys)
    for (const char* name : names) {
      const std::string key = std::string(section) + "." + name;
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
  e << YAML::Key << "curiosity" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "a" << YAML::Value << internal::yaml_number(c.curiosity.a);
  e << YAML::Key << "b" << YAML::Value << internal::yaml_number(c.curiosity.b);
  e << YAML::Key << "K" << YAML::Value << internal::yaml_number(c.curiosity.K) << YAML::EndMap;
  const auto& o = c.object_search;
  e << YAML::Key << "object_search" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "lambda1" << YAML::Value << internal::yaml_number(o.lambda1);
  e << YAML::Key << "lambda2" << YAML::Value << internal::yaml_number(o.lambda2);
  e << YAML::Key << "eta_m" << YAML::Value << internal::yaml_number(o.eta_m);
  e << YAML::Key << "conf_floor" << YAML::Value << internal::yaml_number(o.conf_floor);
  e << YAML::Key << "conf_cap" << YAML::Value << internal::yaml_number(o.conf_cap);
  e << YAML::Key << "miss_likelihood" << YAML::Value << internal::yaml_number(o.miss_likelihood)
    << YAML::EndMap;
  e << YAML::Key << "tether" << YAML::Value << YAML::BeginMap;
  e << YAML::Key << "total_length_m" << YAML::Value
    << internal::yaml_number(c.tether.total_length_m);
  e << YAML::Key << "entry_offset_m" << YAML::Value
    << internal::yaml_number(c.tether.entry_offset_m);
  e << YAML::Key << "catch_speed_limit" << YAML::Value << c.tether.catch_speed_limit
    << YAML::EndMap;
  emit_limits(e, "ugv_limits", c.ugv_limits);
  emit_limits(e, "uav_limits", c.uav_limits);
  if (!c.roles.empty()) {
    e << YAML::Key << "roles" << YAML::Value << YAML::BeginMap;
    for (const auto& [robot, roles] : c.roles) {
      e << YAML::Key << robot << YAML::Value << YAML::BeginMap;
      for (const auto& [role, names] : roles)
        e << YAML::Key << role << YAML::Value << YAML::Flow << names;
      e << YAML::EndMap;
    }
    e << YAML::EndMap;
  }
  e << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

}  // namespace ferret
