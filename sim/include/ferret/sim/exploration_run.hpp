#pragma once
// One object search in the simulated hidden space (the episode of the paper's
// experiment): the miniUGV starts at a pose, folds IR scans into G (20 Hz) and camera
// frames into O (10 Hz), re-decides its goal with an exploration policy (10 Hz, or at
// once when a goal is reached), drives the shortest known-free path with skid-steer
// limits, and stops when a cell of O passes lambda2 (or nothing is left to explore,
// or time runs out). docs/object_search.md describes the loop.

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
#include "ferret/sim/hidden_space_sim.hpp"
#include "ferret/urdf/mission_config.hpp"

namespace ferret {

struct RobotOptions {
  double max_velocity_mps = 2.0;
  double max_yaw_rate_radps = 2.0;
  double max_acceleration_mps2 = 2.0;
  double clearance_m = 0.15;  ///< paths keep this far from occupied cells of G
  /// Within this of the robot the clearance is waived, so that a robot that finds a
  /// wall (or a gap narrower than twice the clearance) around it can drive out.
  double escape_radius_m = 1.0;
};

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
};

struct DecisionRecord {
  double time_s = 0.0;
  Pose2 pose;
  Eigen::Vector2d goal_W = Eigen::Vector2d::Zero();
  std::string reason;
  double score = 0.0;
  std::size_t frontier_global = 0, frontier_visible = 0, evidence_cells = 0;
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
};

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
