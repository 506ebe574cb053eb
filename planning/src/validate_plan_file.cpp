// validate_plan_file(): everything `ferret validate` does between reading its options
// and printing the report. How each input is chosen is docs/validate.md's table.

#include <fmt/format.h>
#include <octomap/OcTree.h>
#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "ferret/core/error.hpp"
#include "ferret/planning/floor_from_map.hpp"
#include "ferret/planning/plan_validation.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

// The names the world YAML gives its boxes and cylinders (WorldSpec keeps the
// geometry only); "boxes[i]" where a YAML entry has none.
std::vector<std::string> yaml_names(const std::filesystem::path& yaml, const char* key,
                                    std::size_t count) {
  std::vector<std::string> names;
  try {
    const YAML::Node doc = YAML::LoadFile(yaml.string());
    const YAML::Node list = doc[key];
    for (std::size_t i = 0; i < count; ++i) {
      const YAML::Node item = list && list.IsSequence() && i < list.size() ? list[i] : YAML::Node();
      names.push_back(item && item.IsMap() && item["name"] ? item["name"].as<std::string>()
                                                           : fmt::format("{}[{}]", key, i));
    }
  } catch (const YAML::Exception&) {  // the world loaded already: this only fails with it gone
    for (std::size_t i = names.size(); i < count; ++i)
      names.push_back(fmt::format("{}[{}]", key, i));
  }
  return names;
}

// What a world YAML has at p_W: objects first (they lie inside hidden spaces), then
// enclosures, named boxes and cylinders, rubble, the ground.
std::function<std::string(const Eigen::Vector3d&)> world_namer(const WorldSpec& spec) {
  const auto boxes = yaml_names(spec.source, "boxes", spec.boxes.size());
  const auto cylinders = yaml_names(spec.source, "cylinders", spec.cylinders.size());
  return [spec, boxes, cylinders](const Eigen::Vector3d& p) -> std::string {
    for (const WorldObject& o : spec.objects)
      if (o.box.contains(p)) return o.name;
    for (const HiddenSpace& h : spec.hidden_spaces)
      for (const OrientedBox& s : h.solids())
        if (s.contains(p)) return h.name;
    for (std::size_t i = 0; i < spec.boxes.size(); ++i)
      if (spec.boxes[i].contains(p)) return boxes[i];
    for (std::size_t i = 0; i < spec.cylinders.size(); ++i)
      if (spec.cylinders[i].contains(p)) return cylinders[i];
    for (std::size_t i = 0; i < spec.rubble.size(); ++i)
      if (spec.rubble[i].contains(p)) return fmt::format("rubble[{}]", i);
    if (p.z() <= spec.ground.height_at(p.x(), p.y())) return "ground";
    for (const HiddenSpace& h : spec.hidden_spaces)
      if (h.outer_bounds_m().contains(p)) return h.name + " floor";
    return "";
  };
}

void check_request(const ValidateRequest& request) {
  if (request.tether_budget_m &&
      !(std::isfinite(*request.tether_budget_m) && *request.tether_budget_m > 0 &&
        *request.tether_budget_m <= 1000))
    throw InputError("--tether-budget", "", "a taut tether length in (0, 1000] m",
                     fmt::format("{}", *request.tether_budget_m));
  if (request.floor_z_m && !std::isfinite(*request.floor_z_m))
    throw InputError("--floor-z", "", "a finite height in metres",
                     fmt::format("{}", *request.floor_z_m));
  if (request.bounds && !(request.bounds->lo.allFinite() && request.bounds->hi.allFinite() &&
                          (request.bounds->lo.array() < request.bounds->hi.array()).all()))
    throw InputError("--bounds", "", "x0,y0,z0,x1,y1,z1: finite, with min < max on every axis");
  if (request.p_WE && !request.p_WE->allFinite())
    throw InputError("--entry", "", "a finite point x,y");
}

// Everything after the plan's and the request's own checks.
ValidationReport validate_checked_plan(PlanFile plan, const PlanningWorld& world,
                                       const ValidateRequest& request, const std::string& source);

}  // namespace

ValidationReport validate_plan_file(const std::filesystem::path& plan_path,
                                    const std::filesystem::path& world_path,
                                    const ValidateRequest& request) {
  PlanFile plan = load_plan(plan_path);
  check_yaw_is_radians(plan, plan_path.string());
  // The request is checked before the (slow) world is built.
  check_request(request);
  return validate_checked_plan(std::move(plan), load_planning_world(world_path), request,
                               plan_path.string());
}

