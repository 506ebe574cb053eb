#pragma once
// The object search's constants (paper sect. IV-A, pinned down in docs/object_search.md):
// the mission's `object_search` section and the one home of their defaults, which the
// object map, the curiosity prediction and the simulated detector take theirs from.

#include <array>
#include <string_view>

namespace YAML {
class Emitter;
}

namespace ferret {
namespace yaml {
class MapReader;
}

/// Object map O and the detection model.
struct ObjectSearchParams {
  double lambda1 = 0.10;     ///< below: labelled free of the object
  double lambda2 = 0.95;     ///< above: the object; found when its cell passes this
  double eta_m = 1.0;        ///< conf = eta / d (d in metres)
  double conf_floor = 0.55;  ///< a detection is always weak positive evidence
  double conf_cap = 0.99;
  double miss_likelihood = 0.4;  ///< "no object" likelihood for a cell seen at zero distance

  /// The section's keys in the order they are emitted.
  static constexpr std::array<std::string_view, 6> kKeys{
      "lambda1", "lambda2", "eta_m", "conf_floor", "conf_cap", "miss_likelihood"};
};

/// Reads the `object_search` section over the values `params` holds (every key optional;
/// unknown keys, values out of range and conf_floor > conf_cap rejected with InputError
/// naming the file and field).
void read_object_search_params(const yaml::MapReader& section, ObjectSearchParams& params);
/// The section as the mapping `key: {...}` that read_object_search_params reads back.
void emit_object_search_params(YAML::Emitter& e, const char* key, const ObjectSearchParams& params);

}  // namespace ferret
