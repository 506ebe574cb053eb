#include "ferret/mapping/object_search_params.hpp"

#include <limits>

#include "ferret/core/yaml_config.hpp"
#include "ferret/core/yaml_emit.hpp"

namespace ferret {

void read_object_search_params(const yaml::MapReader& r, ObjectSearchParams& o) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  r.allow_only(ObjectSearchParams::kKeys);
  o.lambda1 = r.get_in_range_or("lambda1", 0.0, 0.5, o.lambda1);
  o.lambda2 = r.get_in_range_or("lambda2", 0.5, 1.0, o.lambda2);
  o.eta_m = r.get_in_range_or("eta_m", 1e-6, kInf, o.eta_m);
  o.conf_floor = r.get_in_range_or("conf_floor", 0.5, 1.0, o.conf_floor);
  o.conf_cap = r.get_in_range_or("conf_cap", 0.5, 1.0, o.conf_cap);
  o.miss_likelihood = r.get_in_range_or("miss_likelihood", 0.0, 0.5, o.miss_likelihood);
  if (o.conf_floor > o.conf_cap) r.fail("conf_floor", "a value <= conf_cap");
}

void emit_object_search_params(YAML::Emitter& e, const char* key, const ObjectSearchParams& o) {
  internal::emit_key_number_map(e, key,
                                {{"lambda1", o.lambda1},
                                 {"lambda2", o.lambda2},
                                 {"eta_m", o.eta_m},
                                 {"conf_floor", o.conf_floor},
                                 {"conf_cap", o.conf_cap},
                                 {"miss_likelihood", o.miss_likelihood}});
}

}  // namespace ferret
