#pragma once
// An OMPL planner for a robot on a taut tether: RRT whose tree nodes carry the
// tether's state (its wrap points), because whether a state is reachable depends on
// the path that leads there, not on the state alone. A motion is added only when it
// is collision-free (SpaceInformation::checkMotion) and the tether, pulled taut along
// the branch, stays within the length budget. Works in SE2 (x, y, yaw); the tether
// follows (x, y). Deterministic given its seed (it draws from ferret::Rng, not from
// OMPL's process-wide RNG).

#include <ompl/base/Planner.h>
#include <ompl/datastructures/NearestNeighbors.h>

#include <memory>
#include <vector>

#include "ferret/core/random.hpp"
#include "ferret/tether_model/taut_tether.hpp"

namespace ferret {

class TetheredRRT : public ompl::base::Planner {
 public:
  /// @param tether         the tether with the robot at the start state
  /// @param max_taut_m     L - l_0
  TetheredRRT(const ompl::base::SpaceInformationPtr& si, TautTether tether, double max_taut_m,
              std::uint64_t seed);
  ~TetheredRRT() override;

  ompl::base::PlannerStatus solve(const ompl::base::PlannerTerminationCondition& ptc) override;
  void clear() override;
  void setup() override;
  void getPlannerData(ompl::base::PlannerData& data) const override;

  void setRange(double range_m) { range_m_ = range_m; }
  [[nodiscard]] double getRange() const { return range_m_; }
  void setGoalBias(double bias) { goal_bias_ = bias; }
  [[nodiscard]] double getGoalBias() const { return goal_bias_; }
  [[nodiscard]] std::size_t treeSize() const { return motions_.size(); }

 private:
  struct Motion {
    ompl::base::State* state = nullptr;
    Motion* parent = nullptr;
    TautTether tether;
  };
  void freeMemory();

  TautTether tether0_;
  double max_taut_m_;
  Rng rng_;
  double range_m_ = 1.5;
  double goal_bias_ = 0.15;
  std::vector<std::unique_ptr<Motion>> motions_;
  std::shared_ptr<ompl::NearestNeighbors<Motion*>> nn_;
};

}  // namespace ferret
