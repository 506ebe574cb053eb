// Experiment YAML -> ExperimentConfig, with a valid map (room.yaml + room.pgm), the same
// map with its own start and zones (searched.yaml, as ferret world generate-hidden
// writes them) and an empty mission (mission.yaml) beside it, so that inputs naming
// them get past the file lookup into the start, zone and sweep checks. `generate:`
// entries build maps in memory.
#include <cstdint>

#include "ferret/core/error.hpp"
#include "ferret/mission/experiment.hpp"
#include "fixtures.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& dir = ferret::fuzz::ScratchDir::instance();
  static const bool fixtures_written =
      (dir.write("room.pgm", ferret::fuzz::room_pgm()),
       dir.write("room.yaml", ferret::fuzz::room_yaml()),
       dir.write("searched.yaml",
                 ferret::fuzz::room_yaml() +
                     "search:\n  start: [1.0, 1.0, 0.0]\n  zones: {1: [1.5, 1.5, 3.0, 2.5]}\n"),
       dir.write("mission.yaml", "{}\n"), true);
  (void)fixtures_written;
  const auto path = dir.write("experiment.yaml", data, size);
  try {
    (void)ferret::load_experiment_config(path);
  } catch (const ferret::InputError&) {
  }
  return 0;
}
