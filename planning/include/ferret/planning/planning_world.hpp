#pragma once
// What the planning commands share: a world loaded from a world YAML (built into an
// OctoMap) or an OctoMap file, the hidden-space frames a world YAML defines, the
// snapshots the two robots plan against, and the robot shapes from a URDF.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/mapping/world_spec.hpp"
#include "ferret/planning/collision_map.hpp"
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
};

/// Loads `.yaml`/`.yml` (built), `.bt` or `.ot`. InputError for anything else.
[[nodiscard]] PlanningWorld load_planning_world(const std::filesystem::path& path);

/// The planning frame of a hidden space of a world YAML: the axis-aligned box around
/// its interior, its floor, its entry point.
[[nodiscard]] HiddenSpaceFrame hidden_space_frame(const HiddenSpace& space);
/// Index of the hidden space whose interior contains (x, y) at floor level, or -1.
[[nodiscard]] int hidden_space_at(const WorldSpec& world, const Eigen::Vector2d& p_W);

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

/// The shape a plan's robot is checked with: from a URDF when given (a miniUGV's
/// shapes lifted by `ugv.ground_clearance_m`, so wheels resting on floor voxels do not
/// touch them), otherwise ferret's defaults (robot_shape.hpp); for kUavWithUgv the
/// tether and the miniUGV hang below at `released_length_m`.
[[nodiscard]] RobotShape plan_robot_shape(PlanRobot robot, double released_length_m,
                                          const RobotShape* urdf_shape = nullptr, const UgvGeometry& ugv = {});

/// "x,y,..." with exactly `count` finite numbers; InputError naming `option` otherwise.
[[nodiscard]] std::vector<double> parse_number_list(const std::string& text, std::size_t count,
                                                    const std::string& option);

}  // namespace ferret
