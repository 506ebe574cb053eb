#include "ferret/sim/landing_terrain.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "ferret/core/random.hpp"
#include "ferret/sim/sensor_sim.hpp"

namespace ferret {
namespace {

constexpr double kHalfSite_m = 8.0;
constexpr double kPi = std::numbers::pi;

}  // namespace

LandingTerrain landing_terrain(std::uint64_t seed, int index) {
  Rng rng(derive_seed(seed, {0x1a4d, static_cast<std::uint64_t>(index)}));
  LandingTerrain t;
  t.slope_deg = rng.uniform(0.0, 25.0);
  const double azimuth = rng.uniform(-kPi, kPi);
  const double g = std::tan(deg_to_rad(t.slope_deg));
  const double sx = g * std::cos(azimuth), sy = g * std::sin(azimuth);
  const auto ground = [&](double x, double y) { return sx * x + sy * y; };
  t.view_center_m = {rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)};
  // Features: each kind present with its own probability, so that terrains mix them.
  const bool rubble = rng.bernoulli(0.5), steps = rng.bernoulli(0.5), walls = rng.bernoulli(0.4),
             poles = rng.bernoulli(0.4);
  std::string yaml = fmt::format(
      "name: landing_{}\nresolution_m: 0.05\n"
      "bounds_m: {{min: [{}, {}, -6], max: [{}, {}, 10]}}\n"
      "ground: {{height_m: 0, slope: [{:.6f}, {:.6f}]}}\n",
      index, -kHalfSite_m, -kHalfSite_m, kHalfSite_m, kHalfSite_m, sx, sy);
  // The hidden space, 2-4 m from the site's middle, its opening facing it.
  {
    const double dist = rng.uniform(2.5, 4.0), bearing = rng.uniform(-kPi, kPi);
    const Eigen::Vector2d c(dist * std::cos(bearing), dist * std::sin(bearing));
    const double lx = rng.uniform(1.5, 3.0), ly = rng.uniform(1.0, 2.0), lz = rng.uniform(0.3, 0.5);
    // Yaw so that the space's -x wall (the opening) faces the middle.
    const double yaw = std::atan2(-c.y(), -c.x()) + kPi;
    const double r = 0.5 * std::hypot(lx, ly);
    // The floor at the highest ground under the interior (the schema requires it).
    const double floor = ground(c.x(), c.y()) + g * r;
    yaml += fmt::format(
        "hidden_spaces:\n  - name: void\n    center_m: [{:.4f}, {:.4f}]\n    yaw_deg: {:.4f}\n"
        "    floor_z_m: {:.4f}\n    interior_size_m: [{:.3f}, {:.3f}, {:.3f}]\n"
        "    wall_thickness_m: 0.15\n"
        "    opening: {{wall: -x, width_m: 0.15, height_m: 0.07}}\n"
        "    marker: {{id: 3, size_m: 0.15, placement: wall}}\n",
        c.x(), c.y(), rad_to_deg(yaw), floor + 0.001, lx, ly, lz);
  }
  std::vector<std::string> boxes, cylinders, kinds;
  kinds.push_back(fmt::format("slope {:.1f} deg", t.slope_deg));
  if (steps) {
    kinds.emplace_back("steps");
    const int n = static_cast<int>(rng.uniform_int(1, 4));
    for (int k = 0; k < n; ++k)
      boxes.push_back(
          fmt::format("  - {{center_m: [{:.3f}, {:.3f}], size_m: [{:.3f}, {:.3f}, {:.3f}], "
                      "yaw_deg: {:.2f}}}\n",
                      rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0), rng.uniform(1.0, 4.0),
                      rng.uniform(1.0, 4.0), rng.uniform(0.04, 0.6), rng.uniform(-90.0, 90.0)));
  }
  if (walls) {
    kinds.emplace_back("walls");
    const int n = static_cast<int>(rng.uniform_int(1, 3));
    for (int k = 0; k < n; ++k)
      boxes.push_back(
          fmt::format("  - {{center_m: [{:.3f}, {:.3f}], size_m: [{:.3f}, {:.3f}, {:.3f}], "
                      "yaw_deg: {:.2f}}}\n",
                      rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0), rng.uniform(1.5, 5.0),
                      rng.uniform(0.3, 0.4), rng.uniform(0.8, 2.0), rng.uniform(-90.0, 90.0)));
  }
  if (poles) {
    kinds.emplace_back("poles");
    const int n = static_cast<int>(rng.uniform_int(1, 4));
    for (int k = 0; k < n; ++k)
      cylinders.push_back(
          fmt::format("  - {{center_m: [{:.3f}, {:.3f}], radius_m: {:.3f}, height_m: {:.3f}}}\n",
                      rng.uniform(-3.0, 3.0), rng.uniform(-3.0, 3.0), rng.uniform(0.15, 0.3),
                      rng.uniform(0.5, 2.5)));
  }
  if (!boxes.empty()) {
    yaml += "boxes:\n";
    for (const auto& b : boxes) yaml += b;
  }
  if (!cylinders.empty()) {
    yaml += "cylinders:\n";
    for (const auto& c : cylinders) yaml += c;
  }
  if (rubble) {
    kinds.emplace_back("rubble");
    yaml += fmt::format(
        "rubble:\n  - seed: {}\n    count: {}\n    region_m: {{min: [-4, -4], max: [4, 4]}}\n"
        "    size_min_m: [0.3, 0.3, 0.03]\n    size_max_m: [1.0, 1.0, 0.4]\n    clearance_m: 0.3\n",
        rng.next_u64() >> 12, rng.uniform_int(5, 40));
  }
  t.world = parse_world(yaml, fmt::format("landing_terrain(seed {}, index {})", seed, index));
  for (std::size_t k = 0; k < kinds.size(); ++k) t.kind += (k ? ", " : "") + kinds[k];
  return t;
}

