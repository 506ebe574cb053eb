// World YAML -> WorldSpec -> OcTree (the .yaml path of load_or_build_octree). The
// node budget is lowered from 60 million so that one input stays within libFuzzer's
// memory limit; the budget check itself is what is exercised.
#include <cstdint>

#include "ferret/core/error.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const ferret::WorldSpec world =
        ferret::parse_world(ferret::fuzz::as_string(data, size), "world.yaml");
    ferret::WorldBuildOptions options;
    options.max_nodes = 200'000;
    (void)ferret::build_world_octree(world, options);
  } catch (const ferret::InputError&) {
  }
  return 0;
}
