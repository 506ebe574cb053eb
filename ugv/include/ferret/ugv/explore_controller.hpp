#pragma once
// The miniUGV's object search (the explore state of its mission, and the episode of
// the paper's experiment): fold IR scans into G and camera frames into O, re-decide
// the goal with an exploration policy (every decision period, or at once when a goal
// is reached or given up), and command the path follower. It sees only what the
// sensors report; the simulator's truth never reaches it (the oracle policy's object
// position is an explicit option an experiment sets). docs/object_search.md.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/pose.hpp"
#include "ferret/mapping/ir_grid.hpp"
#include "ferret/mapping/object_map.hpp"
#include "ferret/ugv/explore_options.hpp"
#include "ferret/ugv/path_follower.hpp"

namespace ferret {

class FrontierTracker;
class TautTether;
class GridPathPlanner;
class ExplorationPolicy;
struct ExplorationGoal;

struct DecisionRecord {
  double time_s = 0.0;
  Pose2 pose;
  Eigen::Vector2d goal_W = Eigen::Vector2d::Zero();
  std::string reason;
  double score = 0.0;
  std::size_t frontier_global = 0, frontier_visible = 0, evidence_cells = 0;
};

class ExploreController {
 public:
  /// @throws InputError for an unknown method or planner, or a method the planner does
  /// not serve (exploration_policy_for()).
  ExploreController(const GridGeometry& geometry, const Pose2& start, ExploreOptions options);
  ~ExploreController();
  ExploreController(const ExploreController&) = delete;
  ExploreController& operator=(const ExploreController&) = delete;

  /// Folds one IR scan into G.
  void observe_scan(const RangeScan& scan);
  /// The base did not move as told at `pose`, driving forwards: something the IR has not
  /// seen (or has seen in the wrong cell) holds the body. Marks the cells at the front
  /// of the body's disc occupied in G, so the follower and the planners go round them.
  /// Returns how many cells it marked (none for a point robot).
  int mark_bumped(const Pose2& pose);
  /// Folds one camera frame into O; returns the cell that passed lambda2, if one did.
  std::optional<Cell> observe_frame(const CameraFrame& frame);
  /// Whether a camera frame is due at this tick (every camera_rate of the IR rate).
  [[nodiscard]] bool frame_due(long tick) const { return tick % camera_every_ == 0; }

  struct Command {
    VelocityCommand velocity;
    bool explored = false;  ///< nothing left to explore or revisit: the search is over
  };
  /// Decides (when due) and returns the command for the next tick. `tick` counts from
  /// 0 at the start; the pose is the odometry's.
  Command decide(long tick, const Pose2& pose);

