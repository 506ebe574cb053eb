#include "ferret/sim/mission_world.hpp"

#include <algorithm>
#include <cmath>

#include "ferret/core/error.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/planning/ugv_planner.hpp"
#include "ferret/uav/flight_planner.hpp"

namespace ferret::internal {
namespace {

// A controller acts on a timeout at its next tick after it passed: the invariant allows
// that tick and a little more (the miniUGV's controller ticks at the IR rate).
constexpr double kTimeoutSlack_s = 0.5;

InvariantLimits invariant_limits(const MissionRunSettings& s) {
  InvariantLimits l;
  l.max_tension_n = s.uav.winch_control.slack_estimator.tension.max_tension_n;
  l.tether_length_m = s.uav.tether.total_length_m;
  for (int k = 0; k <= static_cast<int>(UavMissionState::kDone); ++k) {
    const auto state = static_cast<UavMissionState>(k);
    if (const auto t = s.uav.state_timeout_s(state))
      l.state_timeout_s["uav"][std::string(to_string(state))] = *t + kTimeoutSlack_s;
  }
  for (int k = 0; k <= static_cast<int>(UgvMissionState::kDone); ++k) {
    const auto state = static_cast<UgvMissionState>(k);
    if (const auto t = s.ugv.ugv.state_timeout_s(state))
      l.state_timeout_s["ugv"][std::string(to_string(state))] = *t + kTimeoutSlack_s;
  }
  return l;
}

}  // namespace

MissionWorld::MissionWorld(const PlanningWorld& world, const RobotDescription& uav_robot,
                           const MissionRunSettings& settings, std::uint64_t seed,
                           TransitionLog& log)
    : world_(world),
      settings_(settings),
      sensors_(world.spec ? *world.spec : WorldSpec{}),
      invariants_(InvariantLimits{}) {
  if (!world.spec)
    throw InputError(world.source.string(), "",
                     "a world YAML (an OctoMap file names no hidden spaces)");
  const WorldSpec& spec = *world.spec;
  UavMissionOptions& uo = settings_.uav;
  fill_uav_mission_from_world(uo, spec, settings_.ugv.exploration.mission);
  uo.validate("mission");

  const CameraSensor& marker_sensor = camera_for(uav_robot, false, "marker_camera");
  const CameraSensor& depth_sensor = camera_for(uav_robot, true, "depth_camera");
  marker_model_ = camera_model(marker_sensor, uav_robot.source);
  depth_model_ = camera_model(depth_sensor, uav_robot.source);

  // Home: the drop zone's edge if there is one, else the area's south-west corner.
  const Eigen::Vector2d home_xy =
      spec.drop_zone ? Eigen::Vector2d(spec.drop_zone->center_m +
                                       Eigen::Vector2d(spec.drop_zone->radius_m + 1.0, 0.0))
                     : Eigen::Vector2d(uo.search_area_m[0], uo.search_area_m[1]);
  double home_z = 0.0;
  if (const auto d = sensors_.cast_ray({home_xy.x(), home_xy.y(), spec.bounds_max_m.z() - 0.01},
                                       -Eigen::Vector3d::UnitZ(), 1e3))
    home_z = spec.bounds_max_m.z() - 0.01 - *d;
  flight_ = std::make_unique<SimFlightController>(
      sensors_, Eigen::Vector3d(home_xy.x(), home_xy.y(), home_z + settings_.landed_height_m),
      settings_);
  cameras_ = std::make_unique<SimUavCameras>(sensors_, *flight_, marker_sensor, marker_model_,
                                             depth_sensor, depth_model_, seed,
                                             settings_.render_markerless_frames);
  tether::SimulatedWinch::Options wo;
  wo.total_length_m = uo.tether.total_length_m;
  winch_ = std::make_unique<tether::SimulatedWinch>(wo);
  spaces_ = std::make_unique<SimHiddenSpaces>(world, sensors_, settings_, clock_, log, seed);
  // The truth check of the UAV's shape (every 0.1 s of flight) on the world's OctoMap.
  const Aabb3 fence = default_uav_bounds(world);
  map_ = CollisionMap::build(*world.tree, uav_map_options(world.spec, UnknownPolicy::kFree, fence));
  const LoadedPlanRobot alone =
      load_plan_robot(PlanRobot::kUav, PlanRobotModel{uav_robot.source, false},
                      settings_.ugv.exploration.mission, 0.0, "UAV");
  truth_checker_ = std::make_unique<CollisionChecker>(map_, alone.shape);

  invariants_ = InvariantMonitor(invariant_limits(settings_));
  check_injectable(settings_.faults, "the mission's fault plan");
  if (!settings_.faults.empty()) faults_.emplace(settings_.faults);
  result_.hidden_spaces_in_world = static_cast<int>(spec.hidden_spaces.size());
  for (const WorldObject& o : spec.objects) result_.objects_in_world += o.hidden_space >= 0 ? 1 : 0;
}

void MissionWorld::run(const MissionControllers& controllers,
                       const std::function<void(double t_s)>& on_sample) {
  const UavMissionOptions& uo = settings_.uav;
  MissionRunResult& result = result_;
  const tether::TensionModel tension_model = uo.winch_control.slack_estimator.tension;
  const auto ugv_every =
      static_cast<long>(std::lround(1.0 / settings_.ugv.exploration.sensors.ir_rate_hz / kDt));
  const auto max_steps = static_cast<long>(std::ceil(settings_.time_limit_s / kDt));
  bool over_tension = false;
  double tension_n = tension_model.hanging_weight_n;
  SimFlightController& flight = *flight_;
  tether::SimulatedWinch& winch = *winch_;
  SimHiddenSpaces& spaces = *spaces_;
  std::string state = controllers.uav_state();
  bool ugv_hold = false;
  long step = 0;
  for (; step < max_steps && !controllers.uav_done(); ++step) {
    clock_.set(static_cast<double>(step) * kDt);
    if (step % kUavEvery == 0) {
      spaces.hang_over(flight.state().p_W);
      controllers.uav_tick();
      state = controllers.uav_state();
      spaces.set_reeling_in(state == to_string(UavMissionState::kRetract));
    }
    if (step % ugv_every == 0) {
      const bool hold = controllers.link_receive && controllers.link_receive();
      ugv_hold = hold;
      if (spaces.active()) {
        if (controllers.ugv_tick) controllers.ugv_tick();
        if (!controllers.ugv_stopped || !controllers.ugv_stopped())
          spaces.step(ugv_every * kDt, hold);
      }
      if (controllers.link_send) controllers.link_send();
    }
    flight.step(kDt);
    // The tether: taut on the floor while the miniUGV works (its tension from the
    // stretch), the miniUGV's weight while it hangs, nothing while it is aboard.
    const auto required = spaces.true_required_m();
    for (int k = 0; k < static_cast<int>(std::lround(kDt / kWinchDt)); ++k) {
      const double l = winch.released_m();
      tension_n = required
                      ? tension_model.tension_n(l, l - *required) + tension_model.hanging_weight_n
                      : tension_model.hanging_weight_n;
      winch.advance(kWinchDt, tension_n);
    }
    result.max_released_m = std::max(result.max_released_m, winch.released_m());
    if (required && *required > uo.tether.total_length_m) ++result.required_over_length;
    result.max_tension_n = std::max(result.max_tension_n, tension_n);
    const bool over = tension_n > tension_model.max_tension_n;
    if (over && !over_tension) ++result.over_tension_events;
    over_tension = over;
    const FlightState fs = flight.state();
    const bool collided = step % 10 == 0 && !fs.on_ground &&
                          fs.p_W.z() - flight.ground_below() > 0.6 &&
                          truth_checker_->in_collision(body_pose(fs));
    if (collided) {
      ++result.uav_collisions;
      ++result.collisions_in[state];
      if (result.uav_collisions == 1) result.first_collision_W = fs.p_W;
    }
    {
      InvariantSample& s = last_sample_;
      s.t_s = clock_.now_s();
      s.tension_n = tension_n;
      s.released_m = winch.released_m();
      s.uav_collision = collided;
      s.uav_battery = fs.battery_fraction;
      s.uav_state = state;
      const UgvMissionSim* ugv = spaces.active();
      s.ugv_body_contact = ugv && ugv->base().in_contact();
      s.ugv_contact_depth_m = ugv ? ugv->base().contact_depth_m() : 0.0;
      s.ugv_battery = ugv ? std::optional(ugv->base().status().battery_fraction) : std::nullopt;
      if (!ugv)
        s.ugv_state.clear();
      else if (ugv_hold)
        s.ugv_state = "link_hold";  // the watchdog's: the controller does not tick
      else if (controllers.ugv_state)
        s.ugv_state = controllers.ugv_state();
      else if (ugv->has_controller())
        s.ugv_state = to_string(ugv->controller().state());
      invariants_.observe(s);
      if (faults_) inject_faults(s.uav_state, s.ugv_state);
    }
    if (step % 50 == 0) {
      MissionSample s;
      s.t_s = clock_.now_s();
      s.p_W = fs.p_W;
      s.yaw_rad = fs.yaw_rad;
      s.state = state;
      s.battery = fs.battery_fraction;
      s.released_m = winch.released_m();
      s.required_m = required.value_or(0.0);
      s.tension_n = tension_n;
      s.ugv_battery = spaces.active() ? spaces.active()->base().status().battery_fraction : 1.0;
      result.samples.push_back(s);
    }
    if (on_sample && step % 10 == 0) on_sample(clock_.now_s());
  }
  result.time_s = clock_.now_s();
  result.flown_m = flight.flown_m();
  result.battery_left = flight.state().battery_fraction;
  const WorldSpec& spec = *world_.spec;
  if (spec.drop_zone)
    for (const Eigen::Vector3d& p : spaces.released_at())
      result.objects_dropped +=
          (p.head<2>() - spec.drop_zone->center_m).norm() <= spec.drop_zone->radius_m ? 1 : 0;
}

void MissionWorld::inject_faults(const std::string& uav_state, const std::string& ugv_state) {
  FaultSchedule& f = *faults_;
  f.note_state(FaultRobot::kUav, uav_state, clock_.now_s());
  if (!ugv_state.empty()) f.note_state(FaultRobot::kUgv, ugv_state, clock_.now_s());
  f.advance(clock_.now_s());
  const auto drain = [&](FaultTarget robot) {
    const Fault* d = f.acting(FaultKind::kBatteryDrain, robot);
    return d ? d->strength : 1.0;
  };
  flight_->set_battery_drain_factor(drain(FaultTarget::kUav));
  for (const Fault& sag : f.take_due(FaultKind::kBatterySag, FaultTarget::kUav))
    flight_->sag_battery(sag.strength);
  if (UgvMissionSim* ugv = spaces_->active()) {
    ugv->base().set_battery_drain_factor(drain(FaultTarget::kUgv));
    for (const Fault& sag : f.take_due(FaultKind::kBatterySag, FaultTarget::kUgv))
      ugv->base().sag_battery(sag.strength);
  }
  cameras_->set_blackout(f.acts(FaultKind::kCameraBlackout, FaultTarget::kMarkerCamera),
                         f.acts(FaultKind::kCameraBlackout, FaultTarget::kDepthCamera));
}

void MissionWorld::finish_invariants(bool ended, const std::string& ugv_left_reason) {
  invariants_.finish(last_sample_, spaces_->active() != nullptr, ugv_left_reason, ended);
  result_.invariant_violations = invariants_.violations();
}

}  // namespace ferret::internal
