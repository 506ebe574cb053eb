#include "ferret/mission/ugv_mission_run.hpp"

#include <cmath>

#include "ferret/core/clock.hpp"
#include "ferret/mission/mission_assembly.hpp"

namespace ferret {

UgvMissionRunResult run_ugv_mission(const OccupancyMap2D& truth, const Pose2& start,
                                    const std::optional<Eigen::Vector2d>& object_W,
                                    const UgvMissionRunSettings& settings, std::uint64_t seed,
                                    TransitionLog* log, const UgvMissionTickHook& on_tick) {
  SimClock clock;
  TransitionLog own_log;
  TransitionLog& transitions = log ? *log : own_log;
  UgvMissionSim sim(truth, start, object_W, settings, seed,
                    MissionAssembly::ugv_controllers(settings, clock, &transitions));

  const double dt = sim.tick_s();
  const auto max_steps = static_cast<long>(std::ceil(settings.time_limit_s / dt));
  std::optional<double> retract_at_s;
  MiniUgvMission& mission = ugv_mission_of(sim);
  sim.start();
  for (long step = 0; step < max_steps && !mission.done(); ++step) {
    clock.set(static_cast<double>(step) * dt);
    if (mission.wants_retraction()) {
      if (!retract_at_s) retract_at_s = clock.now_s() + settings.retract_time_s;
      if (clock.now_s() >= *retract_at_s) {
        mission.retracted();
        break;
      }
    }
    sim.step(dt);
    if (on_tick) on_tick(clock.now_s(), mission, sim.base());
  }
  if (!mission.done()) mission.stop("the simulation's time limit");
  UgvMissionRunResult result = sim.result(transitions);
  result.time_s = clock.now_s();
  return result;
}

}  // namespace ferret
