#pragma once
// The curiosity function's constants (paper eq. curiosity): the mission's `curiosity`
// section and the one home of their defaults.

#include <array>
#include <string_view>

namespace YAML {
class Emitter;
}

namespace ferret {
namespace yaml {
class MapReader;
}

/// Curiosity c(p) = -(p + a)^2 / (4 b) + K.
struct CuriosityParams {
  double a = -0.5;
  double b = 0.1;
  double K = 0.62;

  /// The section's keys in the order they are emitted.
  static constexpr std::array<std::string_view, 3> kKeys{"a", "b", "K"};
};

/// Reads the `curiosity` section over the values `params` holds (every key optional,
/// b > 0; unknown keys rejected with InputError naming the file and field).
void read_curiosity_params(const yaml::MapReader& section, CuriosityParams& params);
/// The section as the mapping `key: {...}` that read_curiosity_params reads back.
void emit_curiosity_params(YAML::Emitter& e, const char* key, const CuriosityParams& params);

}  // namespace ferret
