#pragma once
// The termination condition every ferret planner solves under: its time limit, or the
// caller's cancel flag when it has one (called at every check: it must be cheap, an
// atomic load, since no extra thread polls it).

#include <ompl/base/PlannerTerminationCondition.h>

#include <functional>

namespace ferret::internal {

[[nodiscard]] inline ompl::base::PlannerTerminationCondition termination(
    double time_limit_s, const std::function<bool()>& cancelled) {
  namespace ob = ompl::base;
  if (!cancelled) return ob::timedPlannerTerminationCondition(time_limit_s);
  return ob::plannerOrTerminationCondition(
      ob::timedPlannerTerminationCondition(time_limit_s),
      ob::PlannerTerminationCondition([cancelled] { return cancelled(); }));
}

}  // namespace ferret::internal