  [[nodiscard]] double tick_s() const { return dt_s_; }
  /// A top speed below the robot's own for the paths it follows (the line's, say).
  void set_speed_limit_mps(double v_mps) { follower_.set_speed_limit_mps(v_mps); }
  [[nodiscard]] const IrGrid& grid() const { return *grid_; }
  [[nodiscard]] const ObjectMap& objects() const { return *objects_; }
  [[nodiscard]] std::shared_ptr<const IrGrid> grid_ptr() const { return grid_; }
  [[nodiscard]] std::shared_ptr<const ObjectMap> objects_ptr() const { return objects_; }
  [[nodiscard]] int decisions() const { return decisions_; }
  /// True when the last decide() ran a decision cycle (frontiers, the path field, the
  /// policy's choice), false when it only followed the path of an earlier one.
  [[nodiscard]] bool cycle_ran() const { return cycle_ran_; }
  [[nodiscard]] const std::vector<DecisionRecord>& decision_log() const { return decision_log_; }
  /// The frontier cells of G now.
  [[nodiscard]] std::vector<Cell> frontier();
  /// Follows the robot with the tether model (decide() does it; a caller that drives
  /// the robot itself, as the mission's servo does, calls it every tick).
  void follow_tether(const Pose2& pose, double t_s);
  /// The tether budget, if there is one.
  [[nodiscard]] std::optional<double> tether_budget_m() const { return options_.tether_budget_m; }
  /// The taut tether's length now, as the obstacles in G wrap it, with their bodies
  /// behind the faces seen (0 without a tether budget): the best estimate, which the
  /// winch is told.
  [[nodiscard]] double tether_length_m() const;
  /// The taut tether's length with unknown space wrapping it too (but where the robot
  /// drove): an upper bound of the real line, which the reach check holds to the budget.
  [[nodiscard]] double reach_length_m() const;
  /// The tether's last fixed point (its last wrap point, or the entry) and the taut
  /// length from the entry to it: what the robot reports over the link so that the
  /// winch prices its motion between reports. None without a tether model.
  [[nodiscard]] std::optional<std::pair<Eigen::Vector2d, double>> tether_anchor() const;
  /// Goals refused because their tether would be too long.
  [[nodiscard]] int reach_rejections() const { return reach_rejections_; }
  /// Of those, the goals a policy chose and the controller then refused (the grid
  /// policies; the OMPL ones ask first and never choose such a goal).
  [[nodiscard]] int refused_choices() const { return refused_choices_; }
  /// The driven path backwards from the robot until the tether lies straight from the
  /// entry (no wrap points), or until it is no longer than `enough_m`, both by the bound
  /// of reach_length_m() (straight by G's obstacles alone, the real line can still wrap
  /// one the IR never saw). Empty when the tether is straight already (or there is no
  /// tether model).
  [[nodiscard]] std::vector<Eigen::Vector2d> retrace_path(double enough_m = 0.0) const;
  /// The way home along the tether as estimated (G's obstacles, their bodies): its wrap
  /// points from the robot's end back, each pushed `offset_m` off its corner (then the
  /// entry, not included). Empty when the tether is straight (or there is no tether
  /// model). (The bound's wrap points include corners of unknown patches, whose offsets
  /// often fall in a wall's clearance band, and returns along them stalled.)
  [[nodiscard]] std::vector<Eigen::Vector2d> way_home_along_tether(double offset_m) const;
  [[nodiscard]] const Eigen::Vector2d& entry_W() const { return entry_W_; }
  /// Times the robot retraced its path to unwind a tether wound round obstacles.
  [[nodiscard]] int unwinds() const { return unwinds_; }
  /// Whether the taut tether of the path driven so far, continued along `path_W`,
  /// stays within the budget (always, without one), by the bound of reach_length_m().
  [[nodiscard]] bool within_reach(const std::vector<Eigen::Vector2d>& path_W) const;

 private:
  void drop_goal(bool blacklist);
  /// Per cell of G: unknown space wide enough to hide an obstacle (the bound's).
  [[nodiscard]] std::vector<std::uint8_t> unknown_that_can_hide_obstacles() const;
  /// Marks the cells round a driven point: unknown there does not block the tether.
  void mark_swept(const Eigen::Vector2d& p_W);

  GridGeometry geo_;
  ExploreOptions options_;
  std::shared_ptr<IrGrid> grid_;
  std::shared_ptr<ObjectMap> objects_;
  std::unique_ptr<FrontierTracker> tracker_;
  std::unique_ptr<GridPathPlanner> planner_;
  std::unique_ptr<ExplorationPolicy> policy_;
  double view_distance_m_ = 0.95;
  PathFollower follower_;
  double dt_s_ = 0.05;
  int camera_every_ = 2, decide_every_ = 2;
  double escape_m_ = 1.0;

  std::unique_ptr<ExplorationGoal> goal_;
  bool goal_is_revisit_ = false;
  int revisits_ = 0;
  bool decide_now_ = true;
  double last_full_decision_s_ = 0.0;
  Pose2 progress_pose_;
  double progress_time_s_ = 0.0;
  int decisions_ = 0;
  bool cycle_ran_ = false;
  std::vector<DecisionRecord> decision_log_;
  // The tether (with a budget): the driven path (every 5 cm) replayed over the corners
  // of G's occupied cells when they are refreshed, followed tick by tick in between.
  Eigen::Vector2d entry_W_ = Eigen::Vector2d::Zero();
  bool left_entry_ = false;  ///< moved the object map's min_move_m from entry_W_ at some time
  std::vector<Eigen::Vector2d> driven_W_;
  std::vector<std::uint8_t> swept_;           ///< per cell of G: the robot drove over it
  std::unique_ptr<TautTether> tether_;        ///< the estimate (G's obstacles and their bodies)
  std::unique_ptr<TautTether> reach_tether_;  ///< the bound (and unknown space)
  double corners_refreshed_s_ = -1e9;
  int reach_rejections_ = 0;
  int refused_choices_ = 0;
  bool unwinding_ = false;  ///< retracing the driven path to unwind the tether
  int unwinds_ = 0;
};

}  // namespace ferret
