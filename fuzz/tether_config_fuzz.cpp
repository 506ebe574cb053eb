// `ferret tether-sim --config FILE` YAML -> TetherRunConfig, on top of the defaults of
// config/mission.yaml's tether (L = 15 m, l_0 = 1 m) as the CLI starts from.
#include <cstdint>

#include "ferret/core/error.hpp"
#include "ferret/sim/tether_sim.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = ferret::fuzz::ScratchDir::instance().write("tether.yaml", data, size);
  auto config = ferret::sim::TetherRunConfig::for_tether(15.0, 1.0);
  try {
    ferret::sim::apply_tether_run_config(path, config);
  } catch (const ferret::InputError&) {
  }
  return 0;
}
