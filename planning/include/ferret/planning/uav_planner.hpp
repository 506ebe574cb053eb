#pragma once
// The UAV approach planner: OMPL in position + yaw (R^3 x SO2) from the current pose
// to a hover pose (over a landing point near a hidden-space opening), inside a
// geofence and an altitude band, collision-checked with FCL against the world
// OctoMap for the UAV's shape, or for the UAV with the miniUGV hanging on its
// tether (the transport leg). The path is simplified, then re-validated pose by
// pose with FCL alone at the resolution `ferret validate` uses.

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ferret/planning/collision_map.hpp"
#include "ferret/planning/motion_check.hpp"
#include "ferret/planning/plan_failure.hpp"
#include "ferret/planning/robot_shape.hpp"

namespace ompl::base {
class SpaceInformation;
class State;
}  // namespace ompl::base

namespace ferret {

struct UavPlannerOptions {
  Aabb3 geofence{{-30.0, -30.0, 0.5}, {30.0, 30.0, 8.0}};  ///< x, y fence; z is the altitude band
  std::string planner = "rrtconnect";                      ///< see ompl_planner_names()
  double time_limit_s = 1.0;
  int simplify_rounds =
      5;  ///< rounds of OMPL shortcut/reduce/collapse (stops early when none helps)
  CheckResolution resolution{0.05, 0.1};
  double range_m = 0.0;  ///< planner range; 0 = the planner's default
  /// Re-check the final path with FCL alone instead of the checker (whose answers
  /// equal FCL's, 10-25x faster); `ferret validate` always uses FCL alone.
  bool final_check_fcl_only = false;
  std::uint64_t seed = 1;         ///< seeds OMPL once per process (seed_ompl_once)
  double max_velocity_mps = 5.0;  ///< for time stamps (MissionConfig::uav_limits)
  double max_yaw_rate_radps = 1.0;
  double max_acceleration_mps2 = 2.0;  ///< for time stamps: every segment rest to rest
  /// Polled during the search: true stops it (a service's client went away, a drain).
  std::function<bool()> cancelled;
};

struct UavPlan {
  bool solved = false;
  std::string status;
  PlanFailure failure = PlanFailure::kNone;
  std::vector<Waypoint> states;
  double planning_time_s = 0.0;
};

class UavPlanner {
 public:
  UavPlanner(std::shared_ptr<const CollisionMap> map, RobotShape shape,
             const UavPlannerOptions& options = {});
  ~UavPlanner();
  [[nodiscard]] UavPlan plan(const Waypoint& start, const Waypoint& goal);
  [[nodiscard]] CollisionChecker& checker() { return *checker_; }
  [[nodiscard]] const UavPlannerOptions& options() const { return options_; }

  /// The OMPL setting the planner searches: R^3 x SO2 inside the geofence, this
  /// planner's collision checker, straight-line motions checked at the validation
  /// resolution (bench-plan runs OMPL's Benchmark on it). The planner must outlive it.
  [[nodiscard]] std::shared_ptr<ompl::base::SpaceInformation> space_information();
  /// Writes a waypoint into a state of space_information()'s space (yaw normalised).
  void to_ompl_state(const Waypoint& w, ompl::base::State* state) const;

 private:
  std::shared_ptr<const CollisionMap> map_;
  UavPlannerOptions options_;
  std::unique_ptr<CollisionChecker> checker_;
};

}  // namespace ferret
