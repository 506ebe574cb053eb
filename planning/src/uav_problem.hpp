#pragma once
// Private: the OMPL objects of a UAV planning problem (bench-plan runs OMPL's
// Benchmark on them).

#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>

#include <functional>

#include "ferret/planning/uav_planner.hpp"

namespace ferret {

struct UavPlanner::Problem {
  ompl::base::StateSpacePtr space;
  ompl::base::SpaceInformationPtr si;
  ompl::base::ProblemDefinitionPtr pdef;
  std::function<Waypoint(const ompl::base::State*)> to_waypoint;
};

}  // namespace ferret
