#pragma once
// The options of the miniUGV's object search (explore_controller.hpp is the controller
// that runs it): the method and planner, the sensors' geometry, the robot, the mission,
// the tether's budget. A simulation's settings hold these without the controller.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

#include "ferret/core/pose.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/ugv/path_follower.hpp"

namespace ferret {

/// The sensors' geometry as the controller needs it (the simulator's SensorOptions
/// and a robot's URDF both give it).
struct UgvSensorGeometry {
  double ir_fov_rad = deg_to_rad(30.0);  ///< beta
  double ir_range_m = 4.0;               ///< D_IR
  double ir_rate_hz = 20.0;              ///< the controller's tick
  double camera_range_m = 4.0;           ///< D_cam
  double camera_rate_hz = 10.0;
  double object_radius_m = 0.1;
  double camera_fov_rad = deg_to_rad(90.0);  ///< alpha
};

/// What a user tunes of the search (the mission YAML's `ugv.explore`,
/// ugv_mission_config.hpp): shared by ExploreOptions and a simulated episode's settings
/// (sim/exploration_settings.hpp), so that neither copies the other's fields.
struct ExploreTuning {
  double decision_period_s = 0.1;
  int max_revisits = 3;  ///< revisits of the strongest evidence once exploration ends
  bool cdos_candidates_global = false;  ///< cdos option: score F_g, not F_v
  bool cdos_closest_approach = false;   ///< cdos option: d_{t+1} at the closest approach
  /// With a tether budget (ExploreOptions::tether_budget_m), a goal whose taut tether
  /// would exceed the budget less this margin is never chosen (m).
  double tether_margin_m = 0.3;
  /// How far an obstacle reaches behind a face G has seen, into unknown space the robot
  /// has not driven over, for the tether's estimate (m). The IR sees an obstacle's face,
  /// never its body: wrapped as seen, a one-cell shell, a line round it falls short by
  /// about twice the body's depth. 0: only the cells seen (before 2026-12-07).
  double tether_obstacle_depth_m = 0.2;

  /// Sets the tuning alone (the rest of a struct that embeds it keeps its values).
  void set_tuning(const ExploreTuning& tuning) { static_cast<ExploreTuning&>(*this) = tuning; }
};

struct ExploreOptions : ExploreTuning {
  std::string method = "cdos";
  /// How goals are chosen and reached: the Dijkstra field over G, or OMPL (cdos and
  /// rapid run as cdos+ompl and rapid+ompl: PRM with the CDOS frontier sampler; other
  /// methods have none: an InputError). exploration_policy_for() decides;
  /// docs/planning.md compares the two. Parsed from text by parse_frontier_planner.
  FrontierPlanner planner = FrontierPlanner::kGrid;
  UgvSensorGeometry sensors;
  RobotOptions robot;
  MissionConfig mission;
  std::uint64_t seed = 0;  ///< for policies that draw random numbers
  /// Only for policies that ask (the oracle): the object's true position.
  std::optional<Eigen::Vector2d> oracle_object_W;
  bool record_decisions = false;
  /// The taut tether the robot may use on the floor, L - l_0 (m); none: no tether
  /// (the paper's experiment). With it, a goal whose taut tether (the tether of the
  /// path driven so far, then the path to the goal, wrapped round the corners of G's
  /// occupied cells and of the unknown ones the robot has not driven over: a bound of
  /// the real line) would exceed the budget less `tether_margin_m` is never chosen:
  /// the OMPL planner asks it of every goal it connects (goal validity), the grid
  /// planner's goal is checked after the policy chose it.
  std::optional<double> tether_budget_m;
};

}  // namespace ferret
