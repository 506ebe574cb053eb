#include "ferret/planning/collision_checker.hpp"

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>

#include <array>
#include <cmath>
#include <limits>

#include "collision_map_data.hpp"

namespace ferret {
namespace {

// Spheres (centre in S, radius) that together cover a part. Long parts (the tether,
// a flat rotor disc) get a chain of small spheres instead of one huge one, so the
// distance field can clear them.
// Full extents of the part's bounding box in S.
Eigen::Vector3d part_extent(const ShapePart& p) {
  switch (p.kind) {
    case ShapePart::Kind::kBox:
      return p.box_size_m;
    case ShapePart::Kind::kCylinder:
      return {2 * p.radius_m, 2 * p.radius_m, p.length_m};
    case ShapePart::Kind::kCapsule:
      return {2 * p.radius_m, 2 * p.radius_m, p.length_m + 2 * p.radius_m};
    case ShapePart::Kind::kSphere:
      return Eigen::Vector3d::Constant(2 * p.radius_m);
  }
  return Eigen::Vector3d::Zero();
}

struct SphereGroup {  // a ball around up to 4 x 4 x 4 covering spheres
  Eigen::Vector3d c;
  double r;
  std::size_t begin, end;  ///< its spheres in the part's list
};

// Covering spheres ordered by group, and the groups: a part is cleared by its
// bounding ball, else group by group, descending to the small balls of a group only
// when the group's ball is not clear.
std::vector<std::pair<Eigen::Vector3d, double>> covering_spheres(const ShapePart& p,
                                                                 std::vector<SphereGroup>& groups) {
  if (p.kind == ShapePart::Kind::kSphere) {
    groups.push_back({Eigen::Vector3d::Zero(), p.radius_m, 0, 1});
    return {{Eigen::Vector3d::Zero(), p.radius_m}};
  }
  const Eigen::Vector3d extent = part_extent(p);
  // Cubes about as large as the part's smallest extent (at least 5 cm), at most 64.
  const double edge = std::max(extent.minCoeff(), 0.05);
  Eigen::Vector3i n;
  for (int a = 0; a < 3; ++a)
    n[a] = std::clamp(static_cast<int>(std::ceil(extent[a] / edge - 1e-9)), 1, 64);
  const Eigen::Vector3d cell = extent.cwiseQuotient(n.cast<double>());
  const double r = 0.5 * cell.norm();
  std::vector<std::pair<Eigen::Vector3d, double>> out;
  for (int gk = 0; gk < n.z(); gk += 4)
    for (int gj = 0; gj < n.y(); gj += 4)
      for (int gi = 0; gi < n.x(); gi += 4) {
        const Eigen::Vector3i g0(gi, gj, gk), g1 = (g0 + Eigen::Vector3i::Constant(4)).cwiseMin(n);
        const Eigen::Vector3d lo = -0.5 * extent + cell.cwiseProduct(g0.cast<double>());
        const Eigen::Vector3d hi = -0.5 * extent + cell.cwiseProduct(g1.cast<double>());
        SphereGroup group{0.5 * (lo + hi), 0.5 * (hi - lo).norm(), out.size(), 0};
        for (int k = g0.z(); k < g1.z(); ++k)
          for (int j = g0.y(); j < g1.y(); ++j)
            for (int i = g0.x(); i < g1.x(); ++i)
              out.emplace_back(
                  -0.5 * extent + cell.cwiseProduct(Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5)), r);
        group.end = out.size();
        groups.push_back(group);
      }
  return out;
}

// Points inside a part (in S): the centres of its covering spheres that lie inside
// it. A part with such a point in an occupied voxel certainly collides.
std::vector<Eigen::Vector3d> inner_points(
    const ShapePart& p, const std::vector<std::pair<Eigen::Vector3d, double>>& spheres) {
  std::vector<Eigen::Vector3d> out{Eigen::Vector3d::Zero()};
  for (const auto& [c, r] : spheres) {
    (void)r;
    bool inside = false;
    switch (p.kind) {
      case ShapePart::Kind::kBox:
        inside = true;
        break;
      case ShapePart::Kind::kCylinder:
        inside = c.head<2>().norm() <= p.radius_m && std::abs(c.z()) <= 0.5 * p.length_m;
        break;
      case ShapePart::Kind::kCapsule:
        inside =
            c.head<2>().norm() <= p.radius_m && std::abs(c.z()) <= 0.5 * p.length_m + p.radius_m;
        break;
      case ShapePart::Kind::kSphere:
        inside = c.norm() <= p.radius_m;
        break;
    }
    if (inside && c.norm() > 1e-12) out.push_back(c);
  }
  if (p.kind == ShapePart::Kind::kBox) {
    // The corners pulled 2 % towards the centre: strictly inside, so a voxel holding
    // one overlaps the box with positive volume (a box dipping into the ground).
    for (int c = 0; c < 8; ++c)
      out.push_back(0.49 * Eigen::Vector3d((c & 1 ? 1 : -1) * p.box_size_m.x(),
                                           (c & 2 ? 1 : -1) * p.box_size_m.y(),
                                           (c & 4 ? 1 : -1) * p.box_size_m.z()));
  }
  return out;
}

std::shared_ptr<fcl::CollisionGeometryd> fcl_geometry(const ShapePart& p) {
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

}  // namespace

struct CollisionChecker::Impl {
  struct Part {
    Pose3 X_BS;
    double bounding_radius_m;
    std::vector<std::pair<Eigen::Vector3d, double>> spheres;
    std::vector<SphereGroup> groups;
    std::vector<Eigen::Vector3d> inner;
    std::array<Eigen::Vector3d, 8> corners;  ///< of the part's bounding box, in S
    std::unique_ptr<fcl::CollisionObjectd> object;
  };
  std::vector<Part> parts;
  std::unique_ptr<fcl::CollisionObjectd> tree_object;
  // The whole robot: its bounding box corners and a ball around it, in B. Most
  // queries are cleared by these alone, whatever the number of parts.
  std::array<Eigen::Vector3d, 8> robot_corners;
  Eigen::Vector3d robot_center_B = Eigen::Vector3d::Zero();
  double robot_radius_m = 0.0;

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
  for (const ShapePart& p : shape_.parts) {
    std::vector<SphereGroup> groups;
    auto spheres = covering_spheres(p, groups);
    auto inner = inner_points(p, spheres);
    const Eigen::Vector3d half = 0.5 * part_extent(p);
    std::array<Eigen::Vector3d, 8> corners;
    for (int c = 0; c < 8; ++c)
      corners[c] = Eigen::Vector3d((c & 1 ? 1 : -1) * half.x(), (c & 2 ? 1 : -1) * half.y(),
                                   (c & 4 ? 1 : -1) * half.z());
    impl_->parts.push_back({p.X_BS, p.bounding_radius_m(), std::move(spheres), std::move(groups),
                            std::move(inner), corners,
                            std::make_unique<fcl::CollisionObjectd>(fcl_geometry(p))});
  }
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const auto& part : impl_->parts)
    for (const Eigen::Vector3d& c : part.corners) {
      lo = lo.cwiseMin(part.X_BS * c);
      hi = hi.cwiseMax(part.X_BS * c);
    }
  if (impl_->parts.empty()) lo = hi = Eigen::Vector3d::Zero();
  for (int c = 0; c < 8; ++c)
    impl_->robot_corners[c] =
        Eigen::Vector3d(c & 1 ? hi.x() : lo.x(), c & 2 ? hi.y() : lo.y(), c & 4 ? hi.z() : lo.z());
  impl_->robot_center_B = 0.5 * (lo + hi);
  for (const auto& part : impl_->parts)
    impl_->robot_radius_m =
        std::max(impl_->robot_radius_m,
                 (part.X_BS.translation() - impl_->robot_center_B).norm() + part.bounding_radius_m);
  set_map(std::move(map));
}

