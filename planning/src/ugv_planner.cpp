#include "ferret/planning/ugv_planner.hpp"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/base/terminationconditions/IterationTerminationCondition.h>
#include <ompl/geometric/PathGeometric.h>

#include <chrono>
#include <cmath>

#include "ferret/planning/collision_checker.hpp"
#include "ferret/planning/tethered_rrt.hpp"
#include "ompl_termination.hpp"

namespace ob = ompl::base;

namespace ferret {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool in_plane_bounds(const HiddenSpaceFrame& s, double x, double y) {
  return x >= s.lo_m.x() && x <= s.hi_m.x() && y >= s.lo_m.y() && y <= s.hi_m.y();
}

// The miniUGV's motion between two SE2 states, checked pose by pose (OMPL 1.5's
// discrete validator would interpolate in SE2 and, for curved spaces, under-count
// segments; this one checks exactly the turn-drive-turn motion that is executed).
class TurnDriveTurnValidator : public ob::MotionValidator {
 public:
  TurnDriveTurnValidator(const ob::SpaceInformationPtr& si, UgvPlanner& planner,
                         CheckResolution res)
      : ob::MotionValidator(si), planner_(planner), res_(res) {}

  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    Waypoint a = to_waypoint(s1);
    const Waypoint b = to_waypoint(s2);
    if (!in_plane_bounds(planner_.space(), b.x_m, b.y_m)) {
      ++invalid_;
      return false;
    }
    for (const Waypoint& next : turn_drive_turn(a, b)) {
      if (first_collision(planner_.checker(), a, next, res_)) {
        ++invalid_;
        return false;
      }
      a = next;
    }
    ++valid_;
    return true;
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& last) const override {
    if (checkMotion(s1, s2)) return true;
    // Callers that want the last valid state get the start (conservative).
    if (last.first) si_->copyState(last.first, s1);
    last.second = 0.0;
    return false;
  }

 private:
  Waypoint to_waypoint(const ob::State* s) const {
    const auto* se2 = s->as<ob::SE2StateSpace::StateType>();
    return planner_.waypoint({se2->getX(), se2->getY(), se2->getYaw()});
  }
  UgvPlanner& planner_;
  CheckResolution res_;
};

}  // namespace

std::shared_ptr<const TetherCorners> tether_corners_from_map(const CollisionMap& map,
                                                             const HiddenSpaceFrame& space,
                                                             const UgvGeometry& ugv) {
  const double res = map.resolution_m();
  GridGeometry g;
  g.resolution_m = res;
  g.origin_x_m = std::floor(space.lo_m.x() / res) * res;
  g.origin_y_m = std::floor(space.lo_m.y() / res) * res;
  g.width = static_cast<int>(std::ceil((space.hi_m.x() - g.origin_x_m) / res));
  g.height = static_cast<int>(std::ceil((space.hi_m.y() - g.origin_y_m) / res));
  const double top = space.floor_z_m + ugv.ground_clearance_m + ugv.body_size_m.z();
  return TetherCorners::from_grid(g, [&](Cell c) {
    const Eigen::Vector2d p = g.center(c);
    for (double z = space.floor_z_m + 0.5 * res; z - 0.5 * res < top; z += res)
      if (map.is_occupied({p.x(), p.y(), z})) return true;
    return false;
  });
}

int replay_tether(TautTether& tether, std::vector<Waypoint>& states, double max_taut_m) {
  int first_bad = -1;
  for (std::size_t k = 0; k < states.size(); ++k) {
    tether.move_to({states[k].x_m, states[k].y_m});
    states[k].tether_length_m = tether.length_m();
    if (first_bad < 0 && tether.length_m() > max_taut_m) first_bad = static_cast<int>(k);
  }
  return first_bad;
}

UgvPlanner::UgvPlanner(std::shared_ptr<const CollisionMap> map, const HiddenSpaceFrame& space,
                       const UgvGeometry& ugv, const UgvPlannerOptions& options)
    : map_(std::move(map)), space_(space), ugv_(ugv), options_(options) {
  checker_ =
      std::make_unique<CollisionChecker>(map_, options_.shape ? *options_.shape : ugv_shape(ugv_));
  corners_ = tether_corners_from_map(*map_, space_, ugv_);
}

UgvPlanner::UgvPlanner(std::shared_ptr<const CollisionMap> map, const HiddenSpaceFrame& space,
                       const UgvGeometry& ugv, const UgvPlannerOptions& options,
                       std::shared_ptr<const TetherCorners> corners)
    : map_(std::move(map)),
      space_(space),
      ugv_(ugv),
      options_(options),
      corners_(std::move(corners)) {
  checker_ =
      std::make_unique<CollisionChecker>(map_, options_.shape ? *options_.shape : ugv_shape(ugv_));
  if (!corners_) corners_ = tether_corners_from_map(*map_, space_, ugv_);
}

