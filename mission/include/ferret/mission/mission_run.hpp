#pragma once
// The whole mission in one simulated world (docs/mission.md): the UAV's mission
// controller flying a simulated M100 with rendered camera and depth frames, the winch
// (tether::SimulatedWinch) and the tether, and the miniUGV's mission controller in each
// hidden space the UAV lowers it into, all on one SimClock (`ferret mission`). The
// controllers come from MissionAssembly, the world from sim/mission_world.hpp; only the
// world reads the truth. Deterministic for a seed.

#include <cstdint>

#include "ferret/core/transition_log.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/sim/mission_run.hpp"
#include "ferret/uav/uav_mission.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {

class MissionSimImpl;

/// The running simulation, for hooks (read only).
class MissionSim {
 public:
  explicit MissionSim(const MissionSimImpl& impl) : impl_(impl) {}
  [[nodiscard]] const UavMission& uav() const;
  [[nodiscard]] FlightState uav_truth() const;
  /// The miniUGV's mission in the hidden space it works in now, or null.
  [[nodiscard]] const UgvMissionSim* ugv() const;
  [[nodiscard]] double released_m() const;

 private:
  const MissionSimImpl& impl_;
};

/// Runs the mission. `uav_robot` is the UAV's description (its marker and depth
/// cameras, its shape); throws InputError for a world without a world YAML's hidden
/// spaces, a robot without the cameras, or bad options.
[[nodiscard]] MissionRunResult run_mission(const PlanningWorld& world,
                                           const RobotDescription& uav_robot,
                                           const MissionRunSettings& settings, std::uint64_t seed,
                                           TransitionLog* log = nullptr);

}  // namespace ferret
