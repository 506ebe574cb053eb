// Mission YAML (config/mission.yaml's format) -> MissionConfig.
#include <cstdint>

#include "ferret/core/error.hpp"
#include "ferret/urdf/mission_config.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = ferret::fuzz::ScratchDir::instance().write("mission.yaml", data, size);
  try {
    const ferret::MissionConfig config = ferret::load_mission_config(path);
    // What `ferret config --dump` does next with a config that loaded.
    (void)ferret::mission_config_to_yaml(config);
  } catch (const ferret::InputError&) {
  }
  return 0;
}
