// Tether trajectory YAML (entry, wrap points, snags, samples inline, scripted or from a
// CSV beside it: samples.csv is a valid one) -> TetherScenario.
#include <cstdint>

#include "ferret/core/error.hpp"
#include "ferret/sim/tether_sim.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& dir = ferret::fuzz::ScratchDir::instance();
  static const bool csv_written =
      (dir.write("samples.csv", "t,x,y,yaw\n0,0.5,0,0\n1,1.0,0,0\n2,1.5,0.5,0.7\n"), true);
  (void)csv_written;
  const auto path = dir.write("trajectory.yaml", data, size);
  try {
    (void)ferret::sim::load_tether_scenario(path);
  } catch (const ferret::InputError&) {
  }
  return 0;
}
