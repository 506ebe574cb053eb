// URDF text -> RobotDescription (urdfdom, the Gazebo <sensor> blocks, roles, meshes).
// Mesh references resolve beside the scratch folder, where nothing else lives.
#include <cstdint>

#include "ferret/core/error.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Through the file, as `load_robot` (the CLI's path) reads it: it also resolves
  // relative mesh paths against the file's folder.
  const auto path = ferret::fuzz::ScratchDir::instance().write("robot.urdf", data, size);
  try {
    (void)ferret::load_robot(path.string());
  } catch (const ferret::InputError&) {
  }
  return 0;
}
