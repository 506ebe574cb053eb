#include "ferret/ugv/explore_controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ferret/mapping/frontier.hpp"
#include "ferret/planning/curiosity.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/planning/grid_path_planner.hpp"

namespace ferret {
namespace {

constexpr double kStuckTime_s = 4.0;
constexpr double kWideEscape_m = 4.0;
constexpr double kFullDecision_s = 1.0;

}  // namespace

ExploreController::ExploreController(const GridGeometry& geometry, const Pose2& start,
                                     ExploreOptions options)
    : geo_(geometry), options_(std::move(options)), follower_(options_.robot) {
  if (!has_exploration_policy(options_.method))
    throw std::invalid_argument("unknown exploration method: " + options_.method);
  const UgvSensorGeometry& s = options_.sensors;
  IrGrid::Options grid_options;
  grid_options.clearance_m = options_.robot.clearance_m;
  grid_ = std::make_shared<IrGrid>(geo_, grid_options);
  auto object_options = ObjectMap::Options::from(options_.mission.object_search, s.camera_range_m);
  object_options.object_radius_m = s.object_radius_m;
  objects_ = std::make_shared<ObjectMap>(geo_, object_options);
  tracker_ = std::make_unique<FrontierTracker>(geo_);
  planner_ = std::make_unique<GridPathPlanner>(geo_);

  PolicyOptions policy_options =
      PolicyOptions::from(options_.mission, s.camera_range_m, options_.robot.max_velocity_mps);
  policy_options.cdos_candidates_global = options_.cdos_candidates_global;
  policy_options.curiosity.closest_approach = options_.cdos_closest_approach;
  policy_options.seed = options_.seed;
  view_distance_m_ = policy_options.view_distance_m;
  policy_ = make_exploration_policy(options_.method, policy_options);

  // The robot stands on free ground it cannot see with its forward sensors.
  grid_->mark_free_disk(start.position(), options_.robot.clearance_m + geo_.resolution_m);
  dt_s_ = 1.0 / s.ir_rate_hz;
  camera_every_ = std::max(1, static_cast<int>(std::lround(s.ir_rate_hz / s.camera_rate_hz)));
  decide_every_ = std::max(1, static_cast<int>(std::lround(options_.decision_period_s / dt_s_)));
  escape_m_ = std::max(options_.robot.escape_radius_m,
                       options_.robot.clearance_m + 2 * geo_.resolution_m);
  progress_pose_ = start;
}

ExploreController::~ExploreController() = default;

void ExploreController::observe_scan(const RangeScan& scan) { grid_->integrate_scan(scan); }

std::optional<Cell> ExploreController::observe_frame(const CameraFrame& frame) {
  objects_->integrate_frame(frame);
  return objects_->found_cell();
}

void ExploreController::drop_goal(bool blacklist) {
  if (blacklist && goal_) tracker_->blacklist(goal_->cell);
  policy_->goal_done();
  goal_.reset();
  goal_is_revisit_ = false;
  follower_.clear();
  decide_now_ = true;
}

ExploreController::Command ExploreController::decide(long tick, const Pose2& pose) {
  const double t = static_cast<double>(tick) * dt_s_;
  // Stuck (no headway with a goal over the last kStuckTime_s; turning on the spot does
  // not count): give the goal up. Judged on the pose the last command led to.
  if (tick > 0) {
    const double t_prev = t - dt_s_;
    if ((pose.position() - progress_pose_.position()).norm() > 0.05 || !goal_) {
      progress_pose_ = pose;
      progress_time_s_ = t_prev;
    } else if (t_prev - progress_time_s_ > kStuckTime_s) {
      drop_goal(true);
      progress_pose_ = pose;
      progress_time_s_ = t_prev;
    }
  }

  const bool periodic = tick % decide_every_ == 0;
  if (decide_now_ || periodic) tracker_->update(*grid_);
  // A decision cycle, unless the policy keeps its goal on the evidence of the maps
  // (then the path from the last full cycle is still followed; a full cycle runs at
  // least every kFullDecision_s to refresh it).
  if (decide_now_ ||
      (periodic && (!goal_ || t - last_full_decision_s_ >= kFullDecision_s ||
                    (!goal_is_revisit_ && !policy_->keeps_goal(*objects_, *tracker_))))) {
    decide_now_ = false;
    last_full_decision_s_ = t;
    const Cell robot_cell = geo_.cell_at(pose.x_m, pose.y_m);
    planner_->compute(*grid_, robot_cell, GridPathPlanner::Traversal::kKnownFree, escape_m_);
    const Pose2 X_WS = pose;  // sensors at the robot's origin, facing forward
    const UgvSensorGeometry& s = options_.sensors;
    const FrontierSets sets =
        tracker_->extract(planner_->distances_m(), X_WS, s.ir_fov_rad, s.ir_range_m);
    const double v_mps = follower_.speed_mps();
    const Eigen::Vector2d v_W =
        v_mps * Eigen::Vector2d(std::cos(pose.yaw_rad), std::sin(pose.yaw_rad));
    if (!(goal_ && goal_is_revisit_)) {
      ExplorationState state{*grid_,      *objects_,     *tracker_,
                             sets,        *planner_,     pose,
                             v_W,         s.ir_fov_rad,  s.ir_range_m,
                             std::nullopt};
      if (policy_->needs_oracle()) state.oracle_object_W = options_.oracle_object_W;
      std::optional<ExplorationGoal> goal = policy_->choose(state);
      goal_is_revisit_ = false;
      if (!goal && tracker_->frontier_count() > 0) {
        // Nothing reachable: perhaps the robot is boxed in by the clearance of walls it
        // has just seen. Look again with the clearance waived further out.
        planner_->compute(*grid_, robot_cell, GridPathPlanner::Traversal::kKnownFree,
                          kWideEscape_m);
        const FrontierSets wide =
            tracker_->extract(planner_->distances_m(), X_WS, s.ir_fov_rad, s.ir_range_m);
        ExplorationState again{*grid_,      *objects_,    *tracker_,
                               wide,        *planner_,    pose,
                               v_W,         s.ir_fov_rad, s.ir_range_m,
                               state.oracle_object_W};
        goal = policy_->choose(again);
      }
      if (!goal) {
        // Exploration is over with the object unconfirmed: revisit the strongest evidence.
        const auto evidence = collect_evidence(*objects_);
        if (!evidence.empty() && revisits_ < options_.max_revisits) {
          goal = viewing_goal(*grid_, *tracker_, *planner_, strongest_evidence(evidence).p_W,
                              view_distance_m_);
          if (goal) {
            goal->reason = "revisit";
            goal_is_revisit_ = true;
            ++revisits_;
          }
        }
      }
      if (!goal) {
        goal_.reset();
        follower_.clear();
        return {{}, true};
      }
      ++decisions_;
      goal_ = std::make_unique<ExplorationGoal>(std::move(*goal));
      auto path = goal_->path_W.empty() ? planner_->path_to(goal_->cell) : goal_->path_W;
      if (path.empty()) {  // cannot get there after all: never choose it again
        tracker_->blacklist(goal_->cell);
        policy_->goal_done();
        goal_.reset();
        decide_now_ = true;  // (the follower keeps its last path until then)
      } else {
        follower_.set_path(std::move(path), goal_->heading_rad);
        if (options_.record_decisions)
          decision_log_.push_back({t, pose, goal_->p_W, goal_->reason, goal_->score,
                                   sets.global.size(), sets.visible.size(),
                                   objects_->evidence_cells().size()});
      }
    }
  }

  bool reached = false;
  const VelocityCommand command = follower_.step(pose, *grid_, dt_s_, reached);
  if (reached) {
    // A goal reached that is still frontier, or a viewpoint reached without finding the
    // object, would be chosen again and again.
    drop_goal(goal_ && (tracker_->is_frontier(goal_->cell) || goal_->heading_rad));
  }
  return {command, false};
}

std::vector<Cell> ExploreController::frontier() {
  tracker_->update(*grid_);
  std::vector<Cell> cells;
  for (const std::size_t idx : tracker_->frontier_cells()) cells.push_back(geo_.cell_of_index(idx));
  return cells;
}

}  // namespace ferret
