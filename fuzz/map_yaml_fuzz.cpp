// map_server YAML -> OccupancyMap2D, with a fixed valid image beside it (room.pgm);
// map_pgm_fuzz.cpp fuzzes the image under a fixed YAML.
#include <cstdint>

#include "ferret/core/error.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "fixtures.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& dir = ferret::fuzz::ScratchDir::instance();
  static const bool image_written = (dir.write("room.pgm", ferret::fuzz::room_pgm()), true);
  (void)image_written;
  const auto path = dir.write("map.yaml", data, size);
  try {
    (void)ferret::load_map_server(path);
  } catch (const ferret::InputError&) {
  }
  return 0;
}
