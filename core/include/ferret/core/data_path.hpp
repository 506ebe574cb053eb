#pragma once
// The files ferret ships (robot models, example worlds and plans, the mission YAML,
// the plot script), found where the running ferret library is: an installed library
// (<prefix>/lib/libferret_core.so) reads <prefix>/share/ferret; the library in the
// build tree reads the source tree it was built from. A program linked against an
// installed ferret therefore never reads a source tree, wherever it runs.
//
// Installed layout (share/ferret/)    source tree
//   models/<name>.urdf                urdf/models/
//   worlds/<name>.yaml                examples/worlds/
//   plans/<file>                      examples/plans/
//   config/mission.yaml               config/
//   plot_experiment.py                examples/
//
// The environment variable FERRET_DATA_DIR, when set, replaces the directory (in the
// installed layout), for a relocated data directory.

#include <filesystem>
#include <string_view>

namespace ferret {

struct DataDir {
  std::filesystem::path root;  ///< share/ferret, or the source tree
  bool build_tree = false;     ///< true: `root` is a source tree (source-tree layout)
};

/// Where the data of the running ferret library is (see above).
[[nodiscard]] DataDir data_dir();

/// A shipped file by its installed-layout path ("worlds/default.yaml",
/// "models/m100.urdf", "config/mission.yaml"); relative to the working directory when
/// it lies below it, absolute otherwise. Throws InputError naming the path looked at
/// when there is no such file.
[[nodiscard]] std::filesystem::path data_path(std::string_view relative);

}  // namespace ferret
