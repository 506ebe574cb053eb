#pragma once
// What the planning commands share: a world loaded from a world YAML (built into an
// OctoMap) or an OctoMap file, the hidden spaces a world YAML defines (their frames
// and the UAV's hover pose in front of each opening), the snapshots the two robots
// plan against, and the robot a plan is made for (shapes and limits from a URDF).

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/grid.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "ferret/planning/collision_map.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/planning/plan_failure.hpp"
#include "ferret/planning/plan_file.hpp"
#include "ferret/planning/robot_shape.hpp"
#include "ferret/planning/ugv_planner.hpp"

namespace octomap {
class OcTree;
}

namespace ferret {

struct PlanningWorld {
  std::filesystem::path source;
  std::shared_ptr<const octomap::OcTree> tree;
  std::optional<WorldSpec> spec;  ///< for world YAMLs
  /// For a 2D (map_server) map: its grid. The map is one hidden space, its whole
  /// extent with the floor at z = 0 (extrude_map_2d); it names no tether entry.
  std::optional<GridGeometry> map_2d;
};

/// Loads a world YAML (built), a map_server YAML (extruded: planning_world_from_map_2d),
/// `.bt` or `.ot`. InputError for anything else.
[[nodiscard]] PlanningWorld load_planning_world(const std::filesystem::path& path);
/// A 2D map as a planning world: extrude_map_2d() with `extrusion`, errors naming
/// `source`, which also becomes the world's source.
[[nodiscard]] PlanningWorld planning_world_from_map_2d(const OccupancyMap2D& map,
                                                       const std::string& source,
                                                       const Map2DExtrusion& extrusion = {});
/// The hidden space a 2D map is: its extent, the floor at z = 0, no entry yet (p_WE 0).
[[nodiscard]] HiddenSpaceFrame map_2d_frame(const GridGeometry& map);

/// The planning frame of a hidden space of a world YAML: the axis-aligned box around
/// its interior, its floor, its entry point.
[[nodiscard]] HiddenSpaceFrame hidden_space_frame(const HiddenSpace& space);
/// Index of the hidden space whose interior contains (x, y) at floor level, or -1.
[[nodiscard]] int hidden_space_at(const WorldSpec& world, const Eigen::Vector2d& p_W);
/// The hidden space called `name`. Throws InputError(source, field, "one of the
/// world's hidden spaces: a, b, ...", name) when there is none of that name, or when
/// the world is an OctoMap file (which names no hidden spaces).
[[nodiscard]] const HiddenSpace& find_hidden_space(const PlanningWorld& world,
                                                   const std::string& name,
                                                   const std::string& source,
                                                   const std::string& field);

/// The UAV's hover pose over the landing point in front of a hidden space's opening:
/// `standoff_m` out from the entry along the wall's normal, `hover_height_m` above the
/// floor, facing the opening.
[[nodiscard]] Waypoint approach_hover_pose(const HiddenSpace& space, double standoff_m = 1.0,
                                           double hover_height_m = 1.5);

/// The UAV's default geofence in a world: the world YAML's bounds (an OctoMap file:
/// its known extent) in x and y; in z from 0.5 m above the lower bound (or above z = 0,
/// whichever is higher) to 0.5 m below the top.
[[nodiscard]] Aabb3 default_uav_bounds(const PlanningWorld& world);

/// The region where the miniUGV's "unknown is occupied" policy applies: the hidden
/// space's box from its floor to a little above the miniUGV.
[[nodiscard]] Aabb3 ugv_policy_bounds(const HiddenSpaceFrame& space, const UgvGeometry& ugv = {});
/// A snapshot for the miniUGV (unknown occupied inside ugv_policy_bounds).
[[nodiscard]] std::shared_ptr<const CollisionMap> ugv_collision_map(const octomap::OcTree& tree,
                                                                    const HiddenSpaceFrame& space,
                                                                    const UgvGeometry& ugv = {});

/// Snapshot options for the UAV in a world: unknown space by `unknown` (inside
/// `fence` when occupied); with flat ground (a world YAML without slope), the ground
/// is left out of the distance field (field_floor_cut_z), so parts above it are
/// cleared by the clearance to everything else.
[[nodiscard]] CollisionMapOptions uav_map_options(const std::optional<WorldSpec>& world,
                                                  UnknownPolicy unknown = UnknownPolicy::kFree,
                                                  const std::optional<Aabb3>& fence = std::nullopt);

/// The shape a plan's robot is checked with: from a URDF when given (a ground robot's
/// shapes lifted so that their lowest point is `ugv.ground_clearance_m` above frame G
/// on the floor, so wheels resting on floor voxels do not touch them, wherever the
/// URDF puts its base frame), otherwise ferret's defaults (robot_shape.hpp); for kUavWithUgv the
/// tether and the miniUGV hang below at `released_length_m`.
[[nodiscard]] RobotShape plan_robot_shape(PlanRobot robot, double released_length_m,
                                          const RobotShape* urdf_shape = nullptr,
                                          const UgvGeometry& ugv = {});

/// Which robot a plan is made for. Its URDF gives the collision shapes and the motion
/// limits (RobotDescription::limits: the mission's, with the speed capped by the wheel
/// joints); ferret's built-in shapes take the mission's limits.
struct PlanRobotModel {
  std::filesystem::path urdf;  ///< empty: the shipped model (m100.urdf, miniugv.urdf)
  bool builtin = false;        ///< ferret's built-in shapes (robot_shape.hpp), no URDF
};

/// A plan's robot, loaded: what the planners and the plan file need of it.
struct LoadedPlanRobot {
  RobotShape shape;  ///< as checked (plan_robot_shape)
  MotionLimits limits;
  UgvGeometry ugv;    ///< a ground robot's bounding box (policy band, tether band, offsets)
  std::string model;  ///< the plan's robot_model: the URDF's path, "" for built-in shapes
};

/// Loads the robot of a `robot` plan. Throws InputError(source, field, ...) when the
/// URDF describes the other kind of robot, besides the loader's own errors.
[[nodiscard]] LoadedPlanRobot load_plan_robot(PlanRobot robot, const PlanRobotModel& model,
                                              const MissionConfig& mission,
                                              double released_length_m = 0.0,
                                              const std::string& source = "robot",
                                              const std::string& field = "");

/// What a one-call planner returns: the plan file, filled as `ferret plan` writes it
/// (its states empty when no path was found), and how the search went.
struct PlanResult {
  bool solved = false;
  std::string status;                        ///< "solved", or why not
  PlanFailure failure = PlanFailure::kNone;  ///< why not, as a value
  PlanFile plan;
  double planning_time_s = 0.0;  ///< wall time (not in the plan file: runs would differ)
};

/// "x,y,..." with exactly `count` finite numbers; InputError naming `option` otherwise.
[[nodiscard]] std::vector<double> parse_number_list(const std::string& text, std::size_t count,
                                                    const std::string& option);

}  // namespace ferret
