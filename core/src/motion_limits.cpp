#include "ferret/core/motion_limits.hpp"

#include <limits>

#include "ferret/core/yaml_config.hpp"
#include "ferret/core/yaml_emit.hpp"

namespace ferret {

void read_motion_limits(const yaml::MapReader& r, MotionLimits& l) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  r.allow_only(MotionLimits::kKeys);
  l.max_velocity_mps = r.get_in_range_or("max_velocity_mps", 1e-6, kInf, l.max_velocity_mps);
  l.max_acceleration_mps2 =
      r.get_in_range_or("max_acceleration_mps2", 1e-6, kInf, l.max_acceleration_mps2);
  l.max_yaw_rate_radps = r.get_in_range_or("max_yaw_rate_radps", 1e-6, kInf, l.max_yaw_rate_radps);
}

void emit_motion_limits(YAML::Emitter& e, const char* key, const MotionLimits& l) {
  internal::emit_key_number_map(e, key,
                                {{"max_velocity_mps", l.max_velocity_mps},
                                 {"max_acceleration_mps2", l.max_acceleration_mps2},
                                 {"max_yaw_rate_radps", l.max_yaw_rate_radps}});
}

}  // namespace ferret
