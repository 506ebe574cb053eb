#pragma once
// Motion limits of one robot: a mission section of their own (`ugv_limits`,
// `uav_limits`), the URDF loader's effective limits and the planners' and controllers'
// bounds all use this one struct.

#include <array>
#include <string_view>

namespace YAML {
class Emitter;
}

namespace ferret {
namespace yaml {
class MapReader;
}

struct MotionLimits {
  double max_velocity_mps = 2.0;
  double max_acceleration_mps2 = 2.0;
  double max_yaw_rate_radps = 2.0;

  /// The section's keys in the order they are emitted.
  static constexpr std::array<std::string_view, 3> kKeys{
      "max_velocity_mps", "max_acceleration_mps2", "max_yaw_rate_radps"};
};

/// Reads a limits section (every key optional, each > 0; unknown keys rejected) over the
/// values `limits` holds. Throws InputError naming the file and field.
void read_motion_limits(const yaml::MapReader& section, MotionLimits& limits);
/// The section as the mapping `key: {...}` that read_motion_limits reads back.
void emit_motion_limits(YAML::Emitter& e, const char* key, const MotionLimits& limits);

}  // namespace ferret
