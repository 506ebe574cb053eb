#pragma once
// Private: which part of a robot collides at a pose, and with which voxel (for the
// validation report). Only planning/src includes this.

#include <Eigen/Core>
#include <optional>
#include <string>

#include "ferret/core/pose.hpp"
#include "ferret/planning/collision_map.hpp"
#include "ferret/planning/robot_shape.hpp"

namespace ferret {

struct Contact {
  std::string part;  ///< the first part (in the shape's order) that collides
  Eigen::Vector3d voxel_W = Eigen::Vector3d::Zero();  ///< centre of the occupied voxel it overlaps
  double voxel_size_m = 0.0;
};

/// The first colliding part at X_WB and the occupied leaf it overlaps nearest to the
/// part's centre (FCL, shape against voxel box); nullopt when FCL finds no collision.
[[nodiscard]] std::optional<Contact> find_contact(const CollisionMap& map, const RobotShape& shape,
                                                  const Pose3& X_WB);

}  // namespace ferret
