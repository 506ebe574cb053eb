#include "ferret/planning/uav_planner.hpp"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/Planner.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/ScopedState.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/PathSimplifier.h>

#include <chrono>

#include "ferret/planning/collision_checker.hpp"
#include "ferret/planning/ompl_setup.hpp"
#include "ompl_termination.hpp"

namespace ob = ompl::base;

namespace ferret {
namespace {

Waypoint to_waypoint(const ob::State* s) {
  const auto* c = s->as<ob::CompoundStateSpace::StateType>();
  const auto* p = c->as<ob::RealVectorStateSpace::StateType>(0);
  Waypoint w;
  w.x_m = p->values[0];
  w.y_m = p->values[1];
  w.z_m = p->values[2];
  w.yaw_rad = c->as<ob::SO2StateSpace::StateType>(1)->value;
  return w;
}

void from_waypoint(const Waypoint& w, ob::State* s) {
  auto* c = s->as<ob::CompoundStateSpace::StateType>();
  auto* p = c->as<ob::RealVectorStateSpace::StateType>(0);
  p->values[0] = w.x_m;
  p->values[1] = w.y_m;
  p->values[2] = w.z_m;
  c->as<ob::SO2StateSpace::StateType>(1)->value = wrap_angle_rad(w.yaw_rad);
}

// Straight lines in position with the yaw turning along the shorter arc, checked at
// the poses `ferret validate` checks.
class LinearMotionValidator : public ob::MotionValidator {
 public:
  LinearMotionValidator(const ob::SpaceInformationPtr& si, CollisionChecker& checker,
                        CheckResolution res)
      : ob::MotionValidator(si), checker_(checker), res_(res) {}
  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const bool ok = !first_collision(checker_, to_waypoint(s1), to_waypoint(s2), res_);
    ++(ok ? valid_ : invalid_);
    return ok;
  }
  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& last) const override {
    const Waypoint a = to_waypoint(s1), b = to_waypoint(s2);
    const auto hit = first_collision(checker_, a, b, res_);
    if (!hit) {
      ++valid_;
      return true;
    }
    ++invalid_;
    const double s = std::max(0.0, *hit - 1.0 / segment_steps(a, b, res_));
    if (last.first) from_waypoint(interpolate(a, b, s), last.first);
    last.second = s;
    return false;
  }

 private:
  CollisionChecker& checker_;
  CheckResolution res_;
};

}  // namespace

UavPlanner::UavPlanner(std::shared_ptr<const CollisionMap> map, RobotShape shape,
                       const UavPlannerOptions& options)
    : map_(std::move(map)), options_(options) {
  checker_ = std::make_unique<CollisionChecker>(map_, std::move(shape));
}

UavPlanner::~UavPlanner() = default;

std::shared_ptr<ob::SpaceInformation> UavPlanner::space_information() {
  auto r3 = std::make_shared<ob::RealVectorStateSpace>(3);
  ob::RealVectorBounds bounds(3);
  for (int a = 0; a < 3; ++a) {
    bounds.setLow(a, options_.geofence.lo[a]);
    bounds.setHigh(a, options_.geofence.hi[a]);
  }
  r3->setBounds(bounds);
  auto space = std::make_shared<ob::CompoundStateSpace>();
  space->addSubspace(r3, 1.0);
  space->addSubspace(std::make_shared<ob::SO2StateSpace>(), 0.5);
  auto si = std::make_shared<ob::SpaceInformation>(space);
  CollisionChecker* checker = checker_.get();
  const Aabb3 fence = options_.geofence;
  si->setStateValidityChecker([checker, fence](const ob::State* s) {
    const Waypoint w = to_waypoint(s);
    return fence.contains(w.position()) && !checker->in_collision(w.pose());
  });
  si->setMotionValidator(
      std::make_shared<LinearMotionValidator>(si, *checker, options_.resolution));
  si->setup();
  return si;
}

void UavPlanner::to_ompl_state(const Waypoint& w, ob::State* state) const {
  from_waypoint(w, state);
  // OMPL's SO2 range differs from wrap_angle_rad's at +-pi: let the space normalise.
  auto* so2 = state->as<ob::CompoundStateSpace::StateType>()->as<ob::SO2StateSpace::StateType>(1);
  ob::SO2StateSpace().enforceBounds(so2);
}

UavPlan UavPlanner::plan(const Waypoint& start, const Waypoint& goal) {
  const auto t0 = std::chrono::steady_clock::now();
  seed_ompl_once(options_.seed);
  UavPlan out;
  auto fail = [&](std::string why, PlanFailure failure) {
    out.status = std::move(why);
    out.failure = failure;
    out.planning_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
  };
  for (const bool is_start : {true, false}) {
    const Waypoint& w = is_start ? start : goal;
    const std::string name = is_start ? "start" : "goal";
    if (!options_.geofence.contains(w.position()))
      return fail(name + " outside the geofence",
                  is_start ? PlanFailure::kStartOutside : PlanFailure::kGoalOutside);
    if (checker_->in_collision(w.pose()))
      return fail(name + " in collision",
                  is_start ? PlanFailure::kStartInvalid : PlanFailure::kGoalInvalid);
  }
  auto si = space_information();
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  ob::ScopedState<> s(si->getStateSpace()), g(si->getStateSpace());
  to_ompl_state(start, s.get());
  to_ompl_state(goal, g.get());
  pdef->setStartAndGoalStates(s, g);
  auto planner = make_ompl_planner(options_.planner, si);
  if (options_.range_m > 0.0 && planner->params().hasParam("range"))
    planner->params().setParam("range", std::to_string(options_.range_m));
  planner->setProblemDefinition(pdef);
  planner->setup();
  const ob::PlannerStatus status =
      planner->solve(internal::termination(options_.time_limit_s, options_.cancelled));
  if (status != ob::PlannerStatus::EXACT_SOLUTION) {
    if (options_.cancelled && options_.cancelled())
      return fail("cancelled before a path was found", PlanFailure::kCancelled);
    return fail("no path found within the time limit", PlanFailure::kTimeout);
  }
  auto& path = *pdef->getSolutionPath()->as<ompl::geometric::PathGeometric>();
  // Simplify on a count of rounds, not on time (PathSimplifier::simplify stops on a
  // clock, so a loaded machine would return another path for the same seed). Each
  // step bounds its own attempts by the path's size; no B-spline smoothing (it only
  // adds states to straight segments).
  ompl::geometric::PathSimplifier simplifier(si);
  for (int round = 0; round < options_.simplify_rounds; ++round) {
    const bool shortcut = simplifier.shortcutPath(path);
    const bool reduced = simplifier.reduceVertices(path);
    const bool collapsed = simplifier.collapseCloseVertices(path);
    if (!shortcut && !reduced && !collapsed) break;
  }
  std::vector<Waypoint> states;
  for (const ob::State* s : path.getStates()) states.push_back(to_waypoint(s));
  assign_times(states, options_.max_velocity_mps, options_.max_yaw_rate_radps,
               options_.max_acceleration_mps2);
  // Simplified paths can touch invalid regions (OMPL #221, #1292): check every
  // segment again at the validation resolution, with the checker (same answers as
  // FCL) or, on request, with FCL alone.
  for (std::size_t k = 1; k < states.size(); ++k) {
    if (!options_.geofence.contains(states[k].position()) ||
        first_collision(*checker_, states[k - 1], states[k], options_.resolution,
                        options_.final_check_fcl_only))
      return fail("final path failed exact validation", PlanFailure::kNoPath);
  }
  out.solved = true;
  out.status = "solved";
  out.states = std::move(states);
  out.planning_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace ferret
