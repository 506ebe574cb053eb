#include "ferret/mission/exploration_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "ferret/core/random.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/sim/sim_ugv_base.hpp"

namespace ferret {

UgvSensorGeometry sensor_geometry(const SensorOptions& s) {
  return {s.ir_fov_rad,     s.ir_range_m,      s.ir_rate_hz,    s.camera_range_m,
          s.camera_rate_hz, s.object_radius_m, s.camera_fov_rad};
}

ExploreOptions explore_options(const ExplorationSettings& settings, std::uint64_t seed,
                               const Eigen::Vector2d& object_W) {
  ExploreOptions o;
  o.set_tuning(settings);
  o.method = settings.method;
  o.sensors = sensor_geometry(settings.sensors);
  o.robot = settings.robot;
  o.mission = settings.mission;
  o.seed = derive_seed(seed, {stable_hash("policy")});  // the OMPL frontier policies
  o.oracle_object_W = object_W;  // the controller hands it only to a policy that asks
  o.record_decisions = settings.record;
  return o;
}

EpisodeResult run_exploration(const OccupancyMap2D& truth, const Pose2& start,
                              const Eigen::Vector2d& object_W, const ExplorationSettings& settings,
                              std::uint64_t seed) {
  check_episode(truth, start, settings.method);
  const GridGeometry& geo = truth.geometry;

  SensorOptions sensors = settings.sensors;
  sensors.eta_m = settings.mission.object_search.eta_m;
  HiddenSpaceSim sim(truth, object_W, sensors, seed);
  SimUgvOptions base_options;
  base_options.robot = settings.robot;
  base_options.battery_endurance_s = std::numeric_limits<double>::infinity();  // not the episode's
  SimUgvBase base(sim, start, base_options);
  ExploreController controller(geo, start, explore_options(settings, seed, object_W));

  EpisodeResult result;
  const double dt = controller.tick_s();
  const auto max_steps = static_cast<long>(std::ceil(settings.time_limit_s / dt));
  for (long step = 0;; ++step) {
    const double t = static_cast<double>(step) * dt;
    const Pose2 pose = base.odometry();
    if (settings.record) result.trajectory.push_back(pose);
    // The simulated sensors are drawn outside the timed span: on the robot they arrive.
    const RangeScan scan = base.ir_scan();
    std::optional<CameraFrame> frame;
    if (controller.frame_due(step)) frame = base.camera_frame(t);
    const auto cycle_start = std::chrono::steady_clock::now();
    controller.observe_scan(scan);
    if (frame) {
      if (const auto cell = controller.observe_frame(*frame)) {
        result.found_W = geo.center(*cell);
        result.found =
            (result.found_W - object_W).norm() <= sensors.object_radius_m + 2 * geo.resolution_m;
        result.end_reason = result.found ? "found" : "false_find";
        result.time_s = t;
        break;
      }
    }
    if (step >= max_steps) {
      result.end_reason = "time_limit";
      result.time_s = t;
      break;
    }
    const ExploreController::Command command = controller.decide(step, pose);
    if (settings.time_decision_cycles && controller.cycle_ran())
      result.decision_cycle_s.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - cycle_start).count());
    if (command.explored) {
      result.end_reason = "explored";
      result.time_s = t;
      break;
    }
    base.command_velocity(command.velocity.v_mps, command.velocity.w_radps);
    base.step(dt);
  }
  result.path_m = base.distance_driven_m();
  result.decisions = controller.decisions();
  if (settings.record) {
    result.decision_log = controller.decision_log();
    result.frontier = controller.frontier();
    result.grid = controller.grid_ptr();
    result.objects = controller.objects_ptr();
  }
  return result;
}

}  // namespace ferret
