#include "ferret/sim/exploration_run.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "ferret/mapping/frontier.hpp"
#include "ferret/planning/curiosity.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/planning/grid_path_planner.hpp"

namespace ferret {
namespace {

constexpr double kPositionTolerance_m = 0.1;
constexpr double kViewpointTolerance_m = 0.04;
constexpr double kHeadingTolerance_rad = 0.15;
constexpr double kLookahead_m = 0.3;
constexpr double kStuckTime_s = 4.0;
constexpr double kWideEscape_m = 4.0;
constexpr double kFullDecision_s = 1.0;

// Skid-steer follower of a waypoint path (pure pursuit with turn-in-place), with
// velocity, acceleration and yaw-rate limits. It only ever enters cells that G
// knows to be free: the robot does not drive into space its IR has not seen.
class PathFollower {
 public:
  explicit PathFollower(const RobotOptions& robot) : robot_(robot) {}

  void set_path(std::vector<Eigen::Vector2d> path, std::optional<double> heading_rad) {
    path_ = std::move(path);
    has_heading_ = heading_rad.has_value();
    heading_rad_ = heading_rad.value_or(0.0);
    // After a blocked step, stay precise on the new path too, starting from its first
    // waypoint (the centre of the robot's cell): re-planning every cycle must not
    // throw the robot back into the corner it was cutting.
    next_ = path_.size() > 1 && precise_ == 0 ? 1 : 0;
  }
  [[nodiscard]] bool has_path() const { return !path_.empty(); }
  void clear() { path_.clear(); }

  /// Advances the pose by dt; returns true once the goal (and heading) is reached.
  bool step(Pose2& pose, double& v_mps, const IrGrid& grid, double dt) {
    if (path_.empty()) {
      v_mps = 0.0;
      return false;
    }
    const Eigen::Vector2d p = pose.position();
    const Eigen::Vector2d goal = path_.back();
    const double to_goal = (goal - p).norm();
    double v_des = 0.0, w = 0.0;
    // A goal with a heading is a viewpoint chosen for its line of sight: stand on it.
    if (to_goal < (has_heading_ ? kViewpointTolerance_m : kPositionTolerance_m)) {
      v_mps = 0.0;
      if (!has_heading_) return true;
      const double e = wrap_angle_rad(heading_rad_ - pose.yaw_rad);
      if (std::abs(e) < kHeadingTolerance_rad) return true;
      w = std::clamp(4.0 * e, -robot_.max_yaw_rate_radps, robot_.max_yaw_rate_radps);
      pose.yaw_rad = wrap_angle_rad(pose.yaw_rad + w * dt);
      return false;
    }
    if (precise_ > 0) {
      // Recovery after a blocked step: waypoint by waypoint, exactly along the
      // segments (which cross only free cells), turning on the spot at each.
      while ((path_[next_] - p).norm() < 0.02 && next_ + 1 < path_.size()) {
        ++next_;
        --precise_;
      }
    } else {
      while (next_ + 1 < path_.size() && (path_[next_] - p).norm() < kLookahead_m) ++next_;
    }
    const Eigen::Vector2d target = path_[next_];
    const Eigen::Vector2d to = target - p;
    const double e = wrap_angle_rad(std::atan2(to.y(), to.x()) - pose.yaw_rad);
    w = std::clamp(4.0 * e, -robot_.max_yaw_rate_radps, robot_.max_yaw_rate_radps);
    if (std::abs(e) < (precise_ > 0 ? 0.03 : 0.6)) {
      v_des = robot_.max_velocity_mps * std::cos(e);
      v_des = std::min(
          v_des, std::sqrt(2.0 * robot_.max_acceleration_mps2 * to_goal));  // stop at the goal
      if (precise_ > 0) v_des = std::min(v_des, to.norm() / dt);            // land on the waypoint
    }
    const double dv = robot_.max_acceleration_mps2 * dt;
    double v = std::clamp(v_des, v_mps - 2 * dv, v_mps + dv);  // brake harder than accelerate
    v = std::max(v, 0.0);
    const double yaw = wrap_angle_rad(pose.yaw_rad + w * dt);
    Eigen::Vector2d next = p + v * dt * Eigen::Vector2d(std::cos(yaw), std::sin(yaw));
    const GridGeometry& g = grid.geometry();
    const Cell c = g.cell_at(next.x(), next.y());
    const bool same_cell =
        c == g.cell_at(p.x(), p.y());  // a noisy hit may have marked the robot's own cell
    if (!g.contains(c) || (grid.label(c) != GridLabel::kFree && !same_cell)) {
      // Not known free (a corner cut, or space the IR has not seen): stop, and go on
      // precisely from the centre of the current cell along the path's segments.
      v = 0.0;
      next = p;
      const Eigen::Vector2d centre = g.center(g.cell_at(p.x(), p.y()));
      if ((path_[next_] - centre).norm() > 1e-9)
        path_.insert(path_.begin() + static_cast<std::ptrdiff_t>(next_), centre);
      precise_ = 3;
    }
    if (precise_ > 0 && v > 0 && (target - next).norm() < 1e-3 + 0.5 * v * dt)
      next = target;  // land exactly
    pose = {next.x(), next.y(), yaw};
    v_mps = v;
    return false;
  }

