#include "ferret/mapping/world_octree.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <fstream>
#include <sstream>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"
#include "support/cli_runner.hpp"

namespace ferret {
namespace {
using test::TempDir;
using ::testing::HasSubstr;

const std::string kSmallWorld = std::string(FERRET_SOURCE_DIR) + "/examples/worlds/small.yaml";

SliceOptions at_z(double z_m, double half_band_m = 0.0) {
  SliceOptions o;
  o.z_m = z_m;
  o.half_band_m = half_band_m;
  return o;
}
SliceOptions windowed(double z_m, const Eigen::Vector4d& window_m) {
  SliceOptions o = at_z(z_m);
  o.window_m = window_m;
  return o;
}

enum class Voxel { kUnknown, kFree, kOccupied };
Voxel voxel_at(const octomap::OcTree& t, double x, double y, double z) {
  const octomap::OcTreeNode* n = t.search(x, y, z);
  if (n == nullptr) return Voxel::kUnknown;
  return t.isNodeOccupied(n) ? Voxel::kOccupied : Voxel::kFree;
}

class SmallWorld : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    world_ = new WorldSpec(load_world(kSmallWorld));
    tree_ = build_world_octree(*world_).release();
  }
  static void TearDownTestSuite() {
    delete tree_;
    delete world_;
  }
  static WorldSpec* world_;
  static octomap::OcTree* tree_;
};
WorldSpec* SmallWorld::world_ = nullptr;
octomap::OcTree* SmallWorld::tree_ = nullptr;

TEST_F(SmallWorld, HandPickedVoxels) {
  const auto& t = *tree_;
  EXPECT_EQ(voxel_at(t, -0.55, -1.3, 0.15), Voxel::kOccupied);   // cellar wall
  EXPECT_EQ(voxel_at(t, 0.5, -1.0, 0.15), Voxel::kFree);         // cellar interior
  EXPECT_EQ(voxel_at(t, 0.5, -1.0, 0.35), Voxel::kOccupied);     // roof
  EXPECT_EQ(voxel_at(t, -0.55, -1.0, 0.03), Voxel::kFree);       // in the opening
  EXPECT_EQ(voxel_at(t, -0.55, -1.0, 0.09), Voxel::kOccupied);   // lintel (opening is 7.5 cm)
  EXPECT_EQ(voxel_at(t, -0.55, -0.91, 0.03), Voxel::kOccupied);  // beside the 15 cm opening
  EXPECT_EQ(voxel_at(t, 0.0, 0.0, -0.1), Voxel::kOccupied);      // ground
  EXPECT_EQ(voxel_at(t, 0.0, 0.0, 0.0125), Voxel::kFree);        // first layer above ground
  EXPECT_EQ(voxel_at(t, 0.0, 0.0, -0.0125), Voxel::kOccupied);   // last layer of ground
  EXPECT_EQ(voxel_at(t, 2.0, 2.0, 0.4), Voxel::kOccupied);       // post
  EXPECT_EQ(voxel_at(t, 2.25, 2.0, 0.4), Voxel::kFree);          // beside the post (r = 0.2)
  EXPECT_EQ(voxel_at(t, 1.0, -0.7, 0.0125), Voxel::kOccupied);   // the canister
  EXPECT_EQ(voxel_at(t, 0.0, 0.0, 1.2), Voxel::kUnknown);        // above the ceiling
  EXPECT_EQ(voxel_at(t, 3.5, 0.0, 0.5), Voxel::kUnknown);        // beyond the bounds
}

TEST_F(SmallWorld, EveryVoxelAgreesWithGroundTruthAtItsCentre) {
  // The top-down builder against the plain point test, at 20000 random voxels.
  Rng rng(5);
  const double res = tree_->getResolution();
  int checked = 0;
  for (int k = 0; k < 20000; ++k) {
    const octomap::OcTreeKey key =
        tree_->coordToKey(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(-0.2, 1.0));
    const octomap::point3d c = tree_->keyToCoord(key);
    const Eigen::Vector3d p(c.x(), c.y(), c.z());
    const Voxel v = voxel_at(*tree_, p.x(), p.y(), p.z());
    if (!world_->in_bounds(p)) {
      EXPECT_EQ(v, Voxel::kUnknown);
      continue;
    }
    ASSERT_EQ(v, world_->is_solid(p) ? Voxel::kOccupied : Voxel::kFree)
        << p.transpose() << " res " << res;
    ++checked;
  }
  EXPECT_GT(checked, 19000);
}

