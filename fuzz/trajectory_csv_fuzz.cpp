// Tether trajectory CSV (`ferret tether-sim --trajectory FILE.csv`) -> TetherScenario.
#include <cstdint>

#include "ferret/core/error.hpp"
#include "ferret/sim/tether_sim.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = ferret::fuzz::ScratchDir::instance().write("trajectory.csv", data, size);
  try {
    (void)ferret::sim::load_tether_scenario(path);
  } catch (const ferret::InputError&) {
  }
  return 0;
}