TerrainGroundTruth::TerrainGroundTruth(const WorldSpec& world, double cell_m) : cell_m_(cell_m) {
  lo_ = world.bounds_min_m.head<2>();
  nx_ = static_cast<int>(std::ceil((world.bounds_max_m.x() - lo_.x()) / cell_m));
  ny_ = static_cast<int>(std::ceil((world.bounds_max_m.y() - lo_.y()) / cell_m));
  h_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), 0.0f);
  for (int j = 0; j < ny_; ++j)
    for (int i = 0; i < nx_; ++i)
      h_[static_cast<std::size_t>(j) * nx_ + i] = static_cast<float>(
          world.ground.height_at(lo_.x() + (i + 0.5) * cell_m, lo_.y() + (j + 0.5) * cell_m));
  // Each solid raises the cells whose centre it covers in plan, over its own extent only.
  const auto raise = [&](const Eigen::AlignedBox2d& extent, double top, const auto& covers) {
    const int i0 = std::max(0, static_cast<int>(std::floor((extent.min().x() - lo_.x()) / cell_m)));
    const int j0 = std::max(0, static_cast<int>(std::floor((extent.min().y() - lo_.y()) / cell_m)));
    const int i1 =
        std::min(nx_ - 1, static_cast<int>(std::floor((extent.max().x() - lo_.x()) / cell_m)));
    const int j1 =
        std::min(ny_ - 1, static_cast<int>(std::floor((extent.max().y() - lo_.y()) / cell_m)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const Eigen::Vector2d p(lo_.x() + (i + 0.5) * cell_m, lo_.y() + (j + 0.5) * cell_m);
        if (!covers(p)) continue;
        float& v = h_[static_cast<std::size_t>(j) * nx_ + i];
        v = std::max(v, static_cast<float>(top));
      }
  };
  for (const auto& b : world.solid_boxes()) {
    const double c = std::cos(b.yaw_rad), s = std::sin(b.yaw_rad);
    const double ex = 0.5 * (std::abs(c) * b.size_m.x() + std::abs(s) * b.size_m.y());
    const double ey = 0.5 * (std::abs(s) * b.size_m.x() + std::abs(c) * b.size_m.y());
    const Eigen::Vector2d c2 = b.center_m.head<2>();
    raise(Eigen::AlignedBox2d(c2 - Eigen::Vector2d(ex, ey), c2 + Eigen::Vector2d(ex, ey)),
          b.center_m.z() + 0.5 * b.size_m.z(), [&](const Eigen::Vector2d& p) {
            const Eigen::Vector2d d = p - c2;
            const double u = c * d.x() + s * d.y(), v = -s * d.x() + c * d.y();
            return std::abs(u) <= 0.5 * b.size_m.x() && std::abs(v) <= 0.5 * b.size_m.y();
          });
  }
  for (const auto& cy : world.cylinders) {
    const Eigen::Vector2d r = Eigen::Vector2d::Constant(cy.radius_m);
    raise(Eigen::AlignedBox2d(cy.center_m - r, cy.center_m + r), cy.base_z_m + cy.height_m,
          [&](const Eigen::Vector2d& p) { return (p - cy.center_m).norm() <= cy.radius_m; });
  }
}

double TerrainGroundTruth::surface_height(double x_m, double y_m) const {
  const int i = std::clamp(static_cast<int>(std::floor((x_m - lo_.x()) / cell_m_)), 0, nx_ - 1);
  const int j = std::clamp(static_cast<int>(std::floor((y_m - lo_.y()) / cell_m_)), 0, ny_ - 1);
  return at(i, j);
}