TEST_F(SmallWorld, NodeBudgetRefusesTooFineAWorld) {
  // The small world needs about 12 700 nodes at 2.5 cm.
  WorldBuildOptions options;
  options.max_nodes = 5000;
  try {
    (void)build_world_octree(*world_, options);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "resolution_m");
    EXPECT_THAT(e.source(), HasSubstr("small.yaml"));
  }
  options.max_nodes = 20000;
  EXPECT_GT(build_world_octree(*world_, options)->size(), 5000u);
}

// 4-connected path of free cells between two world points.
bool connected(const OccupancyMap2D& m, const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  std::vector<char> seen(m.cells.size(), 0);
  std::deque<Cell> queue{m.geometry.cell_at(from.x(), from.y())};
  const Cell goal = m.geometry.cell_at(to.x(), to.y());
  while (!queue.empty()) {
    const Cell c = queue.front();
    queue.pop_front();
    if (!m.is_free(c) || seen[m.geometry.index(c)]) continue;
    seen[m.geometry.index(c)] = 1;
    if (c == goal) return true;
    for (const Cell d : {Cell{1, 0}, Cell{-1, 0}, Cell{0, 1}, Cell{0, -1}})
      queue.push_back({c.i + d.i, c.j + d.j});
  }
  return false;
}

TEST_F(SmallWorld, OpeningIsPassableAtGroundLevelOnly) {
  // Flood fill the 2D slice from outside the cellar: the interior is reached
  // through the opening at z = 3 cm, not at 10 cm (above the 7.5 cm opening).
  const Eigen::Vector2d outside(-1.5, -1.0), inside(0.5, -1.0);
  EXPECT_TRUE(connected(slice_octree(*tree_, at_z(0.03)), outside, inside));
  EXPECT_FALSE(connected(slice_octree(*tree_, at_z(0.10)), outside, inside));
}

TEST(DefaultWorld, BothHiddenSpacesAreEnteredOnlyThroughTheirOpenings) {
  const WorldSpec w = load_world(FERRET_SOURCE_DIR "/examples/worlds/default.yaml");
  ASSERT_EQ(w.hidden_spaces.size(), 2u);
  ASSERT_EQ(w.objects.size(), 1u);
  EXPECT_EQ(w.hidden_spaces[w.objects[0].hidden_space].name, "house_void");
  ASSERT_TRUE(w.drop_zone.has_value());
  const auto tree = build_world_octree(w);
  for (const HiddenSpace& h : w.hidden_spaces) {
    EXPECT_DOUBLE_EQ(h.opening_width_m, 0.15);
    EXPECT_DOUBLE_EQ(h.opening_height_m, 0.07);
    const Eigen::Vector2d into(std::cos(h.entry_yaw_rad), std::sin(h.entry_yaw_rad));
    const Eigen::Vector2d outside = h.p_WE.head<2>() - 0.4 * into,
                          inside = h.p_WE.head<2>() + 0.6 * into;
    auto slice = [&](double z) {
      SliceOptions o = at_z(z);
      o.window_m = hidden_space_window(w, h.name, 0.5, "test");
      return slice_octree(*tree, o);
    };
    EXPECT_TRUE(connected(slice(0.03), outside, inside)) << h.name;
    EXPECT_FALSE(connected(slice(0.09), outside, inside)) << h.name;
  }
}

TEST_F(SmallWorld, SliceMatchesVoxels) {
  const OccupancyMap2D m = slice_octree(*tree_, at_z(0.03, 0.0));
  const double res = tree_->getResolution();
  EXPECT_DOUBLE_EQ(m.geometry.resolution_m, res);
  // Cell edges on voxel edges, covering the bounds.
  EXPECT_NEAR(m.geometry.origin_x_m, -3.0, 1e-9);
  EXPECT_EQ(m.geometry.width, 240);
  EXPECT_EQ(m.state_at(-0.55, -1.3), CellState::kOccupied);
  EXPECT_EQ(m.state_at(0.5, -1.0), CellState::kFree);
  EXPECT_EQ(m.state_at(-0.55, -1.0), CellState::kFree);
  EXPECT_EQ(m.state_at(2.0, 2.0), CellState::kOccupied);
  EXPECT_EQ(m.count(CellState::kUnknown), 0u);  // the world is known everywhere in its bounds
  // Every cell equals the voxel at (cell centre, 0.03).
  for (int j = 0; j < m.geometry.height; j += 7)
    for (int i = 0; i < m.geometry.width; i += 3) {
      const auto c = m.geometry.center({i, j});
      const bool occ = voxel_at(*tree_, c.x(), c.y(), 0.03) == Voxel::kOccupied;
      ASSERT_EQ(m.at({i, j}) == CellState::kOccupied, occ) << i << "," << j;
    }
}