UgvPlanner::~UgvPlanner() = default;

Waypoint UgvPlanner::waypoint(const Pose2& X_WG) const {
  Waypoint w;
  w.x_m = X_WG.x_m;
  w.y_m = X_WG.y_m;
  w.z_m = space_.floor_z_m;
  w.yaw_rad = wrap_angle_rad(X_WG.yaw_rad);
  return w;
}

std::shared_ptr<ob::SpaceInformation> UgvPlanner::space_information() {
  auto space = std::make_shared<ob::SE2StateSpace>();
  ob::RealVectorBounds bounds(2);
  bounds.setLow(0, space_.lo_m.x());
  bounds.setHigh(0, space_.hi_m.x());
  bounds.setLow(1, space_.lo_m.y());
  bounds.setHigh(1, space_.hi_m.y());
  space->setBounds(bounds);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([this](const ob::State* s) {
    const auto* se2 = s->as<ob::SE2StateSpace::StateType>();
    return in_plane_bounds(space_, se2->getX(), se2->getY()) &&
           !checker_->in_collision(waypoint({se2->getX(), se2->getY(), se2->getYaw()}).pose());
  });
  si->setMotionValidator(std::make_shared<TurnDriveTurnValidator>(si, *this, options_.resolution));
  si->setup();
  return si;
}

TautTether UgvPlanner::tether_at_start(const UgvPlanRequest& request) const {
  TautTether tether(corners_, space_.p_WE);
  for (const Eigen::Vector2d& p : request.driven) tether.move_to(p);
  tether.move_to(request.start.position());
  return tether;
}

UgvPlan UgvPlanner::plan(const UgvPlanRequest& request) {
  const auto t0 = std::chrono::steady_clock::now();
  UgvPlan out;
  const double max_taut = request.tether.total_length_m - request.tether.entry_offset_m;
  TautTether tether = tether_at_start(request);
  out.initial_wraps = tether.wrap_points();
  auto fail = [&](std::string why, PlanFailure failure) {
    out.status = std::move(why);
    out.failure = failure;
    out.planning_time_s = seconds_since(t0);
    return out;
  };
  if (tether.length_m() > max_taut)
    return fail("the tether at the start already exceeds L - l_0", PlanFailure::kTetherTooShort);
  const Waypoint start = waypoint(request.start), goal = waypoint(request.goal);
  for (const bool is_start : {true, false}) {
    const Waypoint& w = is_start ? start : goal;
    const std::string name = is_start ? "start" : "goal";
    if (!in_plane_bounds(space_, w.x_m, w.y_m))
      return fail(name + " outside the hidden space",
                  is_start ? PlanFailure::kStartOutside : PlanFailure::kGoalOutside);
    if (checker_->in_collision(w.pose()))
      return fail(name + " in collision",
                  is_start ? PlanFailure::kStartInvalid : PlanFailure::kGoalInvalid);
  }
  // No tether of budget L - l_0 reaches farther than that from the entry.
  if ((goal.position().head<2>() - space_.p_WE).norm() > max_taut)
    return fail("the goal is farther from the entry than L - l_0", PlanFailure::kTetherTooShort);

  auto si = space_information();
  auto space = si->getStateSpace();
  ob::ScopedState<ob::SE2StateSpace> s(space), g(space);
  s->setXY(start.x_m, start.y_m);
  s->setYaw(start.yaw_rad);
  g->setXY(goal.x_m, goal.y_m);
  g->setYaw(goal.yaw_rad);
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(s, g);
  TetheredRRT rrt(si, tether, max_taut, options_.seed);
  rrt.setRange(options_.range_m);
  rrt.setGoalBias(options_.goal_bias);
  rrt.setProblemDefinition(pdef);
  rrt.setup();
  const ob::PlannerStatus status =
      rrt.solve(internal::termination(options_.time_limit_s, options_.cancelled));
  out.tree_size = rrt.treeSize();
  if (status != ob::PlannerStatus::EXACT_SOLUTION) {
    if (options_.cancelled && options_.cancelled())
      return fail("cancelled before a path was found", PlanFailure::kCancelled);
    return fail("no tether-feasible path found within the time limit", PlanFailure::kTimeout);
  }
  std::vector<Waypoint> nodes;
  for (const ob::State* st :
       pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>()->getStates()) {
    const auto* se2 = st->as<ob::SE2StateSpace::StateType>();
    nodes.push_back(waypoint({se2->getX(), se2->getY(), se2->getYaw()}));
  }
  UgvPlan done = finish(std::move(nodes), tether, max_taut, 0.0);
  done.initial_wraps = out.initial_wraps;
  done.tree_size = out.tree_size;
  done.planning_time_s = seconds_since(t0);
  return done;
}

