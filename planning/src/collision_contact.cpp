#include "collision_contact.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "collision_map_data.hpp"

namespace ferret {
namespace {

std::shared_ptr<fcl::CollisionGeometryd> geometry(const ShapePart& p) {
  switch (p.kind) {
    case ShapePart::Kind::kBox:
      return std::make_shared<fcl::Boxd>(p.box_size_m);
    case ShapePart::Kind::kCylinder:
      return std::make_shared<fcl::Cylinderd>(p.radius_m, p.length_m);
    case ShapePart::Kind::kCapsule:
      return std::make_shared<fcl::Capsuled>(p.radius_m, p.length_m);
    case ShapePart::Kind::kSphere:
      return std::make_shared<fcl::Sphered>(p.radius_m);
  }
  return nullptr;
}

bool collide(fcl::CollisionObjectd& a, fcl::CollisionObjectd& b) {
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(&a, &b, request, result);
  return result.isCollision();
}

}  // namespace

std::optional<Contact> find_contact(const CollisionMap& map, const RobotShape& shape,
                                    const Pose3& X_WB) {
  const auto& data = map.data();
  fcl::CollisionObjectd tree_object(data.fcl_tree);
  tree_object.computeAABB();
  for (const ShapePart& p : shape.parts) {
    fcl::CollisionObjectd part(geometry(p));
    const Pose3 X_WS = X_WB * p.X_BS;
    part.setTransform(X_WS);
    part.computeAABB();
    if (!collide(tree_object, part)) continue;
    // The voxel: among the occupied leaves in the part's box, those FCL finds the part
    // overlapping, the one nearest the part's centre (ties: the first in key order).
    Contact c{p.name, X_WS.translation(), map.resolution_m()};
    const fcl::AABBd& box = part.getAABB();
    const double pad = map.resolution_m();
    double best = std::numeric_limits<double>::infinity();
    const octomap::OcTree& tree = *data.tree;
    for (auto it = tree.begin_leafs_bbx(
             octomap::point3d(box.min_.x() - pad, box.min_.y() - pad, box.min_.z() - pad),
             octomap::point3d(box.max_.x() + pad, box.max_.y() + pad, box.max_.z() + pad));
         it != tree.end_leafs_bbx(); ++it) {
      if (!tree.isNodeOccupied(*it)) continue;
      const Eigen::Vector3d centre(it.getX(), it.getY(), it.getZ());
      const double d = (centre - X_WS.translation()).norm();
      if (d >= best) continue;
      fcl::CollisionObjectd voxel(
          std::make_shared<fcl::Boxd>(Eigen::Vector3d::Constant(it.getSize())));
      fcl::Transform3d X_WV = fcl::Transform3d::Identity();
      X_WV.translation() = centre;
      voxel.setTransform(X_WV);
      voxel.computeAABB();
      if (!collide(voxel, part)) continue;
      best = d;
      c.voxel_W = centre;
      if (it.getSize() > 1.5 * map.resolution_m()) {
        // A pruned leaf: its voxel nearest the part (voxel centres lie at (k + 1/2) res).
        const double res = map.resolution_m(), half = 0.5 * it.getSize();
        for (int a = 0; a < 3; ++a) {
          const double v =
              std::clamp(X_WS.translation()[a], centre[a] - half, centre[a] + half - 1e-9);
          c.voxel_W[a] = (std::floor(v / res) + 0.5) * res;
        }
      }
    }
    return c;
  }
  return std::nullopt;
}

}  // namespace ferret