ValidationReport validate_plan(PlanFile plan, const PlanningWorld& world,
                               const ValidateRequest& request, const std::string& source) {
  check_yaw_is_radians(plan, source);
  check_request(request);
  return validate_checked_plan(std::move(plan), world, request, source);
}

namespace {

ValidationReport validate_checked_plan(PlanFile plan, const PlanningWorld& world,
                                       const ValidateRequest& request, const std::string& source) {
  const std::filesystem::path world_path = world.source;
  const MissionConfig mission =
      request.mission ? load_mission_config(*request.mission) : MissionConfig{};

  // The robot's shapes: the request's URDF, else the one the plan was made with, else built-in.
  std::optional<RobotDescription> urdf;
  if (request.robot_urdf) {
    urdf = load_robot_description(*request.robot_urdf, mission);
  } else if (!request.builtin_shapes && !plan.robot_model.empty()) {
    // A model path written relative to another directory: the shipped model of that name.
    std::filesystem::path model = plan.robot_model;
    if (!std::filesystem::exists(model)) model = find_model(model.filename().string());
    urdf = load_robot_description(model, mission);
  }
  if (!plan.robot_known) {
    // The plan is what lacks the robot; --robot is how to give it.
    if (!urdf)
      throw InputError(source, "robot",
                       "a plan that names its robot, or --robot URDF|NAME (a CSV or a JSON of "
                       "states does not say which robot it is)",
                       "no robot");
    plan.robot = urdf->kind == RobotKind::kUgv ? PlanRobot::kUgv : PlanRobot::kUav;
  } else if (urdf && (urdf->kind == RobotKind::kUgv) != (plan.robot == PlanRobot::kUgv)) {
    if (request.robot_urdf)
      throw InputError("--robot", "",
                       fmt::format("a URDF of the plan's robot ({})", to_string(plan.robot)),
                       urdf->source);
    throw InputError(source, "robot_model",
                     fmt::format("a URDF of the plan's robot ({})", to_string(plan.robot)),
                     urdf->source);
  }
  check_plan_work(plan, default_resolution(plan.robot), source);
  const bool ugv = plan.robot == PlanRobot::kUgv;
  // A ground robot's box (the unknown-is-occupied band, the tether's obstacle band):
  // its URDF's, as the planner used it; the miniUGV's defaults for built-in shapes.
  const UgvGeometry ugv_box = ugv && urdf ? ugv_geometry_from_description(*urdf) : UgvGeometry{};

  // The box: the request's, else the plan's, else (miniUGV in a world YAML) the hidden
  // space the plan starts in. It is where unknown space is occupied, the geofence,
  // and for the miniUGV the tether's obstacle region.
  std::optional<Aabb3> bounds = request.bounds ? request.bounds : plan.bounds;
  std::string bounds_source = request.bounds ? "--bounds" : "plan";
  // Where a bad box came from, for messages: the option, the plan's field or the world's.
  std::pair<std::string, std::string> bounds_origin =
      request.bounds ? std::pair<std::string, std::string>{"--bounds", ""}
                     : std::pair<std::string, std::string>{source, "bounds"};
  std::optional<Eigen::Vector2d> entry = request.p_WE;
  std::optional<double> floor_z = request.floor_z_m;
  std::string floor_source = "--floor-z";
  if (ugv && world.spec) {
    const int index =
        hidden_space_at(*world.spec, {plan.states.front().x_m, plan.states.front().y_m});
    if (index >= 0) {
      const HiddenSpace& h = world.spec->hidden_spaces[static_cast<std::size_t>(index)];
      const HiddenSpaceFrame space = hidden_space_frame(h);
      if (!bounds) {
        bounds = ugv_policy_bounds(space, ugv_box);
        bounds_source = "hidden space " + h.name;
        bounds_origin = {world_path.string(), "hidden space '" + h.name + "'"};
      }
      if (!entry && !plan.tether) entry = space.p_WE;
      if (!floor_z) {
        floor_z = space.floor_z_m;
        floor_source = "hidden space " + h.name;
      }
    }
  } else if (ugv && world.map_2d) {
    // A 2D map is one hidden space, its whole extent (it names no entry).
    const HiddenSpaceFrame space = map_2d_frame(*world.map_2d);
    if (!bounds) {
      bounds = ugv_policy_bounds(space, ugv_box);
      bounds_source = "the 2D map";
      bounds_origin = {world_path.string(), "the 2D map's extent"};
    }
    if (!floor_z) {
      floor_z = space.floor_z_m;
      floor_source = "the 2D map";
    }
  }
  UnknownPolicy unknown =
      plan.unknown_policy.value_or(ugv ? UnknownPolicy::kOccupied : UnknownPolicy::kFree);
  if (request.unknown) unknown = *request.unknown;
  // No box: the plan has none and no hidden space holds its start; --bounds would give one.
  const std::string no_box = world.spec ? ", no hidden space of the world holds its start" : "";
  if (unknown == UnknownPolicy::kOccupied && !bounds)
    throw InputError(source, "bounds",
                     "a box where unknown space counts as occupied (the plan's bounds, a hidden "
                     "space holding its start, or --bounds x0,y0,z0,x1,y1,z1)",
                     "the plan has no bounds" + no_box);
  if (ugv && !bounds)
    throw InputError(source, "bounds",
                     "the hidden space's box for the tether's obstacles (the plan's bounds, a "
                     "hidden space holding its start, or --bounds x0,y0,z0,x1,y1,z1)",
                     "the plan has no bounds" + no_box);
  // The box becomes voxel keys: it must lie inside the map's key range (named where it came from).
  if (bounds && (ugv || unknown == UnknownPolicy::kOccupied)) {
    const double span_m = 32766.0 * world.tree->getResolution() - 1.0;
    if (!((bounds->lo.array().abs() <= span_m).all() && (bounds->hi.array().abs() <= span_m).all()))
      throw InputError(
          bounds_origin.first, bounds_origin.second,
          fmt::format("a box within +-{:g} m (the map's key range at {:g} m voxels)", span_m,
                      world.tree->getResolution()),
          fmt::format("[{:g}, {:g}, {:g}] - [{:g}, {:g}, {:g}]", bounds->lo.x(), bounds->lo.y(),
                      bounds->lo.z(), bounds->hi.x(), bounds->hi.y(), bounds->hi.z()));
    // At least one voxel centre on every axis (the map's own rule for a box).
    const double res = world.tree->getResolution();
    const Eigen::Vector3d lo = bounds->lo, hi = bounds->hi;
    const std::array<char, 3> axes{'x', 'y', 'z'};
    for (int a = 0; a < 3; ++a)
      if (std::ceil(lo[a] / res - 0.5) > std::floor(hi[a] / res - 0.5))
        throw InputError(
            bounds_origin.first, bounds_origin.second,
            fmt::format("a box holding a voxel centre on every axis ({:g} m voxels)", res),
            fmt::format("{} from {:g} to {:g} m", axes[static_cast<std::size_t>(a)], lo[a], hi[a]));
  }
  // The floor under a miniUGV: from the map, never from the box's lower z (which may
  // lie anywhere in or under the floor slab).
  if (ugv && !floor_z) {
    floor_z = floor_z_from_map(*world.tree, *bounds);
    floor_source = "map";
    if (!floor_z)
      throw InputError(world_path.string(),
                       request.bounds ? "floor under --bounds" : "floor under the plan's bounds",
                       "occupied voxels under the box to find the floor (or --floor-z Z)", "none");
  }

  // The geofence: the box, else the world's bounds (world YAML) or the map's extent.
  std::optional<Aabb3> geofence = bounds;
  std::string geofence_source = bounds_source;
  if (!geofence && world.spec) {
    geofence = Aabb3{world.spec->bounds_min_m, world.spec->bounds_max_m};
    geofence_source = "world bounds";
  } else if (!geofence) {
    double x0, y0, z0, x1, y1, z1;
    world.tree->getMetricMin(x0, y0, z0);
    world.tree->getMetricMax(x1, y1, z1);
    geofence = Aabb3{{x0, y0, z0}, {x1, y1, z1}};
    geofence_source = "map extent";
  }

  CollisionMapOptions map_opt;
  if (ugv) {
    map_opt.unknown = unknown;
    map_opt.bounds = bounds;
    // A fine field over the box, without the floor the miniUGV rides on (the clearance
    // margin is to everything else).
    map_opt.field_region = Aabb3{bounds->lo - Eigen::Vector3d(0.5, 0.5, 0.1),
                                 bounds->hi + Eigen::Vector3d(0.5, 0.5, 0.3)};
    map_opt.field_floor_cut_z = *floor_z;
  } else {
    map_opt = uav_map_options(world.spec, unknown, bounds);
  }
  const auto map = [&] {
    try {
      return request.collision_map ? request.collision_map(*world.tree, map_opt)
                                   : CollisionMap::build(*world.tree, map_opt);
    } catch (const InputError& e) {
      // The box came from the plan or --bounds: name it there, not as the map's.
      if (e.source() != "map" || e.field() != "bounds") throw;
      const std::string head = "map: bounds: expected " + e.expected();
      std::string got = std::string(e.what()).substr(std::min(head.size(), std::strlen(e.what())));
      if (got.rfind(" (got ", 0) == 0 && got.size() > 7) got = got.substr(6, got.size() - 7);
      throw InputError(bounds_origin.first, bounds_origin.second, e.expected(), got);
    }
  }();

  std::optional<RobotShape> urdf_shape;
  if (urdf) urdf_shape = robot_shape_from_description(*urdf);
  CollisionChecker checker(map, plan_robot_shape(plan.robot, plan.released_length_m,
                                                 urdf_shape ? &*urdf_shape : nullptr));

  // The limits: the robot's (its URDF, with the mission), or the plan's own unless a
  // robot or mission was given.
  MotionLimits limits = urdf ? urdf->limits : (ugv ? mission.ugv_limits : mission.uav_limits);
  std::string limits_source = urdf              ? "robot " + urdf->source
                              : request.mission ? "mission"
                                                : "mission defaults";
  if (!request.robot_urdf && !request.mission &&
      (plan.max_velocity_mps || plan.max_acceleration_mps2 || plan.max_yaw_rate_radps)) {
    limits.max_velocity_mps = plan.max_velocity_mps.value_or(limits.max_velocity_mps);
    limits.max_acceleration_mps2 =
        plan.max_acceleration_mps2.value_or(limits.max_acceleration_mps2);
    limits.max_yaw_rate_radps = plan.max_yaw_rate_radps.value_or(limits.max_yaw_rate_radps);
    limits_source = "plan (else " + limits_source + ")";
    // A plan that states the limits it was timed with but no acceleration was timed
    // without an acceleration model (ferret's planners today: every drive starts at
    // full speed); the robot's limit is checked when --robot or --mission is given.
    if (!plan.max_acceleration_mps2) {
      limits.max_acceleration_mps2 = std::numeric_limits<double>::infinity();
      limits_source += "; acceleration unchecked: the plan's limits have none";
    }
  }
  ValidationOptions opt(limits, default_resolution(plan.robot));
  opt.geofence = geofence;
  opt.tether_max_m = request.tether_budget_m;
  opt.p_WE = entry;
  if (ugv && !plan.tether && !opt.tether_max_m)
    opt.tether_max_m = mission.tether.total_length_m - mission.tether.entry_offset_m;
  if (ugv && !plan.tether && !entry)
    throw InputError(source, "tether",
                     "a tether section, a hidden space of the world holding the plan's start, "
                     "or --entry x,y",
                     "no tether entry");
  opt.observed = world.tree.get();
  if (world.spec) opt.name_obstacle = world_namer(*world.spec);
  opt.cancelled = request.cancelled;
  std::shared_ptr<const TetherCorners> corners;
  if (ugv) {
    HiddenSpaceFrame f;
    f.lo_m = bounds->lo.head<2>();
    f.hi_m = bounds->hi.head<2>();
    f.floor_z_m = *floor_z;
    corners = tether_corners_from_map(*map, f, ugv_box);
  }
  ValidationReport report = validate_plan(plan, checker, corners, opt);
  ValidationInputs& r = report.inputs;
  r.plan = source;
  r.world = world_path.string();
  r.robot_model = urdf ? urdf->source : "builtin";
  r.limits_source = limits_source;
  r.unknown = unknown;
  r.geofence_source = geofence_source;
  if (ugv) {
    r.floor_z_m = floor_z;
    r.floor_source = floor_source;
    r.p_WE = plan.tether ? plan.tether->p_WE : *entry;
  }
  return report;
}

}  // namespace

}  // namespace ferret
