#pragma once
// An immutable snapshot of the geometry the planners check against: the OctoMap with
// its unknown space resolved by a policy, the FCL view of it, and a distance field
// that answers clear-cut queries without FCL.
//
// Why a snapshot: OctoMap is not safe to edit while planner threads read it
// (octomap#311). A map update builds a new CollisionMap; planners keep the shared
// pointer they started with (MapSnapshots below hands them out).
//
// Why a policy: FCL treats never-observed space as free (children that do not exist
// are skipped). The miniUGV in a hidden space must treat unknown as occupied, so the
// snapshot materialises unknown voxels inside `bounds` as occupied cubes; FCL and
// the distance field then see the same geometry.

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

namespace octomap {
class OcTree;
}

namespace ferret {

enum class UnknownPolicy { kFree, kOccupied };
[[nodiscard]] const char* to_string(UnknownPolicy policy);
/// "free" or "occupied"; throws InputError naming `source` otherwise.
[[nodiscard]] UnknownPolicy parse_unknown_policy(const std::string& text,
                                                 const std::string& source);

struct Aabb3 {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero();
  Eigen::Vector3d hi = Eigen::Vector3d::Zero();
  [[nodiscard]] bool contains(const Eigen::Vector3d& p) const {
    return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
  }
};

/// Throws InputError(source, field, ...) unless `box` lies inside OctoMap's key range at
/// `resolution_m` (+-2^15 voxels from the origin; a flat box is fine): a box beyond it is
/// no place a map can describe, and planning in it would only check collisions along
/// absurd lengths.
void check_box_in_key_range(const Aabb3& box, double resolution_m, const std::string& source,
                            const std::string& field);

struct CollisionMapOptions {
  UnknownPolicy unknown = UnknownPolicy::kFree;
  /// The region where the unknown policy applies (required for kOccupied; outside it
  /// unknown space stays free, as FCL sees it).
  std::optional<Aabb3> bounds;
  /// Upper bound on distance-field cells (2 bytes each); the field's cell is the map
  /// resolution times the smallest power of two that fits (coarser cells give looser
  /// bounds, so more queries go to FCL).
  std::size_t max_field_cells = 40'000'000;
  /// Upper bound on the voxels on the faces of `bounds` when unknown space in it is
  /// filled as occupied: the fill is top-down, so its cost grows with the box's surface
  /// (a 12 x 8 x 0.2 m hidden space at 5 cm: 0.1 million; the default world's 60 x 60 x
  /// 10 m geofence: 3.8 million). A larger box is an InputError naming the bounds, not
  /// hours of filling (a plan's 3 x 3 km box, 0.2 m high, would be 7 billion).
  std::size_t max_fill_face_voxels = 10'000'000;
  /// Where the distance field is kept (default: around everything occupied). Parts
  /// reaching outside it always go to FCL; a small region allows a fine field.
  std::optional<Aabb3> field_region;
  /// Occupied voxels wholly below this height are left out of the field, and the fast
  /// path only clears spheres above it. For ground robots: with the floor in the
  /// field nothing 1 cm above it could ever be cleared.
  std::optional<double> field_floor_cut_z;
  /// For ground robots: a 2D field over the columns of this height band (z_lo, z_hi)
  /// inside field_region (required with it). Parts that lie within the band are
  /// cleared by their footprint circle.
  std::optional<std::pair<double, double>> ground_band_z;
};

/// A text that is equal for two option sets exactly when they build the same map from
/// one tree (every field, doubles to the last bit): a key for keeping built maps.
[[nodiscard]] std::string collision_map_options_key(const CollisionMapOptions& options);

class CollisionMap {
 public:
  /// Builds a snapshot from `source` (copied; later edits of `source` do not show).
  /// Occupancy is OctoMap's max-likelihood decision at the tree's threshold; the
  /// copy stores every leaf at a clamping value and has its inner nodes updated,
  /// so FCL can never miss a leaf edited with lazy evaluation.
  /// Throws InputError (source "map") for kOccupied without bounds or bounds outside
  /// OctoMap's key range.
  [[nodiscard]] static std::shared_ptr<const CollisionMap> build(
      const octomap::OcTree& source, const CollisionMapOptions& options = {});

  ~CollisionMap();
  CollisionMap(const CollisionMap&) = delete;
  CollisionMap& operator=(const CollisionMap&) = delete;

  [[nodiscard]] const octomap::OcTree& tree() const;
  [[nodiscard]] double resolution_m() const;
  [[nodiscard]] UnknownPolicy unknown_policy() const;
  [[nodiscard]] const std::optional<Aabb3>& bounds() const;
  /// Occupied leaves after the policy (a pruned leaf counts once).
  [[nodiscard]] std::size_t occupied_leaf_count() const;
  /// Edge length of a distance-field cell.
  [[nodiscard]] double field_cell_m() const;

  /// A lower bound on the distance from p_W to the nearest occupied voxel (0 when
  /// p_W may be inside one or the field cannot tell; +inf for a map with nothing
  /// occupied). Ignores field_floor_cut_z: only for maps built without it.
  [[nodiscard]] double clearance_lower_bound_m(const Eigen::Vector3d& p_W) const;
  /// True when the ball (c_W, r) provably touches no occupied voxel (distance field).
  [[nodiscard]] bool sphere_free(const Eigen::Vector3d& c_W, double radius_m) const;
  /// True when the voxel at p_W is occupied after the policy, false when free or unknown.
  [[nodiscard]] bool is_occupied(const Eigen::Vector3d& p_W) const;

  struct Data;  ///< FCL geometry and the field (planning/src/collision_map_data.hpp)
  [[nodiscard]] const Data& data() const { return *data_; }

 private:
  explicit CollisionMap(std::unique_ptr<Data> data);
  std::unique_ptr<Data> data_;
};

/// Hands out the current snapshot to planner threads and swaps in new ones.
class MapSnapshots {
 public:
  explicit MapSnapshots(std::shared_ptr<const CollisionMap> initial)
      : current_(std::move(initial)) {}
  [[nodiscard]] std::shared_ptr<const CollisionMap> current() const {
    std::lock_guard lock(mutex_);
    return current_;
  }
  /// Readers that hold the old snapshot keep using it until they ask again.
  void publish(std::shared_ptr<const CollisionMap> next) {
    std::lock_guard lock(mutex_);
    current_ = std::move(next);
  }

 private:
  mutable std::mutex mutex_;
  std::shared_ptr<const CollisionMap> current_;
};

}  // namespace ferret
