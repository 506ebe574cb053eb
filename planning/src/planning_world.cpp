#include "ferret/planning/planning_world.hpp"

#include <octomap/OcTree.h>

#include <cmath>
#include <sstream>

#include "ferret/core/error.hpp"
#include "ferret/mapping/world_octree.hpp"

namespace ferret {

PlanningWorld load_planning_world(const std::filesystem::path& path) {
  PlanningWorld w;
  w.source = path;
  w.tree = load_or_build_octree(path, &w.spec);
  return w;
}

HiddenSpaceFrame hidden_space_frame(const HiddenSpace& space) {
  HiddenSpaceFrame f;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (int sx : {-1, 1}) {
    for (int sy : {-1, 1}) {
      const Eigen::Vector3d c = space.to_world({0.5 * sx * space.interior_size_m.x(),
                                                0.5 * sy * space.interior_size_m.y(), 0.0});
      lo = lo.cwiseMin(c.head<2>());
      hi = hi.cwiseMax(c.head<2>());
    }
  }
  f.lo_m = lo;
  f.hi_m = hi;
  f.floor_z_m = space.floor_z_m;
  f.p_WE = space.p_WE.head<2>();
  return f;
}

int hidden_space_at(const WorldSpec& world, const Eigen::Vector2d& p_W) {
  for (std::size_t k = 0; k < world.hidden_spaces.size(); ++k) {
    const HiddenSpace& h = world.hidden_spaces[k];
    if (h.interior_contains({p_W.x(), p_W.y(), h.floor_z_m + 0.02})) return static_cast<int>(k);
  }
  return -1;
}

Aabb3 ugv_policy_bounds(const HiddenSpaceFrame& space, const UgvGeometry& ugv) {
  const double top = space.floor_z_m + ugv.ground_clearance_m + ugv.body_size_m.z() + 0.05;
  return {{space.lo_m.x(), space.lo_m.y(), space.floor_z_m}, {space.hi_m.x(), space.hi_m.y(), top}};
}

std::shared_ptr<const CollisionMap> ugv_collision_map(const octomap::OcTree& tree, const HiddenSpaceFrame& space,
                                                      const UgvGeometry& ugv) {
  CollisionMapOptions opt;
  opt.unknown = UnknownPolicy::kOccupied;
  opt.bounds = ugv_policy_bounds(space, ugv);
  // A fine field over the hidden space only, without the floor the miniUGV rides on.
  opt.field_region = Aabb3{opt.bounds->lo - Eigen::Vector3d(0.5, 0.5, 0.1), opt.bounds->hi + Eigen::Vector3d(0.5, 0.5, 0.3)};
  opt.field_floor_cut_z = space.floor_z_m;
  opt.ground_band_z = std::pair{space.floor_z_m, opt.bounds->hi.z()};
  return CollisionMap::build(tree, opt);
}

CollisionMapOptions uav_map_options(const std::optional<WorldSpec>& world, UnknownPolicy unknown,
                                    const std::optional<Aabb3>& fence) {
  CollisionMapOptions opt;
  opt.unknown = unknown;
  if (unknown == UnknownPolicy::kOccupied) opt.bounds = fence;
  if (world && world->ground.slope_x == 0.0 && world->ground.slope_y == 0.0) {
    // The ground's voxels end at its height only when it lies on a voxel boundary.
    const double cells = world->ground.height_m / world->resolution_m;
    if (std::abs(cells - std::round(cells)) < 1e-9) opt.field_floor_cut_z = world->ground.height_m;
  }
  return opt;
}

RobotShape plan_robot_shape(PlanRobot robot, double released_length_m, const RobotShape* urdf_shape,
                            const UgvGeometry& ugv) {
  if (!urdf_shape) {
    switch (robot) {
      case PlanRobot::kUav: return uav_shape();
      case PlanRobot::kUavWithUgv: return uav_with_suspended_ugv_shape(released_length_m, {}, ugv);
      case PlanRobot::kUgv: return ugv_shape(ugv);
    }
  }
  RobotShape s = *urdf_shape;
  if (robot == PlanRobot::kUgv) {
    for (ShapePart& p : s.parts) p.X_BS.translation().z() += ugv.ground_clearance_m;
  } else if (robot == PlanRobot::kUavWithUgv) {
    const RobotShape hanging = uav_with_suspended_ugv_shape(released_length_m, {}, ugv);
    for (const ShapePart& p : hanging.parts)
      if (p.name == "tether" || p.name == "ugv_body") s.parts.push_back(p);
  }
  return s;
}

std::vector<double> parse_number_list(const std::string& text, std::size_t count, const std::string& option) {
  std::vector<double> out;
  std::stringstream ss(text);
  const std::string expected = std::to_string(count) + " comma-separated numbers";
  for (std::string cell; std::getline(ss, cell, ',');) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(cell, &used);
    } catch (const std::exception&) {
      throw InputError(option, "", expected, text);
    }
    if (cell.find_first_not_of(" \t", used) != std::string::npos || !std::isfinite(v))
      throw InputError(option, "", expected, text);
    out.push_back(v);
  }
  if (out.size() != count) throw InputError(option, "", expected, text);
  return out;
}

}  // namespace ferret
