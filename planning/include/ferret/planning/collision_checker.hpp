#pragma once
// Collision queries of a robot shape against a CollisionMap snapshot.
//
// The fast path answers from the snapshot's distance field: a part whose covering
// spheres all clear the nearest occupied voxel by more than their radius is free,
// and a part whose centre lies in an occupied voxel collides. Everything else goes
// to FCL's octree collide, so the answer always equals plain FCL's (tests and
// bench/collision_bench.cpp count disagreements; there are none by construction).
//
// A checker owns FCL collision objects with mutable transforms: use one per thread.

#include <cstdint>
#include <memory>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/planning/collision_map.hpp"
#include "ferret/planning/robot_shape.hpp"

namespace ferret {

class CollisionChecker {
 public:
  CollisionChecker(std::shared_ptr<const CollisionMap> map, RobotShape shape);
  ~CollisionChecker();
  CollisionChecker(const CollisionChecker&) = delete;
  CollisionChecker& operator=(const CollisionChecker&) = delete;

  /// Whether the robot at X_WB overlaps an occupied voxel (after the unknown policy).
  [[nodiscard]] bool in_collision(const Pose3& X_WB);
  /// The same answer from FCL alone (the reference the fast path must match).
  [[nodiscard]] bool in_collision_fcl(const Pose3& X_WB);
  /// A lower bound on the clearance between the robot at X_WB and the map (0 when
  /// it may touch); from the distance field only, never from fcl::distance (which
  /// crashes on an empty tree, fcl#473, and is wrong for boxes, fcl#639).
  [[nodiscard]] double clearance_lower_bound_m(const Pose3& X_WB) const;

  /// Switches to another snapshot (a newer map).
  void set_map(std::shared_ptr<const CollisionMap> map);
  [[nodiscard]] const std::shared_ptr<const CollisionMap>& map() const { return map_; }
  [[nodiscard]] const RobotShape& shape() const { return shape_; }

  struct Stats {
    std::uint64_t queries = 0;
    std::uint64_t fast_free = 0;  ///< parts cleared by the distance field
    std::uint64_t fast_hit = 0;   ///< parts found inside an occupied voxel
    std::uint64_t fcl_calls = 0;  ///< parts sent to FCL
  };
  [[nodiscard]] const Stats& stats() const { return stats_; }

  /// Appends every pose in_collision() is asked about to `sink` (nullptr stops);
  /// the benchmarks replay a planner's queries with it.
  void record_queries(std::vector<Pose3>* sink) { recorder_ = sink; }

 private:
  struct Impl;
  std::shared_ptr<const CollisionMap> map_;
  RobotShape shape_;
  std::unique_ptr<Impl> impl_;
  Stats stats_;
  std::vector<Pose3>* recorder_ = nullptr;
};

}  // namespace ferret
