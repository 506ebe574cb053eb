// Mission YAML (config/mission.yaml's format) -> MissionDocument: MissionConfig, the
// robots' backends and the UAV and miniUGV missions' keys.
#include <cstdint>
#include <optional>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/mission/mission_document.hpp"
#include "ferret/uav/uav_mission_config.hpp"
#include "ferret/ugv/ugv_mission_config.hpp"
#include "fuzz_support.hpp"

namespace {
std::string uav_mission_dump(const ferret::UavMissionOptions& o) {
  YAML::Emitter e;
  e << YAML::BeginMap;
  ferret::emit_uav_mission_options(e, o, true);
  e << YAML::EndMap;
  return e.c_str();
}
std::string ugv_mission_dump(const ferret::UgvMissionOptions& o) {
  YAML::Emitter e;
  e << YAML::BeginMap;
  ferret::emit_ugv_mission_options(e, o);
  e << YAML::EndMap;
  return e.c_str();
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = ferret::fuzz::ScratchDir::instance().write("mission.yaml", data, size);
  std::optional<ferret::RobotBackends> backends;
  ferret::UavMissionOptions uav;
  ferret::UgvMissionOptions ugv;
  try {
    const ferret::MissionDocument document = ferret::load_mission_document(path);
    // What `ferret config --dump` does next with a config that loaded.
    (void)ferret::mission_config_to_yaml(document.config);
    backends = document.backends;
    uav = document.uav_mission;
    ugv = document.ugv_mission;
    // A file without a uav section leaves the options unchecked; `ferret mission` checks
    // them before it flies (l_0 = 0 is a tether the miniUGV's commands take, the UAV's
    // hover release not: regression winch_at_the_entry_no_uav_section.yaml).
    uav.validate(path.string());
  } catch (const ferret::InputError&) {
    return 0;
  }
  // The dumps read back to themselves (outside the catch: a refusal here is a bug).
  const std::string dump = ferret::robot_backends_to_yaml(*backends);
  const auto again =
      ferret::robot_backends_from_yaml(ferret::yaml::load_string(dump, "dump"), "dump");
  if (ferret::robot_backends_to_yaml(again) != dump) __builtin_trap();
  const std::string uav_dump = uav_mission_dump(uav);
  ferret::UavMissionOptions uav_again;
  uav_again.tether = uav.tether;
  (void)ferret::read_uav_mission_options(ferret::yaml::load_string(uav_dump, "dump"), "dump",
                                         uav_again);
  if (uav_mission_dump(uav_again) != uav_dump) __builtin_trap();
  const std::string ugv_dump = ugv_mission_dump(ugv);
  ferret::UgvMissionOptions ugv_again;
  (void)ferret::read_ugv_mission_options(ferret::yaml::load_string(ugv_dump, "dump"), "dump",
                                         ugv_again);
  if (ugv_mission_dump(ugv_again) != ugv_dump) __builtin_trap();
  return 0;
}
