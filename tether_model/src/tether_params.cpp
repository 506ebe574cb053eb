#include "ferret/tether_model/tether_params.hpp"

#include <limits>

#include "ferret/core/yaml_config.hpp"
#include "ferret/core/yaml_emit.hpp"

namespace ferret {

void read_tether_params(const yaml::MapReader& r, TetherParams& t) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  r.allow_only(TetherParams::kKeys);
  t.total_length_m = r.get_in_range_or("total_length_m", 1e-3, kInf, t.total_length_m);
  t.entry_offset_m = r.get_in_range_or("entry_offset_m", 0.0, kInf, t.entry_offset_m);
  if (t.entry_offset_m >= t.total_length_m)
    r.fail("entry_offset_m", "a value below tether.total_length_m");
  t.catch_speed_limit = r.get_or("catch_speed_limit", t.catch_speed_limit);
}

void emit_tether_params(YAML::Emitter& e, const char* key, const TetherParams& t) {
  e << YAML::Key << key << YAML::Value << YAML::BeginMap;
  internal::emit_key_number(e, "total_length_m", t.total_length_m);
  internal::emit_key_number(e, "entry_offset_m", t.entry_offset_m);
  e << YAML::Key << "catch_speed_limit" << YAML::Value << t.catch_speed_limit << YAML::EndMap;
}

}  // namespace ferret