TEST_F(SmallWorld, WindowCutsTheSliceOnVoxelEdges) {
  const OccupancyMap2D full = slice_octree(*tree_, at_z(0.03, 0.0));
  const OccupancyMap2D m =
      slice_octree(*tree_, windowed(0.03, Eigen::Vector4d(-1.01, -2.0, 0.0, -0.5)));
  EXPECT_NEAR(m.geometry.origin_x_m, -1.025, 1e-9);  // widened to the voxel edge below -1.01
  EXPECT_NEAR(m.geometry.origin_y_m, -2.0, 1e-9);
  EXPECT_EQ(m.geometry.width, 41);
  EXPECT_EQ(m.geometry.height, 60);
  for (std::size_t k = 0; k < m.cells.size(); ++k) {
    const Eigen::Vector2d c = m.geometry.center(m.geometry.cell_of_index(k));
    ASSERT_EQ(m.cells[k], full.state_at(c.x(), c.y())) << k;
  }
  // The cellar's enclosure spans x [-0.6, 1.6], y [-1.7, -0.3].
  const Eigen::Vector4d w = hidden_space_window(*world_, "cellar", 0.5, "--space");
  EXPECT_TRUE(w.isApprox(Eigen::Vector4d(-1.1, -2.2, 2.1, 0.2))) << w.transpose();
  EXPECT_THROW((void)hidden_space_window(*world_, "attic", 0.5, "--space"), InputError);
  EXPECT_THROW((void)slice_octree(*tree_, windowed(0.03, Eigen::Vector4d(5, 5, 6, 6))), InputError);
  EXPECT_THROW((void)slice_octree(*tree_, windowed(0.03, Eigen::Vector4d(1, 0, 0, 1))), InputError);
  EXPECT_THROW((void)requested_slice_window({1, 2, 3, 4}, "cellar", *world_), InputError);
  EXPECT_THROW((void)requested_slice_window({}, "cellar", std::nullopt), InputError);
  EXPECT_FALSE(requested_slice_window({}, "", std::nullopt).has_value());
}

TEST(Slice, BandAndUnknownRules) {
  // Hand-made tree (0.1 m): column A occupied at layer 0; B free at layers 0 and 1;
  // C free at layer 0 only; D occupied at layer 1 only.
  octomap::OcTree t(0.1);
  t.updateNode(0.05, 0.05, 0.05, true);
  t.updateNode(0.15, 0.05, 0.05, false);
  t.updateNode(0.15, 0.05, 0.15, false);
  t.updateNode(0.25, 0.05, 0.05, false);
  t.updateNode(0.35, 0.05, 0.15, true);
  const OccupancyMap2D one = slice_octree(t, at_z(0.05, 0.0));
  ASSERT_EQ(one.geometry.width, 4);
  ASSERT_EQ(one.geometry.height, 1);
  EXPECT_NEAR(one.geometry.origin_x_m, 0.0, 1e-9);
  EXPECT_EQ(one.at({0, 0}), CellState::kOccupied);
  EXPECT_EQ(one.at({1, 0}), CellState::kFree);
  EXPECT_EQ(one.at({2, 0}), CellState::kFree);
  EXPECT_EQ(one.at({3, 0}), CellState::kUnknown);
  // Band [0.06, 0.14] spans layers 0 and 1: C is half unknown, D occupied above.
  const OccupancyMap2D two = slice_octree(t, at_z(0.1, 0.04));
  EXPECT_EQ(two.at({0, 0}), CellState::kOccupied);
  EXPECT_EQ(two.at({1, 0}), CellState::kFree);
  EXPECT_EQ(two.at({2, 0}), CellState::kUnknown);
  EXPECT_EQ(two.at({3, 0}), CellState::kOccupied);
}

