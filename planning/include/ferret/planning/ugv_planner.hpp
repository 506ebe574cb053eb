#pragma once
// The tether-aware miniUGV planner: SE2 paths in a hidden space (the miniUGV turns
// in place and drives straight), collision-checked against the hidden-space OctoMap
// with unknown space occupied, and with the taut tether (taut_tether.hpp) tracked
// along every tree branch so that l_0 + taut length <= L holds at every state.
// Built on OMPL (TetheredRRT, tethered_rrt.hpp); this header keeps OMPL out.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/planning/collision_map.hpp"
#include "ferret/planning/motion_check.hpp"
#include "ferret/planning/plan_failure.hpp"
#include "ferret/planning/robot_shape.hpp"
#include "ferret/tether_model/taut_tether.hpp"

namespace ompl::base {
class SpaceInformation;
}

namespace ferret {

/// The hidden space the miniUGV plans in.
struct HiddenSpaceFrame {
  Eigen::Vector2d lo_m{0.0, 0.0};  ///< plan bounds (x, y)
  Eigen::Vector2d hi_m{12.0, 8.0};
  double floor_z_m = 0.0;          ///< the miniUGV's base frame G sits at this height
  Eigen::Vector2d p_WE{0.0, 4.0};  ///< tether entry point
};

struct UgvPlannerOptions {
  double range_m = 1.5;     ///< longest tree edge
  double goal_bias = 0.15;  ///< probability of sampling the goal
  double time_limit_s = 1.0;
  CheckResolution resolution;  ///< motion checks (same as `ferret validate`)
  int shortcut_rounds = 2;     ///< tether-aware shortcutting passes
  /// Re-check the final path with FCL alone instead of the checker (whose answers
  /// equal FCL's, 10-25x faster); `ferret validate` always uses FCL alone.
  bool final_check_fcl_only = false;
  std::uint64_t seed = 1;
  double max_velocity_mps = 2.0;  ///< for time stamps (MissionConfig::ugv_limits)
  double max_yaw_rate_radps = 2.0;
  double max_acceleration_mps2 = 2.0;  ///< for time stamps: every segment rest to rest
  /// The collision shape (e.g. from the URDF, planning_world.hpp's plan_robot_shape);
  /// empty: ugv_shape() of the geometry.
  std::optional<RobotShape> shape;
  /// Polled during the search: true stops it (a service's client went away, a drain).
  std::function<bool()> cancelled;
};

struct UgvPlanRequest {
  Pose2 start;
  Pose2 goal;
  /// The path driven since the entry (entry excluded, start included or not): replayed
  /// to give the tether its current wrap points. Empty: the tether lies straight from
  /// the entry to the start.
  std::vector<Eigen::Vector2d> driven;
  TetherParams tether;
};

struct UgvPlan {
  bool solved = false;
  std::string status;  ///< "solved", or why not
  PlanFailure failure = PlanFailure::kNone;
  std::vector<Waypoint> states;          ///< turn-drive-turn poses with times and tether lengths
  std::vector<WrapPoint> initial_wraps;  ///< the tether at the start
  std::vector<WrapPoint> final_wraps;    ///< the tether at the goal
  double planning_time_s = 0.0;
  std::size_t tree_size = 0;
};

class UgvPlanner {
 public:
  UgvPlanner(std::shared_ptr<const CollisionMap> map, const HiddenSpaceFrame& space,
             const UgvGeometry& ugv = {}, const UgvPlannerOptions& options = {});
  /// The same with the tether's corners already found in this map and space (they cost
  /// more than a short plan: a service computes them once per map).
  UgvPlanner(std::shared_ptr<const CollisionMap> map, const HiddenSpaceFrame& space,
             const UgvGeometry& ugv, const UgvPlannerOptions& options,
             std::shared_ptr<const TetherCorners> corners);
  ~UgvPlanner();

  [[nodiscard]] UgvPlan plan(const UgvPlanRequest& request);
  /// Plans back to `goal` along the tether: through the wrap points in reverse,
  /// offset from their corners, falling back to plan() when that is blocked.
  [[nodiscard]] UgvPlan plan_return(const UgvPlanRequest& request);

  /// The tether's obstacle corners (cells of the floor band blocked by the map).
  [[nodiscard]] const std::shared_ptr<const TetherCorners>& corners() const { return corners_; }
  [[nodiscard]] const HiddenSpaceFrame& space() const { return space_; }
  /// The miniUGV's pose at the floor as a plan state.
  [[nodiscard]] Waypoint waypoint(const Pose2& X_WG) const;
  [[nodiscard]] CollisionChecker& checker() { return *checker_; }
  [[nodiscard]] const UgvPlannerOptions& options() const { return options_; }

  /// The OMPL setting the planner searches: SE2 over the hidden space, this planner's
  /// collision checker as validity checker, the turn-drive-turn motion validator.
  /// (bench-plan runs OMPL's Benchmark on it.) The planner must outlive it.
  [[nodiscard]] std::shared_ptr<ompl::base::SpaceInformation> space_information();
  /// The tether of a request with the robot at its start.
  [[nodiscard]] TautTether tether_at_start(const UgvPlanRequest& request) const;

 private:
  UgvPlan finish(std::vector<Waypoint> nodes, const TautTether& tether0, double max_taut_m,
                 double t0_s);
  std::shared_ptr<const CollisionMap> map_;
  HiddenSpaceFrame space_;
  UgvGeometry ugv_;
  UgvPlannerOptions options_;
  std::unique_ptr<CollisionChecker> checker_;
  std::shared_ptr<const TetherCorners> corners_;
};

/// The floor band of a map as a tether obstacle grid: a cell blocks when any voxel
/// between the floor and the top of the miniUGV's body is occupied.
[[nodiscard]] std::shared_ptr<const TetherCorners> tether_corners_from_map(
    const CollisionMap& map, const HiddenSpaceFrame& space, const UgvGeometry& ugv);

/// Replays a path on a tether (positions only) and reports the first state whose
/// l_0 + taut length exceeds L, or -1. Fills each state's tether_length_m.
[[nodiscard]] int replay_tether(TautTether& tether, std::vector<Waypoint>& states,
                                double max_taut_m);

}  // namespace ferret
