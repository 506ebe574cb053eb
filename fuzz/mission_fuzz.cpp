// Mission YAML (config/mission.yaml's format) -> MissionConfig and the robots' backends.
#include <cstdint>
#include <optional>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/sim/robot_backends.hpp"
#include "ferret/urdf/mission_config.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = ferret::fuzz::ScratchDir::instance().write("mission.yaml", data, size);
  std::optional<ferret::RobotBackends> backends;
  try {
    const ferret::MissionConfig config = ferret::load_mission_config(path);
    // What `ferret config --dump` does next with a config that loaded.
    (void)ferret::mission_config_to_yaml(config);
    backends = ferret::load_robot_backends(path);
  } catch (const ferret::InputError&) {
    return 0;
  }
  // The dump reads back to itself (outside the catch: a refusal here is a bug).
  const std::string dump = ferret::robot_backends_to_yaml(*backends);
  const auto again =
      ferret::robot_backends_from_yaml(ferret::yaml::load_string(dump, "dump"), "dump");
  if (ferret::robot_backends_to_yaml(again) != dump) __builtin_trap();
  return 0;
}
