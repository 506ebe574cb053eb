#include "ferret/planning/planning_world.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {

PlanningWorld load_planning_world(const std::filesystem::path& path) {
  if (is_map_server_yaml(path))
    return planning_world_from_map_2d(load_map_server(path), path.string());
  PlanningWorld w;
  w.source = path;
  w.tree = load_or_build_octree(path, &w.spec);
  return w;
}

PlanningWorld planning_world_from_map_2d(const OccupancyMap2D& map, const std::string& source,
                                         const Map2DExtrusion& extrusion) {
  PlanningWorld w;
  w.source = source;
  w.tree = extrude_map_2d(map, source, extrusion);
  w.map_2d = map.geometry;
  return w;
}

HiddenSpaceFrame map_2d_frame(const GridGeometry& g) {
  HiddenSpaceFrame f;
  f.lo_m = {g.origin_x_m, g.origin_y_m};
  f.hi_m = {g.origin_x_m + g.width * g.resolution_m, g.origin_y_m + g.height * g.resolution_m};
  f.floor_z_m = 0.0;
  f.p_WE = Eigen::Vector2d::Zero();
  return f;
}

HiddenSpaceFrame hidden_space_frame(const HiddenSpace& space) {
  HiddenSpaceFrame f;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (int sx : {-1, 1}) {
    for (int sy : {-1, 1}) {
      const Eigen::Vector3d c = space.to_world(
          {0.5 * sx * space.interior_size_m.x(), 0.5 * sy * space.interior_size_m.y(), 0.0});
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

const HiddenSpace& find_hidden_space(const PlanningWorld& world, const std::string& name,
                                     const std::string& source, const std::string& field) {
  if (!world.spec)
    throw InputError(
        source, field,
        "a world YAML (an OctoMap file names no hidden spaces): " + world.source.string(), name);
  const int index = world.spec->find_hidden_space(name);
  if (index < 0) {
    std::string names;
    for (const HiddenSpace& h : world.spec->hidden_spaces)
      names += (names.empty() ? "" : ", ") + h.name;
    throw InputError(source, field,
                     "one of the hidden spaces of " + world.source.string() + ": " +
                         (names.empty() ? "(none)" : names),
                     name);
  }
  return world.spec->hidden_spaces[static_cast<std::size_t>(index)];
}

Waypoint approach_hover_pose(const HiddenSpace& space, double standoff_m, double hover_height_m) {
  const Eigen::Vector2d inward(std::cos(space.entry_yaw_rad), std::sin(space.entry_yaw_rad));
  Waypoint w;
  w.x_m = space.p_WE.x() - standoff_m * inward.x();
  w.y_m = space.p_WE.y() - standoff_m * inward.y();
  w.z_m = space.floor_z_m + hover_height_m;
  w.yaw_rad = space.entry_yaw_rad;
  return w;
}

Aabb3 default_uav_bounds(const PlanningWorld& world) {
  Eigen::Vector3d lo, hi;
  if (world.spec) {
    lo = world.spec->bounds_min_m;
    hi = world.spec->bounds_max_m;
  } else {
    world.tree->getMetricMin(lo.x(), lo.y(), lo.z());
    world.tree->getMetricMax(hi.x(), hi.y(), hi.z());
  }
  // Half a metre of air above the ground and below the ceiling of the world.
  return {{lo.x(), lo.y(), std::max(lo.z(), 0.0) + 0.5}, {hi.x(), hi.y(), hi.z() - 0.5}};
}

Aabb3 ugv_policy_bounds(const HiddenSpaceFrame& space, const UgvGeometry& ugv) {
  const double top = space.floor_z_m + ugv.ground_clearance_m + ugv.body_size_m.z() + 0.05;
  return {{space.lo_m.x(), space.lo_m.y(), space.floor_z_m}, {space.hi_m.x(), space.hi_m.y(), top}};
}

std::shared_ptr<const CollisionMap> ugv_collision_map(const octomap::OcTree& tree,
                                                      const HiddenSpaceFrame& space,
                                                      const UgvGeometry& ugv) {
  CollisionMapOptions opt;
  opt.unknown = UnknownPolicy::kOccupied;
  opt.bounds = ugv_policy_bounds(space, ugv);
  // A fine field over the hidden space only, without the floor the miniUGV rides on.
  opt.field_region = Aabb3{opt.bounds->lo - Eigen::Vector3d(0.5, 0.5, 0.1),
                           opt.bounds->hi + Eigen::Vector3d(0.5, 0.5, 0.3)};
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

namespace {

// The lowest and highest z of a shape's parts, and its xy extent, in B.
Eigen::AlignedBox3d shape_box_B(const RobotShape& shape) {
  Eigen::AlignedBox3d box;
  for (const ShapePart& p : shape.parts) {
    const Eigen::Matrix3d R = p.X_BS.linear();
    Eigen::Vector3d half;
    switch (p.kind) {
      case ShapePart::Kind::kBox:
        half = R.cwiseAbs() * (p.box_size_m / 2.0);
        break;
      case ShapePart::Kind::kCylinder:
      case ShapePart::Kind::kCapsule: {
        // The axis contributes |a_i| L/2; a cylinder's end discs r sqrt(1 - a_i^2), a
        // capsule's caps r.
        const Eigen::Vector3d a = R.col(2);
        for (int i = 0; i < 3; ++i)
          half[i] = std::abs(a[i]) * p.length_m / 2.0 +
                    (p.kind == ShapePart::Kind::kCapsule
                         ? p.radius_m
                         : p.radius_m * std::sqrt(std::max(0.0, 1.0 - a[i] * a[i])));
        break;
      }
      case ShapePart::Kind::kSphere:
      default:
        half = Eigen::Vector3d::Constant(p.radius_m);
        break;
    }
    box.extend(p.X_BS.translation() - half);
    box.extend(p.X_BS.translation() + half);
  }
  return box;
}

}  // namespace

RobotShape plan_robot_shape(PlanRobot robot, double released_length_m, const RobotShape* urdf_shape,
                            const UgvGeometry& ugv) {
  if (!urdf_shape) {
    switch (robot) {
      case PlanRobot::kUav:
        return uav_shape();
      case PlanRobot::kUavWithUgv:
        return uav_with_suspended_ugv_shape(released_length_m, {}, ugv);
      case PlanRobot::kUgv:
        return ugv_shape(ugv);
    }
  }
  RobotShape s = *urdf_shape;
  if (robot == PlanRobot::kUgv && !s.parts.empty()) {
    // Frame G is on the floor; a URDF's base frame may be anywhere in the body (the
    // miniUGV's is on the ground, another robot's at its centre).
    const double lift = ugv.ground_clearance_m - shape_box_B(s).min().z();
    for (ShapePart& p : s.parts) p.X_BS.translation().z() += lift;
  } else if (robot == PlanRobot::kUavWithUgv) {
    const RobotShape hanging = uav_with_suspended_ugv_shape(released_length_m, {}, ugv);
    for (const ShapePart& p : hanging.parts)
      if (p.name == "tether" || p.name == "ugv_body") s.parts.push_back(p);
  }
  return s;
}

LoadedPlanRobot load_plan_robot(PlanRobot robot, const PlanRobotModel& model,
                                const MissionConfig& mission, double released_length_m,
                                const std::string& source, const std::string& field) {
  const bool ground = robot == PlanRobot::kUgv;
  LoadedPlanRobot out;
  if (model.builtin) {
    out.shape = plan_robot_shape(robot, released_length_m, nullptr, out.ugv);
    out.limits = ground ? mission.ugv_limits : mission.uav_limits;
    return out;
  }
  const std::filesystem::path path =
      model.urdf.empty() ? find_model(ground ? "miniugv.urdf" : "m100.urdf") : model.urdf;
  const RobotDescription description = load_robot_description(path, mission);
  const RobotKind expected = ground ? RobotKind::kUgv : RobotKind::kUav;
  if (description.kind != expected)
    throw InputError(source, field, std::string("a URDF of a ") + to_string(expected),
                     path.string());
  const RobotShape urdf_shape = robot_shape_from_description(description);
  // The ground robot's box, for the bands over the floor and the retrace offsets.
  if (ground) out.ugv = ugv_geometry_from_description(description);
  out.shape = plan_robot_shape(robot, released_length_m, &urdf_shape, out.ugv);
  out.limits = description.limits;
  // Relative to the working directory when it lies below it (the plan then reads the
  // same from any checkout), absolute otherwise.
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec).lexically_normal();
  const std::filesystem::path relative =
      absolute.lexically_relative(std::filesystem::current_path(ec));
  out.model =
      (!relative.empty() && *relative.begin() != "..") ? relative.string() : absolute.string();
  return out;
}

std::vector<double> parse_number_list(const std::string& text, std::size_t count,
                                      const std::string& option) {
  std::vector<double> out;
  const std::string expected = std::to_string(count) + " comma-separated finite numbers";
  std::size_t start = 0;
  while (out.size() <= count) {
    const auto comma = text.find(',', start);
    const std::string cell =
        text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (!number_error(cell, NumberRange::finite()).empty())
      throw InputError(option, "", expected, text);
    out.push_back(parse_number(cell, NumberRange::finite(), option));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (out.size() != count) throw InputError(option, "", expected, text);
  return out;
}

}  // namespace ferret
