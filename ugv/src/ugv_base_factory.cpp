#include "ferret/ugv/ugv_base_factory.hpp"

#include <stdexcept>

#include "ferret/core/yaml_config.hpp"
#include "ferret/core/yaml_emit.hpp"
#include "ferret/ugv/hw_ugv_base.hpp"

namespace ferret::ugv {

UgvBaseConfig ugv_base_config_from_yaml(const YAML::Node& node, const std::string& source) {
  UgvBaseConfig c;
  if (!node.IsDefined() || node.IsNull()) return c;
  const yaml::MapReader section(node, source, "ugv.base");
  c.backend = read_backend(section);
  c.stall_time_s = section.get_in_range_or("stall_time_s", 0.05, 10.0, c.stall_time_s);
  if (c.backend == Backend::kHw || has_device_settings(section, {"stall_time_s"}))
    c.hw = hw_ugv_config_from_yaml(node, source);
  else
    section.allow_only({"backend", "stall_time_s"});
  return c;
}

void emit_ugv_base_config(YAML::Emitter& e, const UgvBaseConfig& c) {
  e << YAML::BeginMap << YAML::Key << "backend" << YAML::Value << std::string(to_string(c.backend));
  e << YAML::Key << "stall_time_s" << YAML::Value << internal::yaml_number(c.stall_time_s);
  if (c.hw) emit_hw_ugv_config(e, *c.hw);
  e << YAML::EndMap;
}

std::unique_ptr<UgvBase> make_ugv_base(const UgvBaseConfig& config, const UgvBaseContext& context,
                                       const UgvBaseFactory& sim) {
  switch (config.backend) {
    case Backend::kHw:
      if (!config.hw) throw std::invalid_argument("make_ugv_base: backend hw without HwUgvConfig");
      return std::make_unique<HwUgvBase>(*config.hw, context.robot, context.object_search,
                                         context.X_WG_start);
    case Backend::kSim:
      if (!sim)
        throw std::invalid_argument("make_ugv_base: backend sim without the simulator's factory");
      return sim(config, context);
  }
  throw std::invalid_argument("make_ugv_base: unknown backend");
}

}  // namespace ferret::ugv
