#include "ferret/planning/tethered_rrt.hpp"

#include <ompl/base/PlannerData.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/datastructures/NearestNeighborsLinear.h>
#include <ompl/geometric/PathGeometric.h>

#include <limits>

#include "ferret/planning/motion_check.hpp"

namespace ob = ompl::base;

namespace ferret {
namespace {
constexpr double kTetherWeight = 0.5;  // metres of drive per metre of tether
Eigen::Vector2d xy(const ob::State* s) {
  const auto* se2 = s->as<ob::SE2StateSpace::StateType>();
  return {se2->getX(), se2->getY()};
}
}  // namespace

TetheredRRT::TetheredRRT(const ob::SpaceInformationPtr& si, TautTether tether, double max_taut_m,
                         std::uint64_t seed)
    : ob::Planner(si, "TetheredRRT"),
      tether0_(std::move(tether)),
      max_taut_m_(max_taut_m),
      rng_(seed) {
  specs_.approximateSolutions = false;
  specs_.directed = true;
  Planner::declareParam<double>("range", this, &TetheredRRT::setRange, &TetheredRRT::getRange,
                                "0.:0.1:10.");
  Planner::declareParam<double>("goal_bias", this, &TetheredRRT::setGoalBias,
                                &TetheredRRT::getGoalBias, "0.:.05:1.");
}

TetheredRRT::~TetheredRRT() { freeMemory(); }

void TetheredRRT::setup() {
  Planner::setup();
  if (!nn_) nn_ = std::make_shared<ompl::NearestNeighborsLinear<Motion*>>();
  // Nearest in the plane: the heading costs only a turn in place.
  nn_->setDistanceFunction(
      [](const Motion* a, const Motion* b) { return (xy(a->state) - xy(b->state)).norm(); });
}

void TetheredRRT::freeMemory() {
  for (auto& m : motions_)
    if (m->state) si_->freeState(m->state);
  motions_.clear();
}

void TetheredRRT::clear() {
  Planner::clear();
  freeMemory();
  if (nn_) nn_->clear();
}

ob::PlannerStatus TetheredRRT::solve(const ob::PlannerTerminationCondition& ptc) {
  checkValidity();
  auto* goal = dynamic_cast<ob::GoalState*>(pdef_->getGoal().get());
  if (!goal) return ob::PlannerStatus::UNRECOGNIZED_GOAL_TYPE;
  const ob::State* goal_state = goal->getState();
  if (motions_.empty()) {
    const ob::State* start = pis_.nextStart();
    if (!start) return ob::PlannerStatus::INVALID_START;
    auto m = std::make_unique<Motion>(Motion{si_->cloneState(start), nullptr, tether0_});
    nn_->add(m.get());
    motions_.push_back(std::move(m));
  }
  const auto& bounds = si_->getStateSpace()->as<ob::SE2StateSpace>()->getBounds();
  ob::State* candidate = si_->allocState();
  Motion* solution = nullptr;
  const Eigen::Vector2d p_goal = xy(goal_state);

  auto try_add = [&](Motion* from, const ob::State* to) -> Motion* {
    if (!si_->checkMotion(from->state, to)) return nullptr;
    TautTether t = from->tether;
    t.move_to(xy(to));
    if (t.length_m() > max_taut_m_) return nullptr;
    auto m = std::make_unique<Motion>(Motion{si_->cloneState(to), from, std::move(t)});
    Motion* raw = m.get();
    nn_->add(raw);
    motions_.push_back(std::move(m));
    return raw;
  };

  while (!ptc && !solution) {
    Eigen::Vector2d target;
    if (rng_.uniform01() < goal_bias_) {
      target = p_goal;
    } else {
      target = {rng_.uniform(bounds.low[0], bounds.high[0]),
                rng_.uniform(bounds.low[1], bounds.high[1])};
    }
    auto* c = candidate->as<ob::SE2StateSpace::StateType>();
    c->setXY(target.x(), target.y());
    c->setYaw(0.0);
    // The nearest node in the plane (the heading costs only a turn in place) plus a
    // share of its tether paid out. By position alone, a branch whose tether went round
    // an obstacle the long way can cover the way to the goal first and starve the
    // branch with the short tether (a tree over positions forgets the homotopy class),
    // and the search times out although a path exists.
    Motion* near = nullptr;
    double near_cost = std::numeric_limits<double>::infinity();
    for (const auto& m : motions_) {
      const double cost = (xy(m->state) - target).norm() + kTetherWeight * m->tether.length_m();
      if (cost < near_cost) {
        near_cost = cost;
        near = m.get();
      }
    }
    const Eigen::Vector2d from = xy(near->state);
    const double d = (target - from).norm();
    if (d < 1e-6) continue;
    if (d > range_m_) target = from + (target - from) * (range_m_ / d);
    const auto* ns = near->state->as<ob::SE2StateSpace::StateType>();
    Waypoint a;
    a.x_m = ns->getX();
    a.y_m = ns->getY();
    a.yaw_rad = ns->getYaw();
    c->setXY(target.x(), target.y());
    c->setYaw(free_drive_heading_rad(a, target));
    Motion* added = try_add(near, candidate);
    if (!added) continue;
    if ((target - p_goal).norm() <= range_m_) solution = try_add(added, goal_state);
  }
  si_->freeState(candidate);
  if (!solution) return ob::PlannerStatus::TIMEOUT;
  auto path = std::make_shared<ompl::geometric::PathGeometric>(si_);
  std::vector<const Motion*> chain;
  for (const Motion* m = solution; m; m = m->parent) chain.push_back(m);
  for (auto it = chain.rbegin(); it != chain.rend(); ++it) path->append((*it)->state);
  pdef_->addSolutionPath(path, false, 0.0, getName());
  return ob::PlannerStatus::EXACT_SOLUTION;
}

void TetheredRRT::getPlannerData(ob::PlannerData& data) const {
  Planner::getPlannerData(data);
  for (const auto& m : motions_) {
    if (m->parent)
      data.addEdge(ob::PlannerDataVertex(m->parent->state), ob::PlannerDataVertex(m->state));
    else
      data.addStartVertex(ob::PlannerDataVertex(m->state));
  }
}

}  // namespace ferret
