#include "ferret/sim/mission_world.hpp"

#include <algorithm>
#include <cmath>

#include "ferret/core/error.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/planning/ugv_planner.hpp"
#include "ferret/uav/flight_planner.hpp"

namespace ferret::internal {

MissionWorld::MissionWorld(const PlanningWorld& world, const RobotDescription& uav_robot,
                           const MissionRunSettings& settings, std::uint64_t seed,
                           TransitionLog& log)
    : world_(world), settings_(settings), sensors_(world.spec ? *world.spec : WorldSpec{}) {
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
    if (step % 10 == 0 && !fs.on_ground && fs.p_W.z() - flight.ground_below() > 0.6 &&
        truth_checker_->in_collision(body_pose(fs))) {
      ++result.uav_collisions;
      ++result.collisions_in[state];
      if (result.uav_collisions == 1) result.first_collision_W = fs.p_W;
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

}  // namespace ferret::internal
