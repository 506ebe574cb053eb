#include "ferret/planning/collision_checker.hpp"

#include <fcl/geometry/octree/octree.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision.h>
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <set>
#include <thread>

#include "ferret/core/error.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "test_maps.hpp"

namespace ferret {
namespace {

using test::cluttered_room;
using test::fill_box;

Pose3 pose(const Eigen::Vector3d& p, double yaw, double roll = 0.0) {
  Pose3 X = Pose3::Identity();
  X.translation() = p;
  X.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return X;
}

// Plain FCL on an OcTree as a user would call it (the pitfalls' reference behaviour).
bool raw_fcl_box_collides(const octomap::OcTree& source, const Eigen::Vector3d& size,
                          const Pose3& X) {
  auto tree = std::make_shared<const octomap::OcTree>(source);
  fcl::CollisionObjectd map(std::make_shared<fcl::OcTreed>(tree));
  fcl::CollisionObjectd box(std::make_shared<fcl::Boxd>(size), X);
  fcl::CollisionRequestd req;
  fcl::CollisionResultd res;
  fcl::collide(&map, &box, req, res);
  return res.isCollision();
}

struct AgreementCase {
  const char* name;
  std::size_t max_field_cells;
  bool floor_cut = false;  ///< leave the room's floor (top at z = 0) out of the field
};

class Agreement : public ::testing::TestWithParam<AgreementCase> {};

// The fast path never disagrees with FCL, for every robot shape, near and far from
// obstacles, with a fine and with a coarse distance field.
TEST_P(Agreement, FastPathEqualsFclOnRandomPoses) {
  const auto source = cluttered_room(11);
  CollisionMapOptions opt;
  opt.max_field_cells = GetParam().max_field_cells;
  if (GetParam().floor_cut) opt.field_floor_cut_z = 0.0;
  const auto map = CollisionMap::build(*source, opt);
  const std::vector<RobotShape> shapes{uav_shape(), uav_with_suspended_ugv_shape(1.2), ugv_shape()};
  Rng rng(5);
  int disagreements = 0, collisions = 0, n = 0;
  std::uint64_t fcl_calls = 0, parts = 0;
  for (const RobotShape& shape : shapes) {
    CollisionChecker checker(map, shape);
    for (int k = 0; k < 1500; ++k) {
      const Pose3 X = pose({rng.uniform(-3.3, 3.3), rng.uniform(-3.3, 3.3), rng.uniform(-0.1, 3.2)},
                           rng.uniform(-3.2, 3.2), rng.uniform(-0.3, 0.3));
      const bool fast = checker.in_collision(X);
      const bool exact = checker.in_collision_fcl(X);
      disagreements += fast != exact;
      collisions += exact;
      ++n;
    }
    fcl_calls += checker.stats().fcl_calls;
    parts += checker.stats().fast_free + checker.stats().fast_hit + checker.stats().fcl_calls;
  }
  EXPECT_EQ(disagreements, 0);
  // Both answers occur, and the fast path decides a good share of the parts.
  EXPECT_GT(collisions, n / 10);
  EXPECT_LT(collisions, n * 9 / 10);
  EXPECT_LT(fcl_calls, parts);
}

INSTANTIATE_TEST_SUITE_P(FieldResolutions, Agreement,
                         ::testing::Values(AgreementCase{"fine", 16'000'000},
                                           AgreementCase{"coarse", 5'000},
                                           AgreementCase{"floor_cut", 16'000'000, true}),
                         [](const auto& info) { return std::string(info.param.name); });

// The ground-robot fast path (2D band field, floor cut, field region) agrees with
// FCL too: poses on and off the floor, tilted and level, in and near obstacles.
TEST(Agreement, GroundRobotMapEqualsFcl) {
  const auto tree =
      test::hidden_space({{3, 4, 0, 6}, {7, 8, 2, 8}, {5.02, 5.33, 1.01, 1.29}}, {{9, 11, 1, 3}});
  HiddenSpaceFrame space;
  const auto map = ugv_collision_map(*tree, space);
  Rng rng(9);
  int disagreements = 0, collisions = 0, n = 0;
  CollisionChecker checker(map, ugv_shape());
  for (int k = 0; k < 6000; ++k) {
    const bool level = k % 3 != 0;
    const double z = level ? 0.0 : rng.uniform(-0.03, 0.08);
    const Pose3 X = pose({rng.uniform(-0.3, 12.3), rng.uniform(-0.3, 8.3), z},
                         rng.uniform(-3.2, 3.2), level ? 0.0 : rng.uniform(-0.4, 0.4));
    const bool exact = checker.in_collision_fcl(X);
    disagreements += checker.in_collision(X) != exact;
    collisions += exact;
    ++n;
  }
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(collisions, n / 10);
  EXPECT_LT(checker.stats().fcl_calls, checker.stats().queries / 2);
}

// The robots' URDF shapes (14 and 6 parts, rotated cylinders) agree with FCL too.
TEST(Agreement, UrdfShapesEqualFcl) {
  const auto map = CollisionMap::build(*cluttered_room(17));
  Rng rng(21);
  for (const char* model : {"m100.urdf", "miniugv.urdf"}) {
    const RobotShape urdf = robot_shape_from_description(load_robot_description(find_model(model)));
    CollisionChecker checker(map, urdf);
    int disagreements = 0, collisions = 0;
    for (int k = 0; k < 2000; ++k) {
      const Pose3 X = pose({rng.uniform(-3.3, 3.3), rng.uniform(-3.3, 3.3), rng.uniform(-0.1, 3.2)},
                           rng.uniform(-3.2, 3.2), rng.uniform(-0.3, 0.3));
      const bool exact = checker.in_collision_fcl(X);
      disagreements += checker.in_collision(X) != exact;
      collisions += exact;
    }
    EXPECT_EQ(disagreements, 0) << model;
    EXPECT_GT(collisions, 100) << model;
    EXPECT_LT(collisions, 1900) << model;
  }
}

TEST(CollisionMap, FieldIsALowerBoundOnTheTrueDistance) {
  octomap::OcTree tree(0.1);
  fill_box(tree, {0, 0, 0}, {0.3, 0.2, 0.1}, true);
  fill_box(tree, {1.0, -1.0, 0.5}, {1.1, -0.9, 0.6}, true);
  const auto map = CollisionMap::build(tree);
  // The exact distance to the union of the occupied voxel boxes, by brute force.
  std::vector<Eigen::AlignedBox3d> boxes;
  for (auto it = tree.begin_leafs(); it != tree.end_leafs(); ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const Eigen::Vector3d c(it.getX(), it.getY(), it.getZ());
    boxes.emplace_back(c.array() - 0.5 * it.getSize(), c.array() + 0.5 * it.getSize());
  }
  Rng rng(3);
  double worst_gap = 0.0;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector3d p{rng.uniform(-1.5, 2.5), rng.uniform(-2.5, 1.5), rng.uniform(-1.0, 2.0)};
    double exact = 1e9;
    for (const auto& b : boxes) exact = std::min(exact, b.exteriorDistance(p));
    const double lb = map->clearance_lower_bound_m(p);
    ASSERT_LE(lb, exact + 1e-12) << p.transpose();
    if (exact < 0.1) worst_gap = std::max(worst_gap, exact - lb);  // inside the field's grid
  }
  // Not uselessly loose: within two cell diagonals.
  EXPECT_LT(worst_gap, 2 * std::sqrt(3.0) * 0.1 + 1e-9);
}

// Pitfall: FCL treats unknown (never observed) space as free. The hidden-space
// policy "occupied" makes it solid inside the bounds, for FCL and the fast path alike.
TEST(CollisionMap, UnknownSpaceIsAPolicy) {
  octomap::OcTree tree(0.05);
  fill_box(tree, {0, 0, 0}, {2, 2, 0.3}, false);   // known free
  fill_box(tree, {0, 0, -0.05}, {4, 2, 0}, true);  // floor; x in [2, 4] is unknown above it
  const Pose3 in_unknown = pose({3.0, 1.0, 0.05}, 0.3);
  const Pose3 in_known_free = pose({1.0, 1.0, 0.05}, 0.3);
  const Eigen::Vector3d ugv = UgvGeometry{}.body_size_m;
  EXPECT_FALSE(raw_fcl_box_collides(tree, ugv, in_unknown));  // the trap

  CollisionChecker as_free(CollisionMap::build(tree), ugv_shape());
  EXPECT_FALSE(as_free.in_collision(in_unknown));

  CollisionMapOptions opt;
  opt.unknown = UnknownPolicy::kOccupied;
  opt.bounds = Aabb3{{0, 0, 0}, {4, 2, 0.3}};
  CollisionChecker as_occupied(CollisionMap::build(tree, opt), ugv_shape());
  EXPECT_TRUE(as_occupied.in_collision(in_unknown));
  EXPECT_TRUE(as_occupied.in_collision_fcl(in_unknown));
  EXPECT_FALSE(as_occupied.in_collision(in_known_free));
  EXPECT_FALSE(as_occupied.in_collision_fcl(in_known_free));
  // Next to the unknown region: the box reaches 0.065 m from its centre.
  EXPECT_TRUE(as_occupied.in_collision(pose({2.0 - 0.06, 1.0, 0.05}, 0.0)));
  EXPECT_FALSE(as_occupied.in_collision(pose({2.0 - 0.07, 1.0, 0.05}, 0.0)));
  // Outside the bounds unknown stays free (as FCL sees it).
  EXPECT_FALSE(as_occupied.in_collision(pose({3.0, 1.0, 1.0}, 0.0)));

  opt.bounds.reset();
  EXPECT_THROW((void)CollisionMap::build(tree, opt), InputError);
  opt.bounds = Aabb3{{0, 0, 0}, {1e6, 2, 0.3}};  // beyond OctoMap's key range
  EXPECT_THROW((void)CollisionMap::build(tree, opt), InputError);
}

// Pitfall: after updateNode(..., lazy_eval=true) the inner nodes keep stale values
// and FCL skips the subtree. The snapshot always updates inner occupancy.
TEST(CollisionMap, LazilyUpdatedLeavesAreNotMissed) {
  octomap::OcTree tree(0.1);
  fill_box(tree, {0, 0, 0}, {1.6, 1.6, 1.6}, false);  // free, pruned into large nodes
  tree.updateNode(0.85, 0.85, 0.85, true, /*lazy_eval=*/true);
  tree.updateNode(0.85, 0.85, 0.85, true, true);
  tree.updateNode(0.85, 0.85, 0.85, true, true);
  const Pose3 X = pose({0.85, 0.85, 0.85}, 0.0);
  const Eigen::Vector3d probe{0.05, 0.05, 0.05};
  EXPECT_FALSE(raw_fcl_box_collides(tree, probe, X));  // the trap: the stale parent is "free"
  RobotShape small{"probe", {}};
  ShapePart part;
  part.box_size_m = probe;
  small.parts.push_back(part);
  CollisionChecker checker(CollisionMap::build(tree), small);
  EXPECT_TRUE(checker.in_collision(X));
  EXPECT_TRUE(checker.in_collision_fcl(X));
}

// Pitfall: fcl::distance on an empty octree segfaults (fcl#473). The checker never
// calls it; an empty map is simply free everywhere.
TEST(CollisionMap, EmptyMapIsFree) {
  octomap::OcTree tree(0.1);
  const auto map = CollisionMap::build(tree);
  EXPECT_EQ(map->occupied_leaf_count(), 0u);
  CollisionChecker checker(map, uav_with_suspended_ugv_shape(2.0));
  EXPECT_FALSE(checker.in_collision(pose({0, 0, 0}, 0)));
  EXPECT_FALSE(checker.in_collision_fcl(pose({0, 0, 0}, 0)));
  EXPECT_TRUE(std::isinf(checker.clearance_lower_bound_m(pose({0, 0, 0}, 0))));
}

TEST(CollisionMap, OptionKeysAreEqualExactlyWhenTheOptionsAre) {
  CollisionMapOptions a;
  a.unknown = UnknownPolicy::kOccupied;
  a.bounds = Aabb3{{0, 0, 0}, {12, 8, 0.2}};
  a.field_floor_cut_z = 0.0;
  const std::string key = collision_map_options_key(a);
  EXPECT_EQ(collision_map_options_key(a), key);
  std::vector<CollisionMapOptions> changed(7, a);
  changed[0].unknown = UnknownPolicy::kFree;
  changed[1].bounds->hi.z() = std::nextafter(0.2, 1.0);  // one bit apart is another map
  changed[2].max_field_cells = a.max_field_cells - 1;
  changed[3].max_fill_face_voxels = a.max_fill_face_voxels + 1;
  changed[4].field_region = a.bounds;
  changed[5].field_floor_cut_z.reset();
  changed[6].ground_band_z = std::pair{0.0, 0.05};
  std::set<std::string> keys{key};
  for (const CollisionMapOptions& o : changed) keys.insert(collision_map_options_key(o));
  EXPECT_EQ(keys.size(), changed.size() + 1);
  // The bounds and the field region are different fields, even holding the same box.
  CollisionMapOptions swapped = a;
  swapped.bounds.reset();
  swapped.field_region = a.bounds;
  EXPECT_NE(collision_map_options_key(swapped), collision_map_options_key(changed[4]));
  EXPECT_NE(collision_map_options_key(swapped), key);
}

TEST(CollisionMap, PrunedOccupiedBlocksKeepTheirExtent) {
  octomap::OcTree tree(0.1);
  fill_box(tree, {0, 0, 0}, {1.6, 1.6, 1.6}, true);  // prunes to one node of 1.6 m
  const auto map = CollisionMap::build(tree);
  EXPECT_LT(map->occupied_leaf_count(), 10u);
  CollisionChecker checker(map, ugv_shape());
  EXPECT_TRUE(checker.in_collision(pose({0.8, 0.8, 0.5}, 0)));
  EXPECT_TRUE(checker.in_collision(pose({1.6 + 0.06, 0.8, 0.5}, 0)));   // the box reaches in
  EXPECT_FALSE(checker.in_collision(pose({1.6 + 0.07, 0.8, 0.5}, 0)));  // just clear
}

// One checker per thread on a shared snapshot; a writer publishes new snapshots
// meanwhile. Every reader's answer equals the answer for the snapshot it held.
TEST(MapSnapshots, ReadersKeepAConsistentSnapshotWhileTheMapChanges) {
  const auto before_tree = cluttered_room(2);
  auto after_tree = std::make_unique<octomap::OcTree>(*before_tree);
  fill_box(*after_tree, {-1, -1, 0}, {1, 1, 2}, true);  // a new pillar in the middle
  after_tree->updateInnerOccupancy();
  const auto before = CollisionMap::build(*before_tree);
  const auto after = CollisionMap::build(*after_tree);
  const Pose3 X = pose({0, 0, 1}, 0);
  {
    CollisionChecker a(before, uav_shape()), b(after, uav_shape());
    ASSERT_FALSE(a.in_collision(X));
    ASSERT_TRUE(b.in_collision(X));
  }
  MapSnapshots snapshots(before);
  std::atomic<int> wrong{0}, queries{0};
  std::atomic<bool> stop{false};
  std::vector<std::thread> readers;
  for (int t = 0; t < 3; ++t) {
    readers.emplace_back([&] {
      while (!stop) {
        auto snap = snapshots.current();
        CollisionChecker checker(snap, uav_shape());
        for (int k = 0; k < 20; ++k) {
          const bool hit = checker.in_collision(X);
          if (hit != (snap == after)) ++wrong;
          ++queries;
        }
      }
    });
  }
  for (int k = 0; k < 40; ++k) {
    snapshots.publish(k % 2 ? before : after);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  stop = true;
  for (auto& r : readers) r.join();
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(queries, 0);
}

}  // namespace
}  // namespace ferret
