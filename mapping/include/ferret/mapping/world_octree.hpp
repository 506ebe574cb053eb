#pragma once
// The 3D world as an OctoMap: built from a WorldSpec, loaded from and saved to
// .bt (max-likelihood) and .ot (full probabilities) files, and sliced into 2D
// map_server maps. docs/maps_and_worlds.md has the rules.

#include <octomap/OcTree.h>

#include <Eigen/Core>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/mapping/world_spec.hpp"

namespace ferret {

/// Voxelizes a world: a voxel is occupied when its centre lies in a solid, known
/// free when its centre lies inside the bounds and in no solid, unknown (absent)
/// outside the bounds. Built top-down: a cube wholly inside one solid, or wholly
/// clear of all of them, becomes one leaf without visiting its voxels, so the cost
/// grows with the area of the surfaces, not the volume. Occupied leaves hold
/// OctoMap's upper clamping log-odds, free leaves the lower one; inner nodes hold
/// the maximum of their children (updateInnerOccupancy has run).
struct WorldBuildOptions {
  /// A world needing more nodes is refused (InputError on resolution_m) instead of
  /// exhausting memory: about 50 bytes a node, so 60 million is about 3 GB.
  std::size_t max_nodes = 60'000'000;
};
[[nodiscard]] std::unique_ptr<octomap::OcTree> build_world_octree(
    const WorldSpec& world, const WorldBuildOptions& options = {});

/// Loads a .bt or .ot OcTree (chosen by extension). The file's structure is
/// validated before OctoMap reads it (OctoMap 1.9.7 recurses without a depth
/// limit and reads uninitialised bytes on a truncated stream), so a truncated or
/// garbage file throws InputError naming the file and the header field or the byte
/// offset, and never crashes or hangs.
[[nodiscard]] std::unique_ptr<octomap::OcTree> load_octree(const std::filesystem::path& path);
/// The same for a file's bytes already in memory (a request body): `binary` for the
/// .bt format, else .ot; errors name `source`.
[[nodiscard]] std::unique_ptr<octomap::OcTree> parse_octree(const std::string& bytes, bool binary,
                                                            const std::string& source);

/// Writes a .bt (max-likelihood: each leaf occupied or free) or .ot (log-odds kept)
/// file atomically, chosen by extension; any other extension is an InputError.
void save_octree(const octomap::OcTree& tree, const std::filesystem::path& path);

/// The world at `path` as an OcTree: a .bt/.ot file is loaded, a world YAML
/// (.yaml/.yml) is parsed and built; then `world`, when given, receives the
/// parsed world (and is reset for OctoMap files).
[[nodiscard]] std::unique_ptr<octomap::OcTree> load_or_build_octree(
    const std::filesystem::path& path, std::optional<WorldSpec>* world = nullptr);

/// Options of a 2D slice.
struct SliceOptions {
  double z_m = 0.03;         ///< height of the slice
  double half_band_m = 0.0;  ///< voxel layers within [z - half_band, z + half_band] count
  /// Cut the slice to [x0, y0, x1, y1] (m), widened to whole voxels; default: the
  /// tree's known extent.
  std::optional<Eigen::Vector4d> window_m;
};

/// The plan window [x0, y0, x1, y1] around the enclosure of the hidden space
/// `name`, widened by `margin_m`: to slice or render just that space. Throws
/// InputError naming `option` (e.g. "--space") when the world has no such space.
[[nodiscard]] Eigen::Vector4d hidden_space_window(const WorldSpec& world, const std::string& name,
                                                  double margin_m, const std::string& option);

/// The window a user asked for on the command line: `window` holds x0, y0, x1, y1
/// (or nothing), `space` names a hidden space of `world` (0.5 m margin), or
/// neither (no window). Errors name --window and --space.
[[nodiscard]] std::optional<Eigen::Vector4d> requested_slice_window(
    const std::vector<double>& window, const std::string& space,
    const std::optional<WorldSpec>& world);

/// A 2D map of the voxel layers at a height: a cell is occupied when any voxel of
/// its column in the band is occupied, free when all of them are known free, and
/// unknown otherwise. The grid covers the tree's known extent in x and y (or the
/// window, clipped to it), cell edges on voxel edges, at the tree's resolution.
[[nodiscard]] OccupancyMap2D slice_octree(const octomap::OcTree& tree, const SliceOptions& options);

/// A 2D map as a 3D world at its own resolution, for planning a ground robot in it:
/// the floor's top at z = 0 (one layer of occupied voxels under every known cell),
/// occupied cells walls from the floor to `height_m`, free cells known free space to
/// `height_m`, unknown cells left unknown. OctoMap's voxels lie on multiples of the
/// resolution, so a map whose origin does not is moved onto them, by under half a cell.
/// InputError naming `source` and the field for a resolution outside [0.001, 100] m,
/// a map beyond OctoMap's key range (+-2^15 cells from 0), or more voxels than allowed.
[[nodiscard]] std::unique_ptr<octomap::OcTree> extrude_map_2d(const OccupancyMap2D& map,
                                                              const std::string& source,
                                                              const Map2DExtrusion& options = {});

/// What `ferret world info` prints.
struct OctreeSummary {
  double resolution_m = 0.0;
  Eigen::Vector3d min_m = Eigen::Vector3d::Zero(),
                  max_m = Eigen::Vector3d::Zero();  ///< known extent
  std::size_t nodes = 0, leaves = 0, occupied_leaves = 0, free_leaves = 0;
  double occupied_volume_m3 = 0.0, free_volume_m3 = 0.0;
  std::size_t memory_bytes = 0;
};
[[nodiscard]] OctreeSummary summarize_octree(const octomap::OcTree& tree);

}  // namespace ferret
