#pragma once
// Where the floor of a hidden space is, from its map: the miniUGV stands on the top
// of the floor voxels, wherever the box someone gave around the space starts.

#include <optional>

#include "ferret/planning/collision_map.hpp"

namespace octomap {
class OcTree;
}

namespace ferret {

/// The height of the floor surface under the plan box `box` (x, y; z: the range the
/// floor is looked for in, extended 1 m below box.lo.z so a box starting above the floor
/// still finds it): in each column of observed-occupied voxels, the top of the lowest
/// run of them (the slab, with whatever stands on it), and over the columns the most
/// common of those heights (a pillar or a wall is a minority of the columns). nullopt
/// when no column holds an occupied voxel.
[[nodiscard]] std::optional<double> floor_z_from_map(const octomap::OcTree& observed,
                                                     const Aabb3& box);

}  // namespace ferret
