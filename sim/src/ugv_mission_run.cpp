#include "ferret/sim/ugv_mission_run.hpp"

#include <cmath>

#include "ferret/core/clock.hpp"

namespace ferret {

UgvMissionRunResult run_ugv_mission(const OccupancyMap2D& truth, const Pose2& start,
                                    const std::optional<Eigen::Vector2d>& object_W,
                                    const UgvMissionRunSettings& settings, std::uint64_t seed,
                                    TransitionLog* log) {
  const ExplorationSettings& ex = settings.exploration;
  check_episode(truth, start, ex.method);
  const GridGeometry& geo = truth.geometry;

  SensorOptions sensors = ex.sensors;
  sensors.eta_m = ex.mission.object_search.eta_m;
  // An empty hidden space: the object far outside the map, where no sensor reaches.
  const Eigen::Vector2d far_W(geo.origin_x_m - 1e6, geo.origin_y_m - 1e6);
  HiddenSpaceSim sim(truth, object_W.value_or(far_W), sensors, seed);
  SimUgvOptions base_options = settings.base;
  base_options.robot = ex.robot;
  SimUgvBase base(sim, start, base_options);
  SimClock clock;
  TransitionLog own_log;
  TransitionLog& transitions = log ? *log : own_log;

  UgvMissionOptions options = settings.ugv;
  options.explore = explore_options(ex, seed, object_W.value_or(far_W));
  if (!object_W) options.explore.oracle_object_W.reset();
  MiniUgvMission mission(base, clock, geo, options, &transitions);

  UgvMissionRunResult result;
  const double dt = 1.0 / sensors.ir_rate_hz;
  const auto max_steps = static_cast<long>(std::ceil(settings.time_limit_s / dt));
  std::optional<double> retract_at_s;
  mission.start();
  long step = 0;
  for (; step < max_steps && !mission.done(); ++step) {
    clock.set(static_cast<double>(step) * dt);
    if (ex.record) result.trajectory.push_back(base.true_pose());
    if (mission.wants_retraction()) {
      if (!retract_at_s) retract_at_s = clock.now_s() + settings.retract_time_s;
      if (clock.now_s() >= *retract_at_s) {
        mission.retracted();
        break;
      }
    }
    mission.tick();
    base.step(dt);
    if (const double l = mission.explore_controller().tether_length_m(); l > result.max_tether_m) {
      result.max_tether_m = l;
      result.max_tether_state = mission.state();
    }
    if (settings.on_tick) settings.on_tick(clock.now_s(), mission, base);
  }
  if (!mission.done()) mission.stop("the simulation's time limit");
  result.outcome = mission.outcome();
  result.final_state = mission.state();
  result.time_s = clock.now_s();
  result.path_m = base.distance_driven_m();
  result.battery_left = base.status().battery_fraction;
  result.object_held = base.object_held();
  result.found_W = mission.found_W();
  if (result.found_W && object_W)
    result.found_right =
        (*result.found_W - *object_W).norm() <= sensors.object_radius_m + 2 * geo.resolution_m;
  result.grasp_attempts = mission.grasp_attempts();
  result.decisions = mission.explore_controller().decisions();
  result.transitions = transitions.all();
  result.grid = mission.explore_controller().grid_ptr();
  result.objects = mission.explore_controller().objects_ptr();
  return result;
}

}  // namespace ferret
