#pragma once
// One object search in the simulated hidden space (the episode of the paper's
// experiment): the miniUGV's explore controller (ugv/explore_controller.hpp) drives the
// simulated miniUGV (sim_ugv_base.hpp) from a start pose, IR at 20 Hz, camera at 10 Hz,
// until a cell of O passes lambda2 (or nothing is left to explore, or time runs out).
// The harness alone knows the object and judges the find. docs/object_search.md.

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/mapping/ir_grid.hpp"
#include "ferret/mapping/object_map.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/sim/hidden_space_sim.hpp"
#include "ferret/ugv/explore_controller.hpp"

namespace ferret {

struct ExplorationSettings {
  std::string method = "cdos";
  SensorOptions sensors;
  RobotOptions robot;
  MissionConfig mission;
  double time_limit_s = 300.0;
  double decision_period_s = 0.1;
  int max_revisits = 3;  ///< revisits of the strongest evidence once exploration ends
  bool cdos_candidates_global = false;  ///< cdos option: score F_g, not F_v
  bool cdos_closest_approach = false;   ///< cdos option: d_{t+1} at the closest approach
  bool record = false;                  ///< keep the trajectory, decisions and final maps
  /// Time each step that ran a decision cycle (EpisodeResult::decision_cycle_s): wall
  /// time, for benchmarks only; it changes nothing the search does.
  bool time_decision_cycles = false;
};

struct EpisodeResult {
  bool found = false;
  double time_s = 0.0;  ///< simulated time at the end (time to find when found)
  double path_m = 0.0;
  int decisions = 0;
  std::string end_reason;                             ///< found, explored, time_limit, false_find
  Eigen::Vector2d found_W = Eigen::Vector2d::Zero();  ///< the cell that passed lambda2
  // Filled when ExplorationSettings::record:
  std::vector<Pose2> trajectory;  ///< one pose per IR step
  std::vector<DecisionRecord> decision_log;
  std::shared_ptr<const IrGrid> grid;
  std::shared_ptr<const ObjectMap> objects;
  std::vector<Cell> frontier;  ///< the frontier cells of G at the end
  /// With ExplorationSettings::time_decision_cycles: the wall time (s) of each step that
  /// ran a decision cycle, its IR scan and camera frame folded into the maps included
  /// (what the miniUGV's computer does in that step).
  std::vector<double> decision_cycle_s;
};

/// The controller's view of the simulated sensors.
[[nodiscard]] UgvSensorGeometry sensor_geometry(const SensorOptions& sensors);
/// The explore controller's options for a run of `settings` with `seed`; the object's
/// position is kept for the oracle policy only.
[[nodiscard]] ExploreOptions explore_options(const ExplorationSettings& settings,
                                             std::uint64_t seed, const Eigen::Vector2d& object_W);

/// The checks every simulated episode makes of its inputs.
/// @throws std::invalid_argument for an unknown method or a start off the free space.
void check_episode(const OccupancyMap2D& truth, const Pose2& start, const std::string& method);

/// Runs one search. Deterministic for a given seed.
/// @throws std::invalid_argument for an unknown method or a start off the free space.
[[nodiscard]] EpisodeResult run_exploration(const OccupancyMap2D& truth, const Pose2& start,
                                            const Eigen::Vector2d& object_W,
                                            const ExplorationSettings& settings,
                                            std::uint64_t seed);

/// Writes G.png, O.png and G_O.png (the paper's map figure: G; O, the probability per
/// cell with a colour bar marking lambda1 and lambda2; G with O's evidence; each with
/// the frontiers, the driven path and the object) into `dir`. Each is titled with
/// `what` (e.g. "sparse.yaml, cdos, seed 1") and the outcome: found in 12.4 s, 18.2 m.
/// The three appear together or not at all (an OutputSet on `dir`).
/// @pre result was recorded (ExplorationSettings::record).
void write_exploration_images(const OccupancyMap2D& truth, const Eigen::Vector2d& object_W,
                              const EpisodeResult& result, const std::filesystem::path& dir,
                              const std::string& what = "");

}  // namespace ferret