double TerrainGroundTruth::highest_within(const Eigen::Vector2d& center_m, double radius_m) const {
  const int r = static_cast<int>(std::ceil(radius_m / cell_m_)) + 1;
  const int ci = static_cast<int>(std::floor((center_m.x() - lo_.x()) / cell_m_));
  const int cj = static_cast<int>(std::floor((center_m.y() - lo_.y()) / cell_m_));
  double top = -std::numeric_limits<double>::infinity();
  for (int j = std::max(0, cj - r); j <= std::min(ny_ - 1, cj + r); ++j)
    for (int i = std::max(0, ci - r); i <= std::min(nx_ - 1, ci + r); ++i) {
      const double x = lo_.x() + (i + 0.5) * cell_m_ - center_m.x();
      const double y = lo_.y() + (j + 0.5) * cell_m_ - center_m.y();
      // Every cell the disc touches.
      if (std::hypot(x, y) <= radius_m + cell_m_ * std::sqrt(0.5)) top = std::max(top, at(i, j));
    }
  return top;
}

bool TerrainGroundTruth::is_safe(const Eigen::Vector2d& center_m, double radius_m,
                                 const LandingCriteria& criteria) const {
  const double outer = radius_m + criteria.min_clearance_m;
  const int r_cells = static_cast<int>(std::ceil(outer / cell_m_)) + 1;
  const int ci = static_cast<int>(std::floor((center_m.x() - lo_.x()) / cell_m_));
  const int cj = static_cast<int>(std::floor((center_m.y() - lo_.y()) / cell_m_));
  if (ci - r_cells < 0 || cj - r_cells < 0 || ci + r_cells >= nx_ || cj + r_cells >= ny_)
    return false;  // not all of it is inside the world
  // Plane fit over the disc's cells (centres within the radius, and the cells a disc
  // edge cuts: any cell the footprint touches).
  const double touch = radius_m + cell_m_ * std::sqrt(0.5);
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d bvec = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> disc;
  for (int j = cj - r_cells; j <= cj + r_cells; ++j)
    for (int i = ci - r_cells; i <= ci + r_cells; ++i) {
      const double x = lo_.x() + (i + 0.5) * cell_m_ - center_m.x();
      const double y = lo_.y() + (j + 0.5) * cell_m_ - center_m.y();
      if (std::hypot(x, y) > touch) continue;
      const double z = at(i, j);
      disc.emplace_back(x, y, z);
      const Eigen::Vector3d q(x, y, 1.0);
      A += q * q.transpose();
      bvec += q * z;
    }
  const Eigen::Vector3d abc = A.ldlt().solve(bvec);
  if (std::atan(std::hypot(abc.x(), abc.y())) > deg_to_rad(criteria.max_slope_deg)) return false;
  double rmin = 1e9, rmax = -1e9;
  for (const auto& p : disc) {
    const double r = p.z() - (abc.x() * p.x() + abc.y() * p.y() + abc.z());
    rmin = std::min(rmin, r);
    rmax = std::max(rmax, r);
  }
  if (rmax - rmin > criteria.max_step_m) return false;
  // The clearance ring: nothing taller than the plane (extended) by taller_than_m.
  for (int j = cj - r_cells; j <= cj + r_cells; ++j)
    for (int i = ci - r_cells; i <= ci + r_cells; ++i) {
      const double x = lo_.x() + (i + 0.5) * cell_m_ - center_m.x();
      const double y = lo_.y() + (j + 0.5) * cell_m_ - center_m.y();
      const double d = std::hypot(x, y);
      if (d <= touch || d > outer + cell_m_ * std::sqrt(0.5)) continue;
      if (at(i, j) > abc.x() * x + abc.y() * y + abc.z() + criteria.taller_than_m) return false;
    }
  return true;
}

bool TerrainGroundTruth::in_view(const Eigen::Vector2d& center_m, double radius_m,
                                 const CameraModel& camera, const Pose3& X_WC) const {
  const Pose3 X_CW = X_WC.inverse();
  const Eigen::Vector3d o = X_WC.translation();
  constexpr int kRim = 24;
  for (int k = 0; k <= kRim; ++k) {
    Eigen::Vector2d q = center_m;
    if (k < kRim) {
      const double a = 2 * kPi * k / kRim;
      q += radius_m * Eigen::Vector2d(std::cos(a), std::sin(a));
    }
    const Eigen::Vector3d p(q.x(), q.y(), surface_height(q.x(), q.y()));
    const auto px = camera.project(X_CW * p);
    if (!px || !camera.in_image(*px, 1.0)) return false;
    // Occlusion: march the height map from the camera to the point.
    const Eigen::Vector3d d = p - o;
    const int steps = static_cast<int>(std::ceil(d.head<2>().norm() / cell_m_)) + 1;
    for (int s = 1; s < steps; ++s) {
      const Eigen::Vector3d m = o + d * (static_cast<double>(s) / steps);
      if (m.z() < surface_height(m.x(), m.y()) - 0.01) return false;
    }
  }
  return true;
}

