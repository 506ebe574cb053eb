#include "ferret/ugv/explore_controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ferret/core/grid_morphology.hpp"
#include "ferret/mapping/frontier.hpp"
#include "ferret/planning/curiosity.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/planning/grid_path_planner.hpp"
#include "ferret/tether_model/taut_tether.hpp"

namespace ferret {
namespace {

constexpr double kStuckTime_s = 4.0;
constexpr double kWideEscape_m = 4.0;
constexpr double kFullDecision_s = 1.0;
constexpr double kCornerRefresh_s = 2.0;
constexpr double kDrivenStep_m = 0.05;
/// Unknown space narrower than this cannot hide an obstacle the tether wraps (m).
constexpr double kHiddenObstacleWidth_m = 0.125;
constexpr int kMaxReachRejections = 32;  ///< per decision: then the search is over
constexpr std::uint8_t kReachMark = 2;   ///< blacklist kind of goals out of the tether's reach
constexpr int kMaxUnwinds = 3;

}  // namespace

ExploreController::ExploreController(const GridGeometry& geometry, const Pose2& start,
                                     ExploreOptions options)
    : geo_(geometry), options_(std::move(options)), follower_(options_.robot) {
  const std::string policy_name = exploration_policy_for(options_.method, options_.planner);
  if (!(options_.tether_obstacle_depth_m >= 0.0 && options_.tether_obstacle_depth_m <= 10.0))
    throw std::invalid_argument("ExploreOptions::tether_obstacle_depth_m: expected 0 to 10 m");
  const UgvSensorGeometry& s = options_.sensors;
  IrGrid::Options grid_options;
  grid_options.clearance_m = options_.robot.clearance_m;
  grid_ = std::make_shared<IrGrid>(geo_, grid_options);
  auto object_options = ObjectMap::Options::from(options_.mission.object_search, s.camera_range_m);
  object_options.object_radius_m = s.object_radius_m;
  objects_ = std::make_shared<ObjectMap>(geo_, object_options);
  tracker_ = std::make_unique<FrontierTracker>(geo_);
  planner_ = std::make_unique<GridPathPlanner>(geo_, options_.robot.body_radius_m);

  PolicyOptions policy_options =
      PolicyOptions::from(options_.mission, s.camera_range_m, options_.robot.max_velocity_mps);
  policy_options.cdos_candidates_global = options_.cdos_candidates_global;
  policy_options.curiosity.closest_approach = options_.cdos_closest_approach;
  policy_options.seed = options_.seed;
  policy_options.camera_fov_rad = s.camera_fov_rad;
  policy_options.max_yaw_rate_radps = options_.robot.max_yaw_rate_radps;
  view_distance_m_ = policy_options.view_distance_m;
  policy_ = make_exploration_policy(policy_name, policy_options);

  // The robot stands on free ground it cannot see with its forward sensors.
  grid_->mark_free_disk(start.position(), options_.robot.clearance_m + geo_.resolution_m);
  dt_s_ = 1.0 / s.ir_rate_hz;
  camera_every_ = std::max(1, static_cast<int>(std::lround(s.ir_rate_hz / s.camera_rate_hz)));
  decide_every_ = std::max(1, static_cast<int>(std::lround(options_.decision_period_s / dt_s_)));
  escape_m_ =
      std::max(options_.robot.escape_radius_m, options_.robot.clearance_m + 2 * geo_.resolution_m);
  progress_pose_ = start;
  entry_W_ = start.position();
  driven_W_.push_back(entry_W_);
  swept_.assign(static_cast<std::size_t>(geo_.width) * geo_.height, 0);
  mark_swept(entry_W_);
  if (options_.tether_budget_m) {
    tether_ = std::make_unique<TautTether>(TetherCorners::from_list({}), entry_W_);
    reach_tether_ = std::make_unique<TautTether>(*tether_);
  }
}

ExploreController::~ExploreController() = default;

void ExploreController::observe_scan(const RangeScan& scan) { grid_->integrate_scan(scan); }

int ExploreController::mark_bumped(const Pose2& pose) {
  const double r = options_.robot.body_radius_m;
  if (!(r > 0.0)) return 0;
  // The front rim: cells within a cell outside the disc, at most 60 degrees off the
  // heading (a body pressed at its front or front corner).
  const double res = geo_.resolution_m;
  const Eigen::Vector2d p = pose.position();
  const Eigen::Vector2d heading(std::cos(pose.yaw_rad), std::sin(pose.yaw_rad));
  const Cell c0 = geo_.cell_at(p.x(), p.y());
  const int n = static_cast<int>(std::ceil((r + res) / res)) + 1;
  int marked = 0;
  for (int dj = -n; dj <= n; ++dj)
    for (int di = -n; di <= n; ++di) {
      const Cell c{c0.i + di, c0.j + dj};
      if (!geo_.contains(c) || grid_->label(c) == GridLabel::kOccupied) continue;
      const Eigen::Vector2d d = geo_.center(c) - p;
      const double dist = d.norm();
      if (dist < r - 0.5 * res || dist > r + res || d.dot(heading) < 0.5 * dist) continue;
      grid_->set_probability(c, 1.0);  // clamped to the grid's most certain occupied
      ++marked;
    }
  return marked;
}

std::optional<Cell> ExploreController::observe_frame(const CameraFrame& frame) {
  objects_->integrate_frame(frame);
  return objects_->found_cell();
}

void ExploreController::follow_tether(const Pose2& pose, double t_s) {
  if (!tether_) return;
  const Eigen::Vector2d p = pose.position();
  if ((p - driven_W_.back()).norm() >= kDrivenStep_m) {
    driven_W_.push_back(p);
    mark_swept(p);
  }
  if (t_s - corners_refreshed_s_ >= kCornerRefresh_s) {
    // G has grown: replay the driven path over its corners now, so corners seen only
    // after the robot passed them still wrap the tether.
    corners_refreshed_s_ = t_s;
    const auto replay = [&](std::shared_ptr<const TetherCorners> corners) {
      auto t = std::make_unique<TautTether>(std::move(corners), entry_W_);
      for (const auto& q : driven_W_) t->move_to(q);
      t->move_to(p);
      return t;
    };
    // The estimate wraps the obstacles G has seen, and their bodies behind the faces it
    // saw (tether_obstacle_depth_m). The bound also wraps unknown space
    // wide enough to hide one: the real line can wrap an obstacle the IR never saw, so
    // the estimate can fall short of it, the bound hardly ever. Neither wraps a cell the
    // robot drove over (a later noisy hit there is no obstacle, and a driven path through
    // an obstacle would tangle the replay).
    const auto occupied = [this](std::size_t i) {
      return grid_->label_at(i) == GridLabel::kOccupied && !swept_[i];
    };
    const std::vector<std::uint8_t> hidden = unknown_that_can_hide_obstacles();
    // The estimate takes the obstacles' bodies behind their seen faces as far as
    // tether_obstacle_depth_m reaches into that unknown space.
    std::vector<std::uint8_t> seen(swept_.size());
    for (std::size_t i = 0; i < seen.size(); ++i) seen[i] = occupied(i);
    const std::vector<std::uint8_t> body =
        grow_within(seen, hidden, geo_.width, geo_.height,
                    options_.tether_obstacle_depth_m / geo_.resolution_m);
    tether_ = replay(TetherCorners::from_grid(geo_, [&](Cell c) {
      const std::size_t i = geo_.index(c);
      return seen[i] != 0 || body[i] != 0;
    }));
    reach_tether_ = replay(TetherCorners::from_grid(geo_, [&](Cell c) {
      const std::size_t i = geo_.index(c);
      return occupied(i) || hidden[i] != 0;
    }));
  } else {
    tether_->move_to(p);
    reach_tether_->move_to(p);
  }
}

std::vector<std::uint8_t> ExploreController::unknown_that_can_hide_obstacles() const {
  // Unknown cells the robot has not driven over, opened by a square of
  // kHiddenObstacleWidth_m: the specks and thin strips between IR rays cannot hide an
  // obstacle the tether could wrap, and wrapping them made the bound wind round holes in
  // free space (tens of metres after an unwind).
  std::vector<std::uint8_t> unknown(swept_.size());
  for (std::size_t i = 0; i < unknown.size(); ++i)
    unknown[i] = grid_->label_at(i) == GridLabel::kUnknown && !swept_[i];
  const int r =
      std::max(1, static_cast<int>(std::lround(0.5 * kHiddenObstacleWidth_m / geo_.resolution_m)));
  return open_square(unknown, geo_.width, geo_.height, r);
}

void ExploreController::mark_swept(const Eigen::Vector2d& p_W) {
  // The driven points lie kDrivenStep_m apart: a disc of that radius covers the path.
  const double r = std::max(kDrivenStep_m, 1.5 * geo_.resolution_m);
  const Cell lo = geo_.cell_at(p_W.x() - r, p_W.y() - r),
             hi = geo_.cell_at(p_W.x() + r, p_W.y() + r);
  for (int j = std::max(0, lo.j); j <= std::min(geo_.height - 1, hi.j); ++j)
    for (int i = std::max(0, lo.i); i <= std::min(geo_.width - 1, hi.i); ++i)
      if ((geo_.center({i, j}) - p_W).norm() <= r) swept_[geo_.index({i, j})] = 1;
}

double ExploreController::tether_length_m() const { return tether_ ? tether_->length_m() : 0.0; }
double ExploreController::reach_length_m() const {
  return reach_tether_ ? reach_tether_->length_m() : 0.0;
}

std::optional<std::pair<Eigen::Vector2d, double>> ExploreController::tether_anchor() const {
  if (!tether_) return std::nullopt;
  const Eigen::Vector2d a = tether_->anchor();
  return std::pair{a, tether_->length_m() - (tether_->robot() - a).norm()};
}

bool ExploreController::within_reach(const std::vector<Eigen::Vector2d>& path_W) const {
  if (!reach_tether_) return true;
  TautTether t = *reach_tether_;
  for (const auto& p : path_W) t.move_to(p);
  return t.length_m() + options_.tether_margin_m <= *options_.tether_budget_m;
}

std::vector<Eigen::Vector2d> ExploreController::retrace_path(double enough_m) const {
  std::vector<Eigen::Vector2d> path;
  if (!reach_tether_ || reach_tether_->wrap_points().empty()) return path;
  TautTether t = *reach_tether_;
  for (std::size_t k = driven_W_.size() - 1;; --k) {
    path.push_back(driven_W_[k]);
    t.move_to(driven_W_[k]);
    if (k == 0 || t.wrap_points().empty() || t.length_m() <= enough_m) break;
  }
  return path;
}

std::vector<Eigen::Vector2d> ExploreController::way_home_along_tether(double offset_m) const {
  if (!tether_) return {};
  return way_back_along_tether(*tether_, offset_m);
}

void ExploreController::drop_goal(bool blacklist) {
  if (unwinding_) {
    // Unwound (or given up on it): the goals the wound tether could not reach may be
    // reachable now.
    unwinding_ = false;
    ++unwinds_;
    blacklist = false;
    tracker_->clear_blacklist(kReachMark);
  }
  if (blacklist && goal_) tracker_->blacklist(goal_->cell);
  policy_->goal_done();
  goal_.reset();
  goal_is_revisit_ = false;
  follower_.clear();
  decide_now_ = true;
}

ExploreController::Command ExploreController::decide(long tick, const Pose2& pose) {
  const double t = static_cast<double>(tick) * dt_s_;
  follow_tether(pose, t);
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

  if ((pose.position() - entry_W_).norm() >= objects_->options().min_move_m) left_entry_ = true;
  const bool periodic = tick % decide_every_ == 0;
  if (decide_now_ || periodic) tracker_->update(*grid_);
  cycle_ran_ = false;
  // A decision cycle, unless the policy keeps its goal on the evidence of the maps
  // (then the path from the last full cycle is still followed; a full cycle runs at
  // least every kFullDecision_s to refresh it).
  if (decide_now_ ||
      (periodic && (!goal_ || t - last_full_decision_s_ >= kFullDecision_s ||
                    (!goal_is_revisit_ && !policy_->keeps_goal(*objects_, *tracker_))))) {
    decide_now_ = false;
    cycle_ran_ = true;
    last_full_decision_s_ = t;
    const Cell robot_cell = geo_.cell_at(pose.x_m, pose.y_m);
    planner_->compute(*grid_, robot_cell, GridPathPlanner::Traversal::kKnownFree, escape_m_);
    const Pose2 X_WS = pose;  // sensors at the robot's origin, facing forward
    const UgvSensorGeometry& s = options_.sensors;
    // The cycle's frontier sets, extracted when first asked for: which frontier cells
    // are reachable needs the whole path field, and a policy keeping its goal does not
    // ask. They are taken before anything of this cycle blacklists a cell, or the field
    // is computed again, so they are what an extraction here would give.
    FrontierSets sets;
    bool sets_ready = false;
    const auto fill_sets = [&] {
      if (sets_ready) return;
      sets = tracker_->extract(planner_->distances_m(), X_WS, s.ir_fov_rad, s.ir_range_m);
      sets_ready = true;
    };
    const double v_mps = follower_.speed_mps();
    const Eigen::Vector2d v_W =
        v_mps * Eigen::Vector2d(std::cos(pose.yaw_rad), std::sin(pose.yaw_rad));
    if (!(goal_ && goal_is_revisit_)) {
      int rejected_now = 0;
      std::optional<Eigen::Vector2d> oracle;
      if (policy_->needs_oracle()) oracle = options_.oracle_object_W;
      // A goal whose tether would be too long is never chosen again: the OMPL policies
      // ask before they choose (goal validity), the others are checked after.
      const auto reach = [&](Cell cell, const std::vector<Eigen::Vector2d>& path) {
        fill_sets();  // before this cycle's first blacklisting
        if (within_reach(path)) return true;
        ++reach_rejections_;
        ++rejected_now;
        tracker_->blacklist(cell, kReachMark);
        return false;
      };
      // The policy's choice, unless its tether would be too long: then the policy
      // chooses among the rest.
      // `first` (when set) fills `sets` on demand; after a refusal the sets are taken
      // again, with the refused goal blacklisted.
      const auto choose =
          [&](const std::function<void()>& first) -> std::optional<ExplorationGoal> {
        FrontierSets current;
        if (!first)
          current = tracker_->extract(planner_->distances_m(), X_WS, s.ir_fov_rad, s.ir_range_m);
        for (int k = 0; k < kMaxReachRejections; ++k) {
          ExplorationState state{
              *grid_,       *objects_, *tracker_, k == 0 && first ? sets : current,
              *planner_,    pose,      v_W,       s.ir_fov_rad,
              s.ir_range_m, oracle};
          if (tether_) state.within_reach = reach;
          if (k == 0) state.fill_frontiers = first;
          state.at_entry = !left_entry_;
          auto g = policy_->choose(state);
          if (!g || !tether_) return g;
          if (reach(g->cell, g->path_W.empty() ? planner_->path_to(g->cell) : g->path_W)) return g;
          ++refused_choices_;
          policy_->goal_done();
          current = tracker_->extract(planner_->distances_m(), X_WS, s.ir_fov_rad, s.ir_range_m);
        }
        return std::nullopt;
      };
      std::optional<ExplorationGoal> goal = choose(fill_sets);
      goal_is_revisit_ = false;
      if (!goal && tracker_->frontier_count() > 0) {
        // Nothing reachable: perhaps the robot is boxed in by the clearance of walls it
        // has just seen. Look again with the clearance waived further out.
        fill_sets();  // the cycle's sets are the first field's
        planner_->compute(*grid_, robot_cell, GridPathPlanner::Traversal::kKnownFree,
                          kWideEscape_m);
        goal = choose({});
      }
      if (!goal && rejected_now > 0 && unwinds_ < kMaxUnwinds) {
        // Goals are left, but the tether is wound round obstacles too far to reach them:
        // retrace the driven path (which unwinds it), then search on.
        auto path = retrace_path(0.5 * *options_.tether_budget_m);
        if (path.size() > 1) {
          goal = ExplorationGoal{geo_.cell_at(path.back().x(), path.back().y()),
                                 path.back(),
                                 std::nullopt,
                                 std::move(path),
                                 0.0,
                                 GoalRule::kUnwind};
          goal_is_revisit_ = true;  // follow it to the end, no re-decision on the way
          unwinding_ = true;
        }
      }
      if (!goal) {
        // Exploration is over with the object unconfirmed: revisit the strongest evidence.
        const auto evidence = collect_evidence(*objects_);
        if (!evidence.empty() && revisits_ < options_.max_revisits) {
          goal = viewing_goal(*grid_, *tracker_, *planner_, strongest_evidence(evidence).p_W,
                              view_distance_m_);
          if (goal &&
              !within_reach(goal->path_W.empty() ? planner_->path_to(goal->cell) : goal->path_W)) {
            ++reach_rejections_;
            goal.reset();
          }
          if (goal) {
            goal->reason = {GoalRule::kRevisit};
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
        if (options_.record_decisions) {
          fill_sets();
          decision_log_.push_back({t, pose, goal_->p_W, to_string(goal_->reason), goal_->score,
                                   sets.global.size(), sets.visible.size(),
                                   objects_->evidence_cells().size()});
        }
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