UgvPlan UgvPlanner::finish(std::vector<Waypoint> nodes, const TautTether& tether0,
                           double max_taut_m, double t0_s) {
  UgvPlan out;
  auto motion_free = [&](const Waypoint& a, const Waypoint& b) {
    Waypoint from = a;
    for (const Waypoint& next : turn_drive_turn(a, b)) {
      if (first_collision(*checker_, from, next, options_.resolution)) return false;
      from = next;
    }
    return true;
  };
  auto tether_fits = [&](const std::vector<Waypoint>& path) {
    TautTether t = tether0;
    std::vector<Waypoint> copy = path;
    return replay_tether(t, copy, max_taut_m) < 0;
  };
  // Shortcutting that keeps the tether feasible: from each node jump to the farthest
  // node the robot can drive to directly, if the whole path's tether still fits
  // (a shortcut changes the homotopy class, so the rest of the path is replayed).
  for (int round = 0; round < options_.shortcut_rounds && nodes.size() > 2; ++round) {
    std::vector<Waypoint> result{nodes.front()};
    std::size_t i = 0;
    while (i + 1 < nodes.size()) {
      std::size_t next = i + 1;
      for (std::size_t j = nodes.size() - 1; j > i + 1; --j) {
        if (!motion_free(nodes[i], nodes[j])) continue;
        std::vector<Waypoint> candidate = result;
        candidate.insert(candidate.end(), nodes.begin() + static_cast<std::ptrdiff_t>(j),
                         nodes.end());
        if (!tether_fits(candidate)) continue;
        next = j;
        break;
      }
      result.push_back(nodes[next]);
      i = next;
    }
    if (result.size() == nodes.size()) break;
    nodes = std::move(result);
  }
  // The executed poses: turns in place and straight drives.
  std::vector<Waypoint> dense{nodes.front()};
  for (std::size_t k = 1; k < nodes.size(); ++k)
    for (const Waypoint& w : turn_drive_turn(nodes[k - 1], nodes[k])) dense.push_back(w);
  dense.front().t_s = t0_s;
  assign_times(dense, options_.max_velocity_mps, options_.max_yaw_rate_radps,
               options_.max_acceleration_mps2);
  TautTether t = tether0;
  if (replay_tether(t, dense, max_taut_m) >= 0) {
    out.status = "final path exceeds the tether length";
    out.failure = PlanFailure::kNoPath;
    return out;
  }
  // Re-validate the executed poses at the resolution `ferret validate` uses
  // (simplified paths can touch invalid regions when checks are coarse, OMPL #221),
  // with the checker (same answers as FCL) or, on request, with FCL alone.
  for (std::size_t k = 1; k < dense.size(); ++k) {
    if (first_collision(*checker_, dense[k - 1], dense[k], options_.resolution,
                        options_.final_check_fcl_only) ||
        !in_plane_bounds(space_, dense[k].x_m, dense[k].y_m)) {
      out.status = "final path failed exact validation";
      out.failure = PlanFailure::kNoPath;
      return out;
    }
  }
  out.solved = true;
  out.status = "solved";
  out.final_wraps = t.wrap_points();
  out.states = std::move(dense);
  return out;
}

UgvPlan UgvPlanner::plan_return(const UgvPlanRequest& request) {
  const auto t0 = std::chrono::steady_clock::now();
  const double max_taut = request.tether.total_length_m - request.tether.entry_offset_m;
  TautTether tether(corners_, space_.p_WE);
  for (const Eigen::Vector2d& p : request.driven) tether.move_to(p);
  tether.move_to(request.start.position());
  // Retrace: the wrap points in reverse, each pushed off its corner into free space by
  // the robot's half diagonal plus a margin.
  const double offset = 0.5 * ugv_.body_size_m.head<2>().norm() + 2.0 * map_->resolution_m();
  std::vector<Waypoint> nodes{waypoint(request.start)};
  for (const Eigen::Vector2d& p : way_back_along_tether(tether, offset))
    nodes.push_back(waypoint({p.x(), p.y(), 0.0}));
  nodes.push_back(waypoint(request.goal));
  bool ok = true;
  for (std::size_t k = 1; k < nodes.size() && ok; ++k) {
    Waypoint from = nodes[k - 1];
    for (const Waypoint& next : turn_drive_turn(nodes[k - 1], nodes[k])) {
      if (!in_plane_bounds(space_, next.x_m, next.y_m) ||
          first_collision(*checker_, from, next, options_.resolution)) {
        ok = false;
        break;
      }
      from = next;
    }
  }
  UgvPlan out;
  if (ok) {
    out = finish(std::move(nodes), tether, max_taut, 0.0);
    out.initial_wraps = tether.wrap_points();
  }
  if (!out.solved) {
    UgvPlanRequest again = request;
    out = plan(again);
  }
  out.planning_time_s = seconds_since(t0);
  return out;
}

}  // namespace ferret
