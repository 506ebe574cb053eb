#include "ferret/planning/curiosity_params.hpp"

#include <limits>

#include "ferret/core/yaml_config.hpp"
#include "ferret/core/yaml_emit.hpp"

namespace ferret {

void read_curiosity_params(const yaml::MapReader& r, CuriosityParams& c) {
  r.allow_only(CuriosityParams::kKeys);
  c.a = r.get_or("a", c.a);
  c.b = r.get_in_range_or("b", 1e-9, std::numeric_limits<double>::infinity(), c.b);
  c.K = r.get_or("K", c.K);
}

void emit_curiosity_params(YAML::Emitter& e, const char* key, const CuriosityParams& c) {
  internal::emit_key_number_map(e, key, {{"a", c.a}, {"b", c.b}, {"K", c.K}});
}

}  // namespace ferret
