#include "ferret/sim/ugv_mission_run.hpp"

namespace ferret {

UgvMissionSim::UgvMissionSim(const OccupancyMap2D& truth, const Pose2& start,
                             const std::optional<Eigen::Vector2d>& object_W,
                             const UgvMissionRunSettings& settings, std::uint64_t seed)
    : object_W_(object_W) {
  const ExplorationSettings& ex = settings.exploration;
  check_episode(truth, start, ex.method);
  const GridGeometry& geo = truth.geometry;

  SensorOptions sensors = ex.sensors;
  sensors.eta_m = ex.mission.object_search.eta_m;
  object_radius_m_ = sensors.object_radius_m + 2 * geo.resolution_m;
  record_ = ex.record;
  tick_s_ = 1.0 / sensors.ir_rate_hz;
  // An empty hidden space: the object far outside the map, where no sensor reaches.
  const Eigen::Vector2d far_W(geo.origin_x_m - 1e6, geo.origin_y_m - 1e6);
  sim_ = std::make_unique<HiddenSpaceSim>(truth, object_W.value_or(far_W), sensors, seed);
  SimUgvOptions base_options = settings.base;
  base_options.robot = ex.robot;
  base_ = std::make_unique<SimUgvBase>(*sim_, start, base_options);
}

UgvMissionSim::UgvMissionSim(const OccupancyMap2D& truth, const Pose2& start,
                             const std::optional<Eigen::Vector2d>& object_W,
                             const UgvMissionRunSettings& settings, std::uint64_t seed,
                             const UgvControllerFactory& make_controller)
    : UgvMissionSim(truth, start, object_W, settings, seed) {
  controller_ =
      make_controller(*base_, ugv_mission_map(truth.geometry, start, settings), seed, object_W);
}

GridGeometry ugv_mission_map(const GridGeometry& truth, const Pose2& start,
                             const UgvMissionRunSettings& settings) {
  return settings.map_window_m
             ? GridGeometry::centred_on(start.position(), settings.map_window_m->x(),
                                        settings.map_window_m->y(), truth.resolution_m)
             : truth;
}

UgvMissionSim::~UgvMissionSim() = default;

void UgvMissionSim::step(double dt_s, bool hold) {
  if (record_) trajectory_.push_back(base_->true_pose());
  if (hold) base_->command_velocity(0.0, 0.0);
  // Set down but not told to search yet (its start on its way over the link): it stands.
  if (!controller_ || hold || controller_->state() == UgvMissionState::kIdle) {
    base_->step(dt_s);
    return;
  }
  controller_->tick();
  base_->step(dt_s);
  if (const double l = controller_->tether_length_m(); l > max_tether_m_) {
    max_tether_m_ = l;
    max_tether_state_ = controller_->state();
  }
}

UgvMissionRunResult UgvMissionSim::result(const TransitionLog& log) const {
  UgvMissionRunResult result;
  // What the truth knows.
  result.path_m = base_->distance_driven_m();
  result.battery_left = base_->status().battery_fraction;
  result.object_held = base_->object_held();
  result.body_contacts = base_->body_contacts();
  result.deepest_contact_m = base_->deepest_contact_m();
  result.trajectory = trajectory_;
  if (!controller_) return result;  // the base alone
  controller_->report(result);
  if (result.found_W && object_W_)
    result.found_right = (*result.found_W - *object_W_).norm() <= object_radius_m_;
  result.max_tether_m = max_tether_m_;
  result.max_tether_state = max_tether_state_;
  result.transitions = log.all();
  return result;
}

}  // namespace ferret
