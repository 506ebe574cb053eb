#include "ferret/core/data_path.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "ferret/core/error.hpp"

namespace ferret {
namespace {
namespace fs = std::filesystem;

bool same_file(const fs::path& a, const fs::path& b) { return fs::equivalent(a, b); }

// The tests link the build tree's libferret_core: its data is the source tree, in the
// source tree's layout.
TEST(DataPath, TheBuildTreeLibraryReadsItsSourceTree) {
  const DataDir d = data_dir();
  EXPECT_TRUE(d.build_tree);
  EXPECT_TRUE(same_file(d.root, FERRET_SOURCE_DIR));
  const fs::path src(FERRET_SOURCE_DIR);
  EXPECT_TRUE(same_file(data_path("worlds/default.yaml"), src / "examples/worlds/default.yaml"));
  EXPECT_TRUE(same_file(data_path("models/m100.urdf"), src / "urdf/models/m100.urdf"));
  EXPECT_TRUE(
      same_file(data_path("plans/detour_ugv.json"), src / "examples/plans/detour_ugv.json"));
  EXPECT_TRUE(same_file(data_path("config/mission.yaml"), src / "config/mission.yaml"));
  EXPECT_TRUE(same_file(data_path("plot_experiment.py"), src / "examples/plot_experiment.py"));
}

TEST(DataPath, AMissingFileNamesThePathLookedAt) {
  try {
    (void)data_path("worlds/no_such_world.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("examples/worlds/no_such_world.yaml"), std::string::npos)
        << e.what();
  }
}

TEST(DataPath, FerretDataDirReplacesTheDirectoryInTheInstalledLayout) {
  const fs::path dir =
      fs::temp_directory_path() / ("ferret_data_path_test_" + std::to_string(::getpid()));
  fs::create_directories(dir / "worlds");
  std::ofstream(dir / "worlds" / "default.yaml") << "name: relocated\n";
  ::setenv("FERRET_DATA_DIR", dir.c_str(), 1);
  const DataDir d = data_dir();
  const fs::path p = data_path("worlds/default.yaml");
  EXPECT_THROW((void)data_path("models/m100.urdf"), InputError);  // not in the relocated dir
  ::unsetenv("FERRET_DATA_DIR");
  EXPECT_FALSE(d.build_tree);
  EXPECT_TRUE(same_file(p, dir / "worlds" / "default.yaml"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ferret
