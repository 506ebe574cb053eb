#pragma once
// The tether and winch geometry of a mission (paper sect. III-A): the mission's `tether`
// section and the one home of its defaults.

#include <array>
#include <string_view>

namespace YAML {
class Emitter;
}

namespace ferret {
namespace yaml {
class MapReader;
}

struct TetherParams {
  double total_length_m = 15.0;  ///< L
  double entry_offset_m = 1.0;   ///< l_0: winch to the hidden-space entry point
  /// The miniUGV drives no faster than the winch can follow should its line catch on a
  /// corner its map does not hold (tether::LineCatchLimit; docs/mission.md).
  bool catch_speed_limit = true;

  /// The section's keys in the order they are emitted.
  static constexpr std::array<std::string_view, 3> kKeys{"total_length_m", "entry_offset_m",
                                                         "catch_speed_limit"};
};

/// Reads the `tether` section over the values `params` holds (every key optional; l_0 < L;
/// unknown keys rejected with InputError naming the file and field).
void read_tether_params(const yaml::MapReader& section, TetherParams& params);
/// The section as the mapping `key: {...}` that read_tether_params reads back.
void emit_tether_params(YAML::Emitter& e, const char* key, const TetherParams& params);

}  // namespace ferret