CollisionChecker::~CollisionChecker() = default;

namespace {
// Ground robots: a box (8 corners in S, placed by X_WS) that lies vertically inside
// the band is free when no occupied column lies under its footprint: its bounding
// rectangle for small footprints, the disc through its farthest corner for large ones.
bool band_box_free(const BandField& band, const std::array<Eigen::Vector3d, 8>& corners,
                   const Pose3& X_WS) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (const Eigen::Vector3d& c : corners) {
    const Eigen::Vector3d w = X_WS * c;
    lo = lo.cwiseMin(w);
    hi = hi.cwiseMax(w);
  }
  if (!(lo.z() > band.z_lo + 1e-9 && hi.z() < band.z_hi - 1e-9)) return false;
  if ((hi.head<2>() - lo.head<2>()).maxCoeff() < 32 * band.cell_m)
    return band.rect_free(lo.head<2>(), hi.head<2>());
  const Eigen::Vector2d c = X_WS.translation().head<2>();
  return band.disc_free(c, std::hypot(std::max(c.x() - lo.x(), hi.x() - c.x()),
                                      std::max(c.y() - lo.y(), hi.y() - c.y())));
}
}  // namespace

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
  if (recorder_) recorder_->push_back(X_WB);
  const DistanceField& field = map_->data().field;
  const std::optional<BandField>& band = map_->data().band;
  // The whole robot at once.
  if ((band && band_box_free(*band, impl_->robot_corners, X_WB)) ||
      field.sphere_free(X_WB * impl_->robot_center_B, impl_->robot_radius_m)) {
    stats_.fast_free += impl_->parts.size();
    return false;
  }
  // Then the cheap certainties of every part, then FCL for the undecided ones.
  std::uint64_t undecided = 0;  // bit k: part k needs FCL (shapes have few parts)
  for (std::size_t k = 0; k < impl_->parts.size(); ++k) {
    auto& part = impl_->parts[k];
    const Pose3 X_WS = X_WB * part.X_BS;
    // For ground robots: the footprint against the band's columns. Then one ball
    // around the whole part, then the small balls that cover it.
    bool free = band && band_box_free(*band, part.corners, X_WS);
    if (!free) free = field.sphere_free(X_WS.translation(), part.bounding_radius_m);
    if (!free) {
      free = true;
      for (const SphereGroup& g : part.groups) {
        if (g.end - g.begin > 1 && field.sphere_free(X_WS * g.c, g.r)) continue;
        for (std::size_t k = g.begin; k < g.end && free; ++k)
          free = field.sphere_free(X_WS * part.spheres[k].first, part.spheres[k].second);
        if (!free) break;
      }
    }
    if (free) {
      ++stats_.fast_free;
      continue;
    }
    for (const Eigen::Vector3d& p_S : part.inner) {
      const Eigen::Vector3d p_W = X_WS * p_S;
      const int occ = field.occupied_at(p_W);
      if (occ == 1 || (occ < 0 && map_->is_occupied(p_W))) {
        ++stats_.fast_hit;
        return true;
      }
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
