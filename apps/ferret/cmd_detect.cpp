// `ferret detect marker`: fiducial markers (AprilTag 3 or OpenCV ArUco) in a camera
// image, with each marker's pose in the camera's optical frame. The `detect` group
// itself is shared with `detect landing` and `detect object` (cmd_detect.hpp).

#include "cmd_detect.hpp"

#include "command.hpp"

namespace ferret::cli {

CLI::App& detect_group(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    if (sub->get_name() == "detect") return *sub;
  auto* detect =
      app.add_subcommand("detect", "Detect markers, landing zones and objects in frames");
  detect->require_subcommand(1);
  return *detect;
}

}  // namespace ferret::cli