TEST(Slice, CoarseLeavesCoverTheirCells) {
  // A pruned 8-voxel free cube must make 2 x 2 free cells.
  octomap::OcTree t(0.1);
  for (double x : {0.05, 0.15})
    for (double y : {0.05, 0.15})
      for (double z : {0.05, 0.15}) t.updateNode(x, y, z, -2.0f);
  t.updateNode(0.25, 0.05, 0.05, true);
  t.prune();
  const OccupancyMap2D m = slice_octree(t, at_z(0.05, 0.0));
  ASSERT_EQ(m.geometry.width, 3);
  ASSERT_EQ(m.geometry.height, 2);
  EXPECT_EQ(m.count(CellState::kFree), 4u);
  EXPECT_EQ(m.at({2, 0}), CellState::kOccupied);
  EXPECT_EQ(m.at({2, 1}), CellState::kUnknown);
}

TEST_F(SmallWorld, BinaryAndFullRoundTrips) {
  TempDir dir;
  for (const std::string name : {"w.bt", "w.ot"}) {
    save_octree(*tree_, dir / name);
    const auto back = load_octree(dir / name);
    EXPECT_EQ(back->size(), tree_->size()) << name;
    EXPECT_DOUBLE_EQ(back->getResolution(), tree_->getResolution());
    std::size_t leaves = 0;
    for (auto it = tree_->begin_leafs(), end = tree_->end_leafs(); it != end; ++it, ++leaves) {
      const octomap::OcTreeNode* n = back->search(it.getKey(), it.getDepth());
      ASSERT_NE(n, nullptr);
      // The builder writes clamped values only, so even .bt keeps them exactly.
      ASSERT_EQ(n->getLogOdds(), it->getLogOdds()) << name;
    }
    EXPECT_EQ(back->getNumLeafNodes(), leaves);
  }
  EXPECT_EQ(dir.count(), 2u);
}

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
void write_all(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

void expect_bad_octree(const std::string& path, const std::string& field_part) {
  try {
    (void)load_octree(path);
    FAIL() << "expected InputError (" << field_part << ")";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), path);
    EXPECT_THAT(e.field(), HasSubstr(field_part)) << e.what();
  }
}

TEST_F(SmallWorld, TruncatedAndGarbageOctreeFilesAreInputErrors) {
  TempDir dir;
  for (const std::string ext : {".bt", ".ot"}) {
    const std::string good = dir / ("good" + ext), bad = dir / ("bad" + ext);
    save_octree(*tree_, good);
    const std::string bytes = read_all(good);
    const std::size_t data = bytes.find("\ndata\n") + 6;
    ASSERT_GT(bytes.size(), data + 100);
    // Truncated anywhere in the data, including one byte short.
    for (const std::size_t cut :
         {data + 1, data + 50, (data + bytes.size()) / 2, bytes.size() - 1}) {
      write_all(bad, bytes.substr(0, cut));
      expect_bad_octree(bad, "data");
    }
    // Truncated inside the header.
    write_all(bad, bytes.substr(0, data - 8));
    expect_bad_octree(bad, "header");
    // A trailing extra byte.
    write_all(bad, bytes + "x");
    expect_bad_octree(bad, "data");
    // 10 MB of all-ones data: every node claims eight inner children. OctoMap's
    // own reader overflows its stack on this (measured); the validator stops at depth 16.
    write_all(bad, bytes.substr(0, data) + std::string(10'000'000, '\xff'));
    expect_bad_octree(bad, "data");
    // Random garbage after the header.
    Rng rng(ext == ".bt" ? 1 : 2);
    std::string garbage(5000, '\0');
    for (char& c : garbage) c = static_cast<char>(rng.uniform_int(0, 255));
    write_all(bad, bytes.substr(0, data) + garbage);
    EXPECT_THROW((void)load_octree(bad), InputError);
  }
}