 private:
  RobotOptions robot_;
  std::vector<Eigen::Vector2d> path_;
  int precise_ = 0;           ///< waypoints left to follow precisely after a blocked step
  bool has_heading_ = false;  // (not std::optional: GCC 12 warns falsely about it here)
  double heading_rad_ = 0.0;
  std::size_t next_ = 0;
};

}  // namespace

EpisodeResult run_exploration(const OccupancyMap2D& truth, const Pose2& start,
                              const Eigen::Vector2d& object_W, const ExplorationSettings& settings,
                              std::uint64_t seed) {
  if (!has_exploration_policy(settings.method))
    throw std::invalid_argument("unknown exploration method: " + settings.method);
  const GridGeometry& geo = truth.geometry;
  if (!truth.is_free(geo.cell_at(start.x_m, start.y_m)))
    throw std::invalid_argument("the start pose is not on a free cell of the map");

  SensorOptions sensors = settings.sensors;
  sensors.eta_m = settings.mission.object_search.eta_m;
  HiddenSpaceSim sim(truth, object_W, sensors, seed);

  IrGrid::Options grid_options;
  grid_options.clearance_m = settings.robot.clearance_m;
  auto grid = std::make_shared<IrGrid>(geo, grid_options);
  auto object_options =
      ObjectMap::Options::from(settings.mission.object_search, sensors.camera_range_m);
  object_options.object_radius_m = sensors.object_radius_m;
  auto objects = std::make_shared<ObjectMap>(geo, object_options);
  FrontierTracker tracker(geo);
  GridPathPlanner planner(geo);

  PolicyOptions policy_options = PolicyOptions::from(settings.mission, sensors.camera_range_m,
                                                     settings.robot.max_velocity_mps);
  policy_options.cdos_candidates_global = settings.cdos_candidates_global;
  policy_options.curiosity.closest_approach = settings.cdos_closest_approach;
  policy_options.seed = derive_seed(seed, {stable_hash("policy")});  // the OMPL frontier policies
  auto policy = make_exploration_policy(settings.method, policy_options);

  EpisodeResult result;
  Pose2 pose = start;
  double v_mps = 0.0;
  grid->mark_free_disk(pose.position(), settings.robot.clearance_m + geo.resolution_m);
  PathFollower follower(settings.robot);

  const double dt = 1.0 / sensors.ir_rate_hz;
  const int camera_every =
      std::max(1, static_cast<int>(std::lround(sensors.ir_rate_hz / sensors.camera_rate_hz)));
  const int decide_every =
      std::max(1, static_cast<int>(std::lround(settings.decision_period_s / dt)));
  const double escape_m =
      std::max(settings.robot.escape_radius_m, settings.robot.clearance_m + 2 * geo.resolution_m);

  std::optional<ExplorationGoal> goal;
  bool goal_is_revisit = false;
  int revisits = 0;
  bool decide_now = true;
  double last_full_decision = 0.0;
  Pose2 progress_pose = pose;
  double progress_time = 0.0;
  const auto max_steps = static_cast<long>(std::ceil(settings.time_limit_s / dt));

  auto finish = [&](const std::string& reason, double t) {
    result.end_reason = reason;
    result.time_s = t;
  };

  for (long step = 0;; ++step) {
    const double t = step * dt;
    if (settings.record) result.trajectory.push_back(pose);
    grid->integrate_scan(sim.ir_scan(pose));
    if (step % camera_every == 0) {
      objects->integrate_frame(sim.camera_frame(pose, t));
      if (const auto cell = objects->found_cell()) {
        result.found_W = geo.center(*cell);
        const bool right =
            (result.found_W - object_W).norm() <= sensors.object_radius_m + 2 * geo.resolution_m;
        result.found = right;
        finish(right ? "found" : "false_find", t);
        break;
      }
    }
    if (step >= max_steps) {
      finish("time_limit", t);
      break;
    }

    if (decide_now || step % decide_every == 0) {
      tracker.update(*grid);
    }
    // A decision cycle, unless the policy keeps its goal on the evidence of the maps
    // (then the path from the last full cycle is still followed; a full cycle runs at
    // least every kFullDecision_s to refresh it).
    if (decide_now || (step % decide_every == 0 &&
                       (!goal || t - last_full_decision >= kFullDecision_s ||
                        (!goal_is_revisit && !policy->keeps_goal(*objects, tracker))))) {
      decide_now = false;
      last_full_decision = t;
      const Cell robot_cell = geo.cell_at(pose.x_m, pose.y_m);
      planner.compute(*grid, robot_cell, GridPathPlanner::Traversal::kKnownFree, escape_m);
      const Pose2 X_WS = pose;  // sensors at the robot's origin, facing forward
      const FrontierSets sets =
          tracker.extract(planner.distances_m(), X_WS, sensors.ir_fov_rad, sensors.ir_range_m);
      const Eigen::Vector2d v_W =
          v_mps * Eigen::Vector2d(std::cos(pose.yaw_rad), std::sin(pose.yaw_rad));
      if (!(goal && goal_is_revisit)) {
        ExplorationState state{*grid,
                               *objects,
                               tracker,
                               sets,
                               planner,
                               pose,
                               v_W,
                               sensors.ir_fov_rad,
                               sensors.ir_range_m,
                               std::nullopt};
        if (policy->needs_oracle()) state.oracle_object_W = object_W;
        goal = policy->choose(state);
        goal_is_revisit = false;
        if (!goal && tracker.frontier_count() > 0) {
          // Nothing reachable: perhaps the robot is boxed in by the clearance of walls
          // it has just seen. Look again with the clearance waived further out.
          planner.compute(*grid, robot_cell, GridPathPlanner::Traversal::kKnownFree, kWideEscape_m);
          const FrontierSets wide =
              tracker.extract(planner.distances_m(), X_WS, sensors.ir_fov_rad, sensors.ir_range_m);
          ExplorationState again{*grid,
                                 *objects,
                                 tracker,
                                 wide,
                                 planner,
                                 pose,
                                 v_W,
                                 sensors.ir_fov_rad,
                                 sensors.ir_range_m,
                                 state.oracle_object_W};
          goal = policy->choose(again);
        }
        if (!goal) {
          // Exploration is over with the object unconfirmed: revisit the strongest evidence.
          const auto evidence = collect_evidence(*objects);
          if (!evidence.empty() && revisits < settings.max_revisits) {
            goal = viewing_goal(*grid, tracker, planner, strongest_evidence(evidence).p_W,
                                policy_options.view_distance_m);
            if (goal) {
              goal->reason = "revisit";
              goal_is_revisit = true;
              ++revisits;
            }
          }
        }
        if (!goal) {
          finish("explored", t);
          break;
        }
        ++result.decisions;
        auto path = goal->path_W.empty() ? planner.path_to(goal->cell) : goal->path_W;
        if (path.empty()) {  // cannot get there after all: never choose it again
          tracker.blacklist(goal->cell);
          policy->goal_done();
          goal.reset();
          decide_now = true;
        } else {
          follower.set_path(std::move(path), goal->heading_rad);
        }
        if (settings.record && goal)
          result.decision_log.push_back({t, pose, goal->p_W, goal->reason, goal->score,
                                         sets.global.size(), sets.visible.size(),
                                         objects->evidence_cells().size()});
      }
    }

    const Pose2 before = pose;
    const bool reached = follower.step(pose, v_mps, *grid, dt);
    result.path_m += (pose.position() - before.position()).norm();
    if (reached) {
      // A goal reached that is still frontier, or a viewpoint reached without finding
      // the object, would be chosen again and again.
      if (goal && (tracker.is_frontier(goal->cell) || goal->heading_rad))
        tracker.blacklist(goal->cell);
      policy->goal_done();
      goal.reset();
      goal_is_revisit = false;
      follower.clear();
      decide_now = true;
    }
    // Stuck (no headway for a while with a goal; turning on the spot does not count):
    // give the goal up.
    if ((pose.position() - progress_pose.position()).norm() > 0.05 || !goal) {
      progress_pose = pose;
      progress_time = t;
    } else if (t - progress_time > kStuckTime_s) {
      tracker.blacklist(goal->cell);
      policy->goal_done();
      goal.reset();
      goal_is_revisit = false;
      follower.clear();
      decide_now = true;
      progress_pose = pose;
      progress_time = t;
    }
  }

  if (settings.record) {
    tracker.update(*grid);
    for (const std::size_t idx : tracker.frontier_cells())
      result.frontier.push_back(geo.cell_of_index(idx));
    result.grid = grid;
    result.objects = objects;
  }
  return result;
}

}  // namespace ferret
