#pragma once
// The miniUGV's whole mission in a simulated hidden space (`ferret explore --retrieve`,
// docs/mission.md): its controller from MissionAssembly driving the world's SimUgvBase
// (sim/ugv_mission_run.hpp) on a SimClock, the winch's lift simulated when the robot asks
// for it. Deterministic for a seed; only the simulation knows where the object really is.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>

#include "ferret/core/transition_log.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/sim/ugv_mission_run.hpp"
#include "ferret/ugv/mini_ugv_mission.hpp"

namespace ferret {

/// Called after every tick with the time, the controller and the simulated robot (a
/// recorder's hook: UgvMissionRecorder writes the MCAP log from it).
using UgvMissionTickHook =
    std::function<void(double t_s, const MiniUgvMission&, const SimUgvBase&)>;

/// Runs one miniUGV mission from `start` in `truth` with `seed`.
/// @param object_W the object, or none (an empty hidden space)
/// @param log      receives the transitions as they happen (may be null)
/// @param on_tick  called after every tick (may be empty)
/// @throws std::invalid_argument as run_exploration; InputError for bad options.
[[nodiscard]] UgvMissionRunResult run_ugv_mission(const OccupancyMap2D& truth, const Pose2& start,
                                                  const std::optional<Eigen::Vector2d>& object_W,
                                                  const UgvMissionRunSettings& settings,
                                                  std::uint64_t seed, TransitionLog* log = nullptr,
                                                  const UgvMissionTickHook& on_tick = {});

}  // namespace ferret
