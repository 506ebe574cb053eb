#pragma once
// Offline plan validation (`ferret validate`, docs/validate.md): every segment checked
// at the exact checker's resolution (FCL alone, with the map's unknown-space policy),
// the geofence, speed, acceleration and yaw-rate limits, monotonic time, and for
// miniUGV plans the tether: replayed from its initial wrap points, l_0 + taut length
// <= L everywhere. The result is a report of every violation and the plan's margins.
//
// Two levels: validate_plan() checks a loaded plan against a checker the caller built;
// validate_plan_file() does everything `ferret validate` does (robot, limits, world,
// hidden space, floor, map, tether obstacles) from file names and a request.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "ferret/core/motion_limits.hpp"
#include "ferret/planning/collision_checker.hpp"
#include "ferret/planning/plan_file.hpp"

namespace octomap {
class OcTree;
}

namespace ferret {

struct PlanningWorld;

enum class ViolationKind {
  kCollision,     ///< a robot part overlaps an occupied voxel
  kUnknownSpace,  ///< ... a voxel that was never observed (occupied by the policy)
  kGeofence,      ///< a state outside the geofence
  kTimeOrder,     ///< time goes backwards, or the robot moves in no time
  kSpeed,         ///< a segment faster than max_velocity_mps
  kAcceleration,  ///< the velocity change at a state over max_acceleration_mps2
  kYawRate,       ///< a segment turning faster than max_yaw_rate_radps
  kTetherLength,  ///< the taut tether longer than its budget L - l_0
};
/// "collision", "unknown_space", "geofence", "time_order", "speed", "acceleration",
/// "yaw_rate", "tether_length".
[[nodiscard]] const char* to_string(ViolationKind kind);

/// What a voxel hit by a collision is: its centre and, when the world is a world YAML,
/// the thing it belongs to ("block", "boxes[2]", "cellar", "ground" ...; empty if unknown).
struct Obstacle {
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  std::string name;
};

struct Violation {
  ViolationKind kind = ViolationKind::kCollision;
  /// The segment it happens on: states from_index -> to_index. A violation at a state
  /// (geofence, tether, the first pose) has from_index == to_index; an acceleration
  /// at state k spans the two segments around it (k-1 -> k+1).
  std::size_t from_index = 0, to_index = 0;
  double s = 0.0;    ///< where inside the segment (0 at from_index, 1 at to_index)
  double t_s = 0.0;  ///< the interpolated time of the offending pose
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero();
  double yaw_rad = 0.0;
  std::string part;                  ///< collisions: the robot part (URDF link or built-in part)
  std::optional<Obstacle> obstacle;  ///< collisions: the voxel it hits
  /// The measured value and the limit it breaks, in the kind's unit (m/s, m/s^2,
  /// rad/s, m); NaN where the kind has none (collision, time order, geofence).
  double value = std::numeric_limits<double>::quiet_NaN();
  double limit = std::numeric_limits<double>::quiet_NaN();

