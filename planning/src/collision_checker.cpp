#include "ferret/planning/collision_checker.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <cmath>
#include <limits>

#include "collision_map_data.hpp"

namespace ferret {
namespace {

// Spheres (centre in S, radius) that together cover a part. Long parts (the tether,
// a flat rotor disc) get a chain of small spheres instead of one huge one, so the
// distance field can clear them.
std::vector<std::pair<Eigen::Vector3d, double>> covering_spheres(const ShapePart& p) {
  Eigen::Vector3d extent = Eigen::Vector3d::Zero();  // full extents of the part's bounding box in S
  switch (p.kind) {
    case ShapePart::Kind::kBox: extent = p.box_size_m; break;
    case ShapePart::Kind::kCylinder: extent = {2 * p.radius_m, 2 * p.radius_m, p.length_m}; break;
    case ShapePart::Kind::kCapsule:
      extent = {2 * p.radius_m, 2 * p.radius_m, p.length_m + 2 * p.radius_m};
      break;
    case ShapePart::Kind::kSphere: return {{Eigen::Vector3d::Zero(), p.radius_m}};
  }
  // Cubes about as large as the part's smallest extent (at least 5 cm), at most 64.
  const double edge = std::max(extent.minCoeff(), 0.05);
  Eigen::Vector3i n;
  for (int a = 0; a < 3; ++a) n[a] = std::clamp(static_cast<int>(std::ceil(extent[a] / edge - 1e-9)), 1, 64);
  const Eigen::Vector3d cell = extent.cwiseQuotient(n.cast<double>());
  const double r = 0.5 * cell.norm();
  std::vector<std::pair<Eigen::Vector3d, double>> out;
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i)
        out.emplace_back(-0.5 * extent + cell.cwiseProduct(Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5)), r);
  return out;
}

std::shared_ptr<fcl::CollisionGeometryd> fcl_geometry(const ShapePart& p) {
  switch (p.kind) {
    case ShapePart::Kind::kBox: return std::make_shared<fcl::Boxd>(p.box_size_m);
    case ShapePart::Kind::kCylinder: return std::make_shared<fcl::Cylinderd>(p.radius_m, p.length_m);
    case ShapePart::Kind::kCapsule: return std::make_shared<fcl::Capsuled>(p.radius_m, p.length_m);
    case ShapePart::Kind::kSphere: return std::make_shared<fcl::Sphered>(p.radius_m);
  }
  return nullptr;
}

}  // namespace

struct CollisionChecker::Impl {
  struct Part {
    Pose3 X_BS;
    std::vector<std::pair<Eigen::Vector3d, double>> spheres;
    std::unique_ptr<fcl::CollisionObjectd> object;
  };
  std::vector<Part> parts;
  std::unique_ptr<fcl::CollisionObjectd> tree_object;

  bool fcl_collides(Part& part, const Pose3& X_WS) {
    part.object->setTransform(X_WS);
    part.object->computeAABB();
    fcl::CollisionRequestd request;  // one contact is enough; no cost sources
    fcl::CollisionResultd result;
    fcl::collide(tree_object.get(), part.object.get(), request, result);
    return result.isCollision();
  }
};

CollisionChecker::CollisionChecker(std::shared_ptr<const CollisionMap> map, RobotShape shape)
    : shape_(std::move(shape)), impl_(std::make_unique<Impl>()) {
  for (const ShapePart& p : shape_.parts)
    impl_->parts.push_back({p.X_BS, covering_spheres(p), std::make_unique<fcl::CollisionObjectd>(fcl_geometry(p))});
  set_map(std::move(map));
}

CollisionChecker::~CollisionChecker() = default;

void CollisionChecker::set_map(std::shared_ptr<const CollisionMap> map) {
  map_ = std::move(map);
  // Each checker has its own object for the shared (read-only) FCL tree.
  impl_->tree_object = std::make_unique<fcl::CollisionObjectd>(map_->data().fcl_tree);
  impl_->tree_object->computeAABB();
}

bool CollisionChecker::in_collision_fcl(const Pose3& X_WB) {
  for (auto& part : impl_->parts)
    if (impl_->fcl_collides(part, X_WB * part.X_BS)) return true;
  return false;
}

bool CollisionChecker::in_collision(const Pose3& X_WB) {
  ++stats_.queries;
  const CollisionMap& map = *map_;
  // First the cheap certainties of every part, then FCL for the undecided ones.
  std::uint64_t undecided = 0;  // bit k: part k needs FCL (shapes have few parts)
  for (std::size_t k = 0; k < impl_->parts.size(); ++k) {
    auto& part = impl_->parts[k];
    const Pose3 X_WS = X_WB * part.X_BS;
    bool free = true;
    for (const auto& [p_S, r] : part.spheres) {
      if (map.clearance_lower_bound_m(X_WS * p_S) <= r) {
        free = false;
        break;
      }
    }
    if (free) {
      ++stats_.fast_free;
      continue;
    }
    if (map.is_occupied(X_WS.translation())) {
      ++stats_.fast_hit;
      return true;
    }
    if (k < 64) {
      undecided |= std::uint64_t{1} << k;
    } else {
      ++stats_.fcl_calls;
      if (impl_->fcl_collides(part, X_WS)) return true;
    }
  }
  for (std::size_t k = 0; k < impl_->parts.size() && k < 64; ++k) {
    if (!(undecided >> k & 1)) continue;
    ++stats_.fcl_calls;
    if (impl_->fcl_collides(impl_->parts[k], X_WB * impl_->parts[k].X_BS)) return true;
  }
  return false;
}

double CollisionChecker::clearance_lower_bound_m(const Pose3& X_WB) const {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& part : impl_->parts) {
    const Pose3 X_WS = X_WB * part.X_BS;
    for (const auto& [p_S, r] : part.spheres)
      best = std::min(best, std::max(0.0, map_->clearance_lower_bound_m(X_WS * p_S) - r));
  }
  return best;
}

}  // namespace ferret