bool TerrainGroundTruth::safe_zone_in_view(double radius_m, double view_radius_m,
                                           const LandingCriteria& criteria,
                                           const CameraModel& camera, const Pose3& X_WC,
                                           double step_m) const {
  // Candidates on the ground under the image: intersect the corner rays with the
  // plane of the nadir's height to bound the search.
  const Eigen::Vector3d o = X_WC.translation();
  const double z0 = surface_height(o.x(), o.y());
  Eigen::AlignedBox2d box;
  for (const auto& px : {Eigen::Vector2d(0, 0), Eigen::Vector2d(camera.width_px - 1, 0),
                         Eigen::Vector2d(0, camera.height_px - 1),
                         Eigen::Vector2d(camera.width_px - 1, camera.height_px - 1)}) {
    const Eigen::Vector3d d = X_WC.linear() * camera.ray(px);
    if (d.z() >= -1e-6) return false;  // not a downward view
    const double t = (z0 - o.z()) / d.z();
    box.extend((o + t * d).head<2>());
  }
  // Sloped ground widens the footprint; a margin covers it.
  box.min() -= Eigen::Vector2d::Constant(2.0);
  box.max() += Eigen::Vector2d::Constant(2.0);
  for (double y = box.min().y(); y <= box.max().y(); y += step_m)
    for (double x = box.min().x(); x <= box.max().x(); x += step_m) {
      const Eigen::Vector2d c(x, y);
      if (!in_view(c, view_radius_m, camera, X_WC)) continue;
      if (is_safe(c, radius_m, criteria)) return true;
    }
  return false;
}

LandingScene landing_scene(std::uint64_t seed, int index, const CameraSensor& sensor,
                           const CameraModel& camera, const LandingSceneOptions& options) {
  LandingTerrain terrain = landing_terrain(seed, index);
  TerrainGroundTruth truth(terrain.world);
  const SensorSimulator sim(terrain.world);
  Rng rng(derive_seed(seed, {0x1a4e, static_cast<std::uint64_t>(index)}));
  std::vector<LandingFrame> frames;
  for (std::size_t k = 0; k < options.heights_m.size(); ++k) {
    LandingFrame f;
    f.height_m = options.heights_m[k];
    const Eigen::Vector2d c = terrain.view_center_m;
    const double roll = rng.uniform(-options.max_tilt_rad, options.max_tilt_rad);
    const double pitch = rng.uniform(-options.max_tilt_rad, options.max_tilt_rad);
    const double yaw = rng.uniform(-kPi, kPi);
    f.X_WB = pose_from_xyz_rpy({c.x(), c.y(), truth.surface_height(c.x(), c.y()) + f.height_m},
                               roll, pitch, yaw);
    if (truth.highest_within(c, options.footprint_radius_m) >
        f.X_WB.translation().z() - options.hover_clearance_m)
      continue;  // the UAV would be inside it (the draws above keep the other frames' poses)
    f.X_WC = optical_pose(f.X_WB, sensor);
    f.depth = sim.render_depth(camera, f.X_WC, options.depth,
                               derive_seed(seed, {0x1a4f, static_cast<std::uint64_t>(index), k}));
    f.safe_zone_in_view = truth.safe_zone_in_view(options.footprint_radius_m, options.view_radius_m,
                                                  options.criteria, camera, f.X_WC);
    // The hover's further frames: drawn from their own stream, so that the first frame
    // of every view is the same bytes whatever frames_per_view is.
    Rng drift(derive_seed(seed, {0x1a50, static_cast<std::uint64_t>(index), k}));
    for (int m = 1; m < options.frames_per_view; ++m) {
      const double dm = options.hover_drift_m, dr = options.hover_drift_rad;
      const Eigen::Vector3d d_m(drift.uniform(-dm, dm), drift.uniform(-dm, dm),
                                drift.uniform(-dm, dm));
      const double r = drift.uniform(-dr, dr), p = drift.uniform(-dr, dr),
                   y = drift.uniform(-dr, dr);
      const Pose3 X_WB = Eigen::Translation3d(d_m) * f.X_WB * pose_from_xyz_rpy({0, 0, 0}, r, p, y);
      f.more_X_WC.push_back(optical_pose(X_WB, sensor));
      f.more_depth.push_back(
          sim.render_depth(camera, f.more_X_WC.back(), options.depth,
                           derive_seed(seed, {0x1a51, static_cast<std::uint64_t>(index), k,
                                              static_cast<std::uint64_t>(m)})));
    }
    frames.push_back(std::move(f));
  }
  return {std::move(terrain), std::move(truth), std::move(frames)};
}

}  // namespace ferret
