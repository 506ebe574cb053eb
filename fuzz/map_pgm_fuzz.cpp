// PGM image (P5/P2, 8/16 bit) -> OccupancyMap2D under a fixed valid map_server YAML.
#include <cstdint>

#include "ferret/core/error.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "fixtures.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& dir = ferret::fuzz::ScratchDir::instance();
  static const auto yaml = dir.write("map.yaml", ferret::fuzz::room_yaml());
  dir.write("room.pgm", data, size);
  try {
    (void)ferret::load_map_server(yaml);
  } catch (const ferret::InputError&) {
  }
  return 0;
}
