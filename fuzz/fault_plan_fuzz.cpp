// A mission YAML's `faults:` section -> FaultPlan; what loads writes back to itself.
#include <yaml-cpp/yaml.h>

#include <array>
#include <cstdint>
#include <string_view>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/sim/fault_plan.hpp"
#include "fuzz_support.hpp"

namespace {
constexpr std::array<std::string_view, 3> kUav{"search", "lower", "ugv_ops"};
constexpr std::array<std::string_view, 2> kUgv{"explore", "return"};
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = ferret::fuzz::ScratchDir::instance().write("faults.yaml", data, size);
  const ferret::FaultStates states{kUav, kUgv};
  ferret::FaultPlan plan;
  try {
    const YAML::Node root = ferret::yaml::load_file(path);
    if (!root.IsMap()) return 0;
    plan = ferret::fault_plan_from_yaml(root["faults"], path.string(), states);
  } catch (const ferret::InputError&) {
    return 0;
  }
  // The plan written out reads back the same (outside the catch: a refusal is a bug).
  const std::string text = ferret::fault_plan_to_yaml(plan);
  const auto again = ferret::fault_plan_from_yaml(ferret::yaml::load_string(text, "dump")["faults"],
                                                  "dump", states);
  if (!(again == plan)) __builtin_trap();
  for (const auto& f : plan.faults) (void)ferret::describe(f);
  return 0;
}