TEST_F(SmallWorld, MutatedOctreeFilesLoadOrFailCleanly) {
  // 150 random byte changes in the data of each format: every result is a tree
  // of the declared size or an InputError, never a crash or another exception.
  TempDir dir;
  Rng rng(17);
  for (const std::string ext : {".bt", ".ot"}) {
    const std::string good = dir / ("good" + ext), bad = dir / ("bad" + ext);
    save_octree(*tree_, good);
    const std::string bytes = read_all(good);
    const std::size_t data = bytes.find("\ndata\n") + 6;
    int loaded = 0, rejected = 0;
    for (int k = 0; k < 150; ++k) {
      std::string mutated = bytes;
      const auto at = static_cast<std::size_t>(rng.uniform_int(
          static_cast<std::int64_t>(data), static_cast<std::int64_t>(bytes.size()) - 1));
      mutated[at] = static_cast<char>(mutated[at] ^ static_cast<char>(rng.uniform_int(1, 255)));
      write_all(bad, mutated);
      try {
        const auto t = load_octree(bad);
        EXPECT_EQ(t->size(), tree_->size());
        ++loaded;
      } catch (const InputError&) {
        ++rejected;
      }
    }
    EXPECT_GT(rejected, 0) << ext;
    EXPECT_EQ(loaded + rejected, 150);
  }
}

TEST(OctreeFiles, BadHeadersNameTheField) {
  TempDir dir;
  const std::string p = dir / "x.bt";
  const std::string magic = "# Octomap OcTree binary file\n";
  auto check = [&](const std::string& bytes, const std::string& field) {
    write_all(p, bytes);
    expect_bad_octree(p, field);
  };
  check("", "header");
  check("hello\n", "header");
  check(magic + "id OcTree\nsize -5\nres 0.1\ndata\n", "header.size");
  check(magic + "id OcTree\nsize 5\nres -0.1\ndata\n", "header.res");
  check(magic + "id OcTree\nsize 5\nres nan\ndata\n", "header.res");
  check(magic + "id ColorOcTree\nsize 5\nres 0.1\ndata\n", "header.id");
  check(magic + "id OcTree\nres 0.1\ndata\n", "header.size");
  check(magic + "id OcTree\nsize 5\nres 0.1\n", "header");
  // A header promising 4 billion nodes over 2 bytes of data.
  check(magic + "id OcTree\nsize 4000000000\nres 0.1\ndata\n" + std::string{'\x01', '\x00'},
        "header.size");
  check(magic + "id OcTree\nsize 1\nres 0.1\ndata\n", "data");
  // The .ot header is a different first line.
  write_all(dir / "x.ot", magic + "id OcTree\nsize 0\nres 0.1\ndata\n");
  expect_bad_octree(dir / "x.ot", "header");
  EXPECT_THROW((void)load_octree(dir / "x.txt"), InputError);
  EXPECT_THROW((void)load_octree(dir / "missing.bt"), InputError);
}

TEST(OctreeFiles, EmptyTreeRoundTrips) {
  TempDir dir;
  const octomap::OcTree empty(0.2);
  save_octree(empty, dir / "e.bt");
  const auto back = load_octree(dir / "e.bt");
  EXPECT_EQ(back->size(), 0u);
  EXPECT_DOUBLE_EQ(back->getResolution(), 0.2);
  EXPECT_THROW(save_octree(empty, dir / "e.png"), InputError);
  EXPECT_EQ(dir.count(), 1u);
}