  /// One line: "segment 0-1 at t = 0.935 s (s = 0.117), position (...): collision of
  /// chassis_link with block at (...)".
  [[nodiscard]] std::string describe() const;
};

/// The plan's margins over all of it (whatever its violations).
struct ValidationMargins {
  /// A lower bound on the smallest distance between the robot and the map over every
  /// checked pose (distance field; the floor a ground robot rides on left out); 0 where
  /// it may touch, +inf with nothing occupied in reach of the field.
  double min_clearance_m = std::numeric_limits<double>::infinity();
  double peak_speed_mps = 0.0;
  double peak_acceleration_mps2 = 0.0;
  double peak_yaw_rate_radps = 0.0;
  std::optional<double> peak_tether_m;    ///< miniUGV plans: the largest taut length
  std::optional<double> tether_budget_m;  ///< ... and its budget L - l_0
};

/// Where each input came from (for the report: what was checked, against what).
struct ValidationInputs {
  std::string plan, world;
  PlanRobot robot = PlanRobot::kUav;
  std::string robot_model;  ///< the URDF whose shapes were checked; "builtin" otherwise
  std::vector<std::string> parts;
  MotionLimits limits;
  /// "robot <urdf>", "mission", "mission defaults", or "plan (else ...)"
  std::string limits_source;
  UnknownPolicy unknown = UnknownPolicy::kFree;
  std::optional<Aabb3> geofence;
  std::string
      geofence_source;  ///< "--bounds", "plan", "hidden space <name>", "world bounds", "map extent"
  std::optional<double> floor_z_m;
  std::string floor_source;  ///< "--floor-z", "hidden space <name>", "map"
  std::optional<Eigen::Vector2d> p_WE;
  std::size_t states = 0;
  CheckResolution resolution;
};

struct ValidationReport {
  std::vector<Violation> violations;  ///< in the plan's order (by segment, then kind)
  ValidationMargins margins;
  ValidationInputs inputs;
  [[nodiscard]] bool valid() const { return violations.empty(); }
};

/// The limits and settings of a check. The limits are the robot's: there is no
/// default (a miniUGV value would silently apply to any robot).
struct ValidationOptions {
  explicit ValidationOptions(const MotionLimits& robot_limits,
                             const CheckResolution& check_resolution)
      : limits(robot_limits), resolution(check_resolution) {}
  MotionLimits limits;
  CheckResolution resolution;
  std::optional<Aabb3> geofence;
  /// The taut-tether budget L - l_0; nullopt: from the plan's tether section.
  std::optional<double> tether_max_m;
  /// Entry point for plans without a tether section (CSV); the tether starts straight.
  std::optional<Eigen::Vector2d> p_WE;
  /// The map as observed (before the unknown policy): a colliding voxel unknown there
  /// is reported as unknown_space. nullptr: every hit is a collision. Not owned.
  const octomap::OcTree* observed = nullptr;
  /// Names the thing a colliding voxel belongs to (validate_plan_file() names world
  /// YAML objects); empty: unnamed.
  std::function<std::string(const Eigen::Vector3d& p_W)> name_obstacle;
  /// Asked between states and every 64 poses checked; true stops the check with
  /// ValidationCancelled (a deadline passed, the client went away). Empty: never.
  std::function<bool()> cancelled;
};

/// validate_plan() was stopped by its `cancelled` flag before it finished.
class ValidationCancelled : public std::runtime_error {
 public:
  ValidationCancelled() : std::runtime_error("validation cancelled before it finished") {}
};

/// The most poses validate_plan() checks for collision in one plan (a limit on the
/// work a plan file can ask for).
inline constexpr std::uint64_t kMaxPlanChecks = 1'000'000;
/// The poses the collision check of `states` visits at `res` (saturating).
[[nodiscard]] std::uint64_t plan_check_count(const std::vector<Waypoint>& states,
                                             const CheckResolution& res);
/// InputError naming `source`'s states when the plan asks more than kMaxPlanChecks.
void check_plan_work(const PlanFile& plan, const CheckResolution& res, const std::string& source);

/// Checks the whole plan: every violation, and the margins. `corners` are the
/// tether's obstacle corners (required for miniUGV plans). InputError (source: the
/// plan) when a miniUGV plan has no entry point. Fills report.inputs' plan-side
/// fields only (states, robot, limits, geofence, resolution, parts).
[[nodiscard]] ValidationReport validate_plan(const PlanFile& plan, CollisionChecker& exact,
                                             const std::shared_ptr<const TetherCorners>& corners,
                                             const ValidationOptions& options);

/// Headings must be radians in [-pi, pi] (a small tolerance for rounding): InputError
/// naming `source` and the state otherwise, saying when the values look like degrees.
void check_yaw_is_radians(const PlanFile& plan, const std::string& source);

/// The check resolution the planners use for a robot (validation uses the same).
[[nodiscard]] CheckResolution default_resolution(PlanRobot robot);

/// What `ferret validate` takes besides the plan and the world.
struct ValidateRequest {
  /// The robot's URDF. nullopt: the URDF named by the plan (robot_model), else
  /// ferret's built-in shapes. Required for plans that do not say which robot they are.
  std::optional<std::filesystem::path> robot_urdf;
  bool builtin_shapes = false;  ///< check with the built-in shapes even if the plan names a URDF
  std::optional<std::filesystem::path> mission;  ///< motion limits, tether L and l_0
  std::optional<Aabb3> bounds;  ///< geofence / hidden space (default: plan, hidden space, world)
  std::optional<double>
      tether_budget_m;  ///< L - l_0 (default: the plan's tether section, else the mission's)
  std::optional<Eigen::Vector2d> p_WE;   ///< tether entry for plans without a tether section
  std::optional<UnknownPolicy> unknown;  ///< default: the plan's, else the robot's
  std::optional<double> floor_z_m;       ///< override of the floor found in the map
  std::function<bool()> cancelled;       ///< ValidationOptions::cancelled
  /// Where the collision map comes from (default: built for this request). A program
  /// that validates many plans against one world (the planner service) keeps the maps
  /// it built, by collision_map_options_key(); building one is most of a validation.
  std::function<std::shared_ptr<const CollisionMap>(const octomap::OcTree&,
                                                    const CollisionMapOptions&)>
      collision_map;
};

/// Loads the plan and the world and validates the one against the other, as
/// `ferret validate` does (docs/validate.md says how each input is chosen).
/// InputError for bad input (files, request, headings not in radians, a CSV plan
/// without a robot, a miniUGV plan without bounds or entry).
[[nodiscard]] ValidationReport validate_plan_file(const std::filesystem::path& plan,
                                                  const std::filesystem::path& world,
                                                  const ValidateRequest& request);

/// The same for a plan already in memory, against a world already loaded (a program
/// that plans and checks without files); `source` names the plan in errors.
[[nodiscard]] ValidationReport validate_plan(PlanFile plan, const PlanningWorld& world,
                                             const ValidateRequest& request,
                                             const std::string& source = "plan");

/// The report as JSON (docs/validate.md, docs/validate.schema.json), one document.
[[nodiscard]] std::string validation_report_to_json(const ValidationReport& report);

}  // namespace ferret
