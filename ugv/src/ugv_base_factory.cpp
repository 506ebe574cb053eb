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
  c.backend = read_backend(section, ugv_base_backends().names());
  c.stall_time_s = section.get_in_range_or("stall_time_s", 0.05, 10.0, c.stall_time_s);
  if (!c.simulated() || has_device_settings(section, {"stall_time_s"}))
    c.hw = hw_ugv_config_from_yaml(node, source);
  else
    section.allow_only({"backend", "stall_time_s"});
  return c;
}

void emit_ugv_base_config(YAML::Emitter& e, const UgvBaseConfig& c) {
  e << YAML::BeginMap << YAML::Key << "backend" << YAML::Value << c.backend;
  e << YAML::Key << "stall_time_s" << YAML::Value << internal::yaml_number(c.stall_time_s);
  if (c.hw) emit_hw_ugv_config(e, *c.hw);
  e << YAML::EndMap;
}

bool UgvBaseConfig::simulated() const { return ugv_base_backends().traits(backend).simulated; }

void register_builtin_ugv_base_backends(UgvBaseBackendRegistry& registry) {
  registry.add(
      "sim", "the simulated base (built by the simulator, which owns the world)",
      [](const UgvBaseSetup& s) {
        if (!s.sim)
          throw std::invalid_argument("make_ugv_base: backend sim without the simulator's factory");
        return s.sim(s.config, s.context);
      },
      {}, BackendTraits{.simulated = true});
  registry.add("hw", "the miniUGV's MCU on a serial port and its camera (HwUgvBase)",
               [](const UgvBaseSetup& s) -> std::unique_ptr<UgvBase> {
                 if (!s.config.hw)
                   throw std::invalid_argument("make_ugv_base: backend hw without HwUgvConfig");
                 return std::make_unique<HwUgvBase>(*s.config.hw, s.context.robot,
                                                    s.context.object_search, s.context.X_WG_start);
               });
}

const UgvBaseBackendRegistry& ugv_base_backends() {
  return filled_registry<UgvBaseBackendRegistry, register_builtin_ugv_base_backends>();
}

std::unique_ptr<UgvBase> make_ugv_base(const UgvBaseConfig& config, const UgvBaseContext& context,
                                       const UgvBaseFactory& sim) {
  return ugv_base_backends().make(config.backend, {config, context, sim}, "make_ugv_base",
                                  "ugv.base.backend");
}

}  // namespace ferret::ugv
