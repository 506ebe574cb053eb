#include "ferret/sim/exploration_settings.hpp"

#include <stdexcept>

#include "ferret/planning/exploration_policy.hpp"

namespace ferret {

void check_episode(const OccupancyMap2D& truth, const Pose2& start, const std::string& method) {
  if (!has_exploration_policy(method))
    throw std::invalid_argument("unknown exploration method: " + method);
  if (!truth.is_free(truth.geometry.cell_at(start.x_m, start.y_m)))
    throw std::invalid_argument("the start pose is not on a free cell of the map");
}

}  // namespace ferret
