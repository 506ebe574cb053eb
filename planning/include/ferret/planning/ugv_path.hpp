#pragma once
// One call for a miniUGV path in a hidden space: the hidden space chosen by name, by
// the start's position or by an explicit box; the tether replayed from the path driven
// since the entry and held within its budget; the robot's shapes and its URDF's
// limits; returning the whole plan file `ferret plan ugv` writes. No OMPL or FCL types.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/planning/planning_world.hpp"

namespace ferret {

/// Plan to the goal (any tether-feasible way), or back along the tether (through its
/// wrap points in reverse, falling back to planning when that is blocked).
enum class UgvPathMode { kPlan, kReturnAlongTether };

struct UgvPathRequest {
  Pose2 start;  ///< x, y, yaw on the hidden space's floor
  Pose2 goal;
  /// The hidden space: by name (world YAML); "" the one whose interior holds `start`.
  std::string hidden_space;
  /// An explicit box instead (needed for OctoMap worlds): x, y the plan bounds, z0 the
  /// floor height (unless floor_z_m); replaces the named or found space's box.
  std::optional<Aabb3> bounds;
  std::optional<double> floor_z_m;      ///< top of the floor voxels; overrides the space's
  std::optional<Eigen::Vector2d> p_WE;  ///< tether entry point; default: the space's
  /// The taut length the miniUGV may use on the floor, L - l_0, (0, 1000] m; nullopt:
  /// the mission's tether.total_length_m - entry_offset_m.
  std::optional<double> tether_budget_m;
  /// The path driven since the entry (gives the tether its wrap points); empty: the
  /// tether lies straight from the entry to the start.
  std::vector<Eigen::Vector2d> driven;
  UgvPathMode mode = UgvPathMode::kPlan;
  PlanRobotModel robot;  ///< default: the shipped miniugv.urdf; its limits cap the speed
  MissionConfig mission;
  double time_limit_s = 1.0;  ///< (0, 3600]
  std::uint64_t seed = 1;
  /// Polled during the search (cheap: an atomic load); true stops it.
  std::function<bool()> cancelled;
};

struct UgvPathResult : PlanResult {
  std::vector<WrapPoint> final_wraps;  ///< the tether at the goal
  double tether_budget_m = 0.0;        ///< L - l_0 the plan was held to
};

/// Plans the miniUGV path of `request` in `world` (unknown space occupied inside the
/// hidden space). Returns solved = false with the reason when no tether-feasible path
/// is found. Throws InputError naming the request field (source "UgvPathRequest") for
/// bad input: non-finite poses or points, a hidden space the world does not have (the
/// message lists the world's), no hidden space at all (an OctoMap world without bounds
/// and entry), a budget or time limit out of range, a URDF of an aerial robot; and the
/// loaders' errors.
[[nodiscard]] UgvPathResult plan_ugv_path(const PlanningWorld& world,
                                          const UgvPathRequest& request);

/// What a miniUGV plan needs besides the request's poses, tether and limits: the hidden
/// space, the robot and the collision snapshot with the tether's corners in it. Making
/// it costs far more than a short plan (the distance field), so a program planning
/// many times in one space (the planner service) makes it once.
struct UgvPathSetup {
  HiddenSpaceFrame space;
  LoadedPlanRobot model;
  std::shared_ptr<const CollisionMap> map;
  std::shared_ptr<const TetherCorners> corners;
};

/// The hidden space `request` plans in: named, found from the start, or its explicit
/// box, floor and entry. Cheap; InputError as plan_ugv_path().
[[nodiscard]] HiddenSpaceFrame ugv_request_space(const PlanningWorld& world,
                                                 const UgvPathRequest& request);
/// The setup for `space` with the request's robot and mission (its poses are not read).
[[nodiscard]] UgvPathSetup prepare_ugv_path(const PlanningWorld& world,
                                            const UgvPathRequest& request,
                                            const HiddenSpaceFrame& space);
/// plan_ugv_path() with a setup prepare_ugv_path() made in this world for the request's
/// space, robot and mission.
[[nodiscard]] UgvPathResult plan_ugv_path(const PlanningWorld& world, const UgvPathRequest& request,
                                          const UgvPathSetup& setup);

}  // namespace ferret
