// OctoMap .bt file -> OcTree: ferret's structure check, then OctoMap's reader.
#include <cstdint>

#include "ferret/core/error.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = ferret::fuzz::ScratchDir::instance().write("world.bt", data, size);
  try {
    (void)ferret::load_octree(path);
  } catch (const ferret::InputError&) {
  }
  return 0;
}