// A 2D map stands as walls on a floor: every voxel of a hand-made map checked at its
// centre, above, below and beside it.
TEST(ExtrudeMap2D, WallsFreeSpaceFloorAndUnknownAtTheirCells) {
  // 4 x 3 cells of 0.1 m from (-0.2, 0.3): row j = 0 at the bottom.
  OccupancyMap2D map = OccupancyMap2D::filled({-0.2, 0.3, 0.1, 4, 3}, CellState::kFree);
  map.at({1, 1}) = CellState::kOccupied;
  map.at({3, 2}) = CellState::kUnknown;
  Map2DExtrusion e;
  e.height_m = 0.3;  // three layers
  const auto tree = extrude_map_2d(map, "m.yaml", e);
  EXPECT_DOUBLE_EQ(tree->getResolution(), 0.1);
  const auto centre = [&](int i, int j) {
    return std::pair{-0.2 + 0.1 * i + 0.05, 0.3 + 0.1 * j + 0.05};
  };
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 4; ++i) {
      const auto [x, y] = centre(i, j);
      const CellState s = map.at({i, j});
      const Voxel above = s == CellState::kOccupied ? Voxel::kOccupied
                          : s == CellState::kFree   ? Voxel::kFree
                                                    : Voxel::kUnknown;
      for (double z : {0.05, 0.15, 0.25})
        EXPECT_EQ(voxel_at(*tree, x, y, z), above) << i << "," << j << " z " << z;
      // The floor under every known cell; nothing above the walls' height.
      EXPECT_EQ(voxel_at(*tree, x, y, -0.05),
                s == CellState::kUnknown ? Voxel::kUnknown : Voxel::kOccupied);
      EXPECT_EQ(voxel_at(*tree, x, y, 0.35), Voxel::kUnknown);
      EXPECT_EQ(voxel_at(*tree, x, y, -0.15), Voxel::kUnknown);
    }
  }
  // Beside the map: unknown.
  EXPECT_EQ(voxel_at(*tree, -0.25, 0.35, 0.05), Voxel::kUnknown);
  EXPECT_EQ(voxel_at(*tree, 0.25, 0.35, 0.05), Voxel::kUnknown);
  // Its slice at the floor is the map again.
  SliceOptions at_floor = at_z(0.05);
  at_floor.window_m = Eigen::Vector4d(-0.2, 0.3, 0.2, 0.6);
  const OccupancyMap2D slice = slice_octree(*tree, at_floor);
  ASSERT_EQ(slice.geometry.width, 4);
  ASSERT_EQ(slice.geometry.height, 3);
  EXPECT_NEAR(slice.geometry.origin_x_m, -0.2, 1e-9);
  EXPECT_NEAR(slice.geometry.origin_y_m, 0.3, 1e-9);
  EXPECT_EQ(slice.cells, map.cells);
}

TEST(ExtrudeMap2D, AnOriginOffTheVoxelGridMovesLessThanHalfACell) {
  OccupancyMap2D map = OccupancyMap2D::filled({0.13, -0.04, 0.1, 2, 1}, CellState::kFree);
  map.at({1, 0}) = CellState::kOccupied;
  const auto tree = extrude_map_2d(map, "m.yaml");
  // Cell (1, 0) spans x 0.23..0.33: its voxel is x 0.2..0.3, whose centre lies in the cell.
  // In y the cell spans -0.04..0.06, its voxel 0..0.1.
  EXPECT_EQ(voxel_at(*tree, 0.25, 0.05, 0.05), Voxel::kOccupied);
  EXPECT_EQ(voxel_at(*tree, 0.15, 0.05, 0.05), Voxel::kFree);
  EXPECT_EQ(voxel_at(*tree, 0.35, 0.05, 0.05), Voxel::kUnknown);
  EXPECT_EQ(voxel_at(*tree, 0.25, -0.05, 0.05), Voxel::kUnknown);
}

TEST(ExtrudeMap2D, ImpossibleMapsAreRefusedNamingTheField) {
  const auto field_of = [](const OccupancyMap2D& m, const Map2DExtrusion& e = {}) {
    try {
      (void)extrude_map_2d(m, "m.yaml", e);
    } catch (const InputError& err) {
      EXPECT_EQ(err.source(), "m.yaml");
      return err.field();
    }
    return std::string("(accepted)");
  };
  EXPECT_EQ(field_of(OccupancyMap2D::filled({0.0, 0.0, 1e-5, 2, 2}, CellState::kFree)),
            "resolution");
  // Beyond OctoMap's key range: 2^15 cells of 0.05 m is 1638 m.
  EXPECT_EQ(field_of(OccupancyMap2D::filled({1700.0, 0.0, 0.05, 2, 2}, CellState::kFree)),
            "origin");
  EXPECT_EQ(field_of(OccupancyMap2D::filled({-1637.0, 0.0, 0.05, 2, 2}, CellState::kFree)),
            "(accepted)");
  Map2DExtrusion small;
  small.max_voxels = 100;  // 10 x 10 known cells x (1 floor + 10 layers) = 1100
  EXPECT_EQ(field_of(OccupancyMap2D::filled({0.0, 0.0, 0.05, 10, 10}, CellState::kFree), small),
            "resolution");
  // Unknown cells cost nothing.
  EXPECT_EQ(field_of(OccupancyMap2D::filled({0.0, 0.0, 0.05, 10, 10}, CellState::kUnknown), small),
            "(accepted)");
  Map2DExtrusion flat;
  flat.height_m = std::nan("");
  EXPECT_EQ(field_of(OccupancyMap2D::filled({0.0, 0.0, 0.05, 2, 2}, CellState::kFree), flat),
            "height_m");
}

}  // namespace
}  // namespace ferret
