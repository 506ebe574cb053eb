#include "ferret/sim/mission_run.hpp"

#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "ferret/core/clock.hpp"
#include "ferret/core/error.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/colour.hpp"
#include "ferret/planning/collision_checker.hpp"
#include "ferret/planning/collision_map.hpp"
#include "ferret/planning/ompl_setup.hpp"
#include "ferret/planning/uav_planner.hpp"
#include "ferret/sim/search_robot.hpp"
#include "ferret/sim/sensor_sim.hpp"
#include "ferret/tether_model/simulated_winch.hpp"
#include "ferret/tether_model/taut_tether.hpp"

#include <ompl/base/SpaceInformation.h>

namespace ferret {

std::vector<OpeningInMarker> world_openings(const WorldSpec& world) {
  std::vector<OpeningInMarker> out;
  for (const HiddenSpace& h : world.hidden_spaces) out.push_back(opening_in_marker(h));
  return out;
}

namespace {

constexpr double kDt = 0.01;          // the simulation's step
constexpr int kUavEvery = 2;          // UAV control (and winch control) at 50 Hz
constexpr double kWinchDt = 0.001;    // spool physics: the tether is stiff

Pose3 body_pose(const FlightState& s) { return pose_from_xyz_rpy(s.p_W, 0.0, 0.0, s.yaw_rad); }

// The M100 as its flight controller's position loop flies it: a point mass whose
// velocity follows a proportional command within speed and acceleration limits, the
// heading within the yaw-rate limit; landing descends until it rests on what is under it.
class SimFlightController final : public FlightController {
 public:
  SimFlightController(const SensorSimulator& world, const Eigen::Vector3d& start, const MissionRunSettings& s)
      : world_(world), settings_(s) {
    state_.p_W = start;
    state_.on_ground = true;
    setpoint_ = start;
  }
  [[nodiscard]] std::string backend() const override { return "sim"; }
  [[nodiscard]] FlightState state() const override { return state_; }
  void command_takeoff(double z_m) override {
    mode_ = Mode::kPosition;
    setpoint_ = {state_.p_W.x(), state_.p_W.y(), z_m};
    speed_ = 2.0;
    state_.on_ground = false;
  }
  void command_position(const Eigen::Vector3d& p_W, double yaw_rad, double speed_mps) override {
    if (state_.on_ground) return;  // take off first
    mode_ = Mode::kPosition;
    setpoint_ = p_W;
    yaw_sp_ = yaw_rad;
    speed_ = speed_mps;
  }
  void command_land() override {
    if (!state_.on_ground) mode_ = Mode::kLand;
  }

  void step(double dt) {
    if (state_.on_ground) {
      state_.v_W.setZero();
      return;
    }
    Eigen::Vector3d v_cmd = Eigen::Vector3d::Zero();
    if (mode_ == Mode::kPosition) {
      // Towards the setpoint, braking in time to stop on it (no overshoot past a corner).
      const Eigen::Vector3d d = setpoint_ - state_.p_W;
      const double brake = std::sqrt(2.0 * 0.8 * settings_.uav_max_accel_mps2 * d.norm());
      const double cap = std::min({speed_ > 0 ? speed_ : 0.5, settings_.uav_max_speed_mps, brake, 1.2 * d.norm()});
      v_cmd = d.norm() > 1e-9 ? Eigen::Vector3d(d.normalized() * cap) : Eigen::Vector3d::Zero();
    } else {
      v_cmd = {0.0, 0.0, -0.6};
    }
    Eigen::Vector3d dv = v_cmd - state_.v_W;
    const double max_dv = settings_.uav_max_accel_mps2 * dt;
    if (dv.norm() > max_dv) dv *= max_dv / dv.norm();
    state_.v_W += dv;
    state_.p_W += state_.v_W * dt;
    flown_m_ += state_.v_W.norm() * dt;
    double dyaw = std::remainder(yaw_sp_ - state_.yaw_rad, 2 * std::numbers::pi);
    const double max_dyaw = settings_.uav_max_yaw_rate_radps * dt;
    state_.yaw_rad = std::remainder(state_.yaw_rad + std::clamp(dyaw, -max_dyaw, max_dyaw), 2 * std::numbers::pi);
    // Battery: hover power plus a share growing with speed (the M100 with its payload).
    state_.battery_fraction = std::max(
        0.0, state_.battery_fraction - dt * (1.0 + 0.15 * state_.v_W.norm() / settings_.uav_max_speed_mps) /
                                          settings_.uav.flight_endurance_s);
    if (mode_ == Mode::kLand) {
      const double ground = ground_below();
      if (state_.p_W.z() <= ground + settings_.landed_height_m) {
        state_.p_W.z() = ground + settings_.landed_height_m;
        state_.v_W.setZero();
        state_.on_ground = true;
        mode_ = Mode::kPosition;
        setpoint_ = state_.p_W;
      }
    }
  }
  [[nodiscard]] double flown_m() const { return flown_m_; }
  [[nodiscard]] double ground_below() const {
    const auto d = world_.cast_ray(state_.p_W, -Eigen::Vector3d::UnitZ(), 100.0);
    return d ? state_.p_W.z() - *d : 0.0;
  }

 private:
  enum class Mode { kPosition, kLand };
  const SensorSimulator& world_;
  const MissionRunSettings& settings_;
  FlightState state_;
  Mode mode_ = Mode::kPosition;
  Eigen::Vector3d setpoint_ = Eigen::Vector3d::Zero();
  double yaw_sp_ = 0.0;
  double speed_ = 0.0;
  double flown_m_ = 0.0;
};

class SimUavCameras final : public UavCameras {
 public:
  SimUavCameras(const SensorSimulator& world, const SimFlightController& flight, const CameraSensor& marker,
                CameraModel marker_model, const CameraSensor& depth, CameraModel depth_model, std::uint64_t seed)
      : world_(world), flight_(flight), marker_(marker), depth_(depth),
        marker_model_(std::move(marker_model)), depth_model_(std::move(depth_model)), seed_(seed) {}
  CameraShot<GrayImage> marker_frame() override {
    const Pose3 X_WC = optical_pose(body_pose(flight_.state()), marker_);
    return {world_.render_gray(marker_model_, X_WC, CameraFrameOptions{}, seed_ + 2 * frame_++), X_WC};
  }
  CameraShot<DepthImageMm> depth_frame() override {
    const Pose3 X_WC = optical_pose(body_pose(flight_.state()), depth_);
    return {world_.render_depth(depth_model_, X_WC, DepthFrameOptions{}, seed_ + 2 * frame_++ + 1), X_WC};
  }

 private:
  const SensorSimulator& world_;
  const SimFlightController& flight_;
  const CameraSensor& marker_;
  const CameraSensor& depth_;
  CameraModel marker_model_, depth_model_;
  std::uint64_t seed_;
  std::uint64_t frame_ = 0;
};

}  // namespace

// The miniUGV in the world: lowered at an opening, it runs its mission in the true
// hidden space there (a slice of the world's OctoMap at its floor) on the shared clock.
class SimUgvLink final : public UgvLink {
 public:
  SimUgvLink(const PlanningWorld& world, const SensorSimulator& sensors, const MissionRunSettings& settings,
             const SimClock& clock, TransitionLog& log, std::uint64_t seed)
      : world_(world), spec_(*world.spec), sensors_(sensors), settings_(settings), clock_(clock), log_(log),
        seed_(seed) {}

  void deploy(const Eigen::Vector3d& p_WE, double /*entry_yaw_rad*/) override {
    UgvDeployment d;
    d.deployed_s = clock_.now_s();
    const int k = nearest_space(p_WE);
    deployments_.push_back(std::move(d));
    UgvDeployment& dep = deployments_.back();
    if (k < 0) {  // lowered where no hidden space is: nothing to search
      lonely_ = true;
      return;
    }
    lonely_ = false;
    const HiddenSpace& h = spec_.hidden_spaces[static_cast<std::size_t>(k)];
    dep.hidden_space = h.name;
    SliceOptions so;
    so.z_m = h.floor_z_m + 0.03;
    so.window_m = hidden_space_window(spec_, h.name, 0.5, "hidden space");
    dep.truth = slice_octree(*world_.tree, so);
    // The hidden space is its interior: the slice's ring outside the walls would let the
    // miniUGV out through the opening and round the building.
    {
      const GridGeometry& g = dep.truth.geometry;
      for (int j = 0; j < g.height; ++j)
        for (int i = 0; i < g.width; ++i) {
          const Eigen::Vector2d c = g.center({i, j});
          if (!h.interior_contains({c.x(), c.y(), h.floor_z_m + 0.03})) dep.truth.at({i, j}) = CellState::kOccupied;
        }
    }
    for (const WorldObject& o : spec_.objects) {
      if (o.hidden_space != k) continue;
      dep.object_W = o.p_WO().head<2>();
      // The object is the simulator's own (HiddenSpaceSim); its voxels are floor here.
      const Eigen::Vector3d half = 0.5 * o.box.size_m;
      const double r = half.head<2>().norm() + dep.truth.geometry.resolution_m;
      const GridGeometry& g = dep.truth.geometry;
      for (double y = -r; y <= r; y += g.resolution_m)
        for (double x = -r; x <= r; x += g.resolution_m) {
          const Cell c = g.cell_at(dep.object_W->x() + x, dep.object_W->y() + y);
          if (g.contains(c) && dep.truth.at(c) == CellState::kOccupied) dep.truth.at(c) = CellState::kFree;
        }
      break;
    }
    const Eigen::Vector2d e = h.p_WE.head<2>();
    const Eigen::Vector2d in(std::cos(h.entry_yaw_rad), std::sin(h.entry_yaw_rad));
    const Eigen::Vector2d start = e + (h.wall_thickness_m + 0.15) * in;
    // l_0 runs from the winch to where the miniUGV is set down, its entry: the taut
    // tether on the floor starts there, as the miniUGV's own model does.
    entry_W_ = start;
    tether_ = std::make_unique<TautTether>(TetherCorners::from_map(dep.truth), start, start);
    sim_ = std::make_unique<UgvMissionSim>(dep.truth, Pose2{start.x(), start.y(), h.entry_yaw_rad}, dep.object_W,
                                           settings_.ugv, seed_ + 7919 * deployments_.size(), clock_, log_);
    sim_->start();
  }
  void retracted() override {
    if (sim_) {
      if (sim_->mission().wants_retraction()) sim_->mission().retracted();
      if (!sim_->mission().done()) sim_->mission().stop("lifted out");
      deployments_.back().result = sim_->result(log_);
      deployments_.back().result.time_s = clock_.now_s() - deployments_.back().deployed_s;
      holding_ = sim_->base().object_held();
      finished_.push_back(std::move(sim_));
    }
    tether_.reset();
  }
  void release_object() override {
    if (!holding_) return;
    holding_ = false;
    released_at_.push_back(last_uav_W_);
  }
  void abort(const std::string& reason) override {
    if (sim_ && !sim_->mission().done()) sim_->mission().stop(reason);
  }
  void recall(const std::string& reason) override {
    if (sim_) sim_->mission().recall(reason);
  }
  [[nodiscard]] UgvReport report() const override {
    UgvReport r;
    if (lonely_ && !sim_) {
      r.done = true;
      r.outcome = "no_hidden_space";
      r.wants_retraction = true;
      return r;
    }
    if (!sim_) {  // hanging or aboard: its IMU sees where it would touch down
      r.object_held = holding_;
      r.roll_rad = touchdown_.roll_rad;
      r.pitch_rad = touchdown_.pitch_rad;
      return r;
    }
    const MiniUgvMission& m = sim_->mission();
    r.running = !m.done();
    r.done = m.done();
    r.wants_retraction = m.wants_retraction();
    if (m.done()) r.outcome = std::string(to_string(m.outcome()));
    if (m.wants_retraction()) r.outcome = std::string(to_string(m.return_outcome()));
    r.object_held = sim_->base().status().epm_on && sim_->base().status().contact;
    const Pose2 p = sim_->base().odometry();
    r.p_WG = {p.x_m, p.y_m};
    r.v_WG = sim_->base().speed_mps() * Eigen::Vector2d(std::cos(p.yaw_rad), std::sin(p.yaw_rad));
    if (const auto a = m.explore_controller().tether_anchor()) {
      r.tether_anchor_W = a->first;
      r.tether_to_anchor_m = a->second;
      r.tether_uncertainty_m =
          std::max(0.0, m.explore_controller().reach_length_m() - m.explore_controller().tether_length_m());
    } else {
      r.tether_anchor_W = entry_W_;
    }
    r.battery_fraction = sim_->base().status().battery_fraction;
    return r;
  }

  // The world's step for the miniUGV (every UgvMissionSim::tick_s()).
  void step(double dt) {
    if (!sim_ || sim_->mission().done() || sim_->mission().wants_retraction()) return;
    sim_->step(dt);
    const Pose2& p = sim_->base().true_pose();
    tether_->move_to({p.x_m, p.y_m});
    deployments_.back().max_true_tether_m =
        std::max(deployments_.back().max_true_tether_m, settings_.uav.tether.entry_offset_m + tether_->length_m());
  }
  // Where the miniUGV will touch down if lowered from the UAV at p_W: the entry of the
  // nearest hidden space, its resting attitude there as its IMU reads it.
  void hang_over(const Eigen::Vector3d& p_W) {
    last_uav_W_ = p_W;
    if (sim_) return;
    const int k = nearest_space(p_W);
    if (k < 0 || k == touchdown_space_) return;  // called every UAV tick: once a space
    touchdown_space_ = k;
    const HiddenSpace& h = spec_.hidden_spaces[static_cast<std::size_t>(k)];
    const Eigen::Vector2d e = h.p_WE.head<2>() + 0.1 * Eigen::Vector2d(std::cos(h.entry_yaw_rad), std::sin(h.entry_yaw_rad));
    if (const auto rest = sensors_.resting_pose(e, h.entry_yaw_rad, h.floor_z_m + 0.3))
      touchdown_ = sensors_.imu(*rest, ImuOptions{}, seed_ + 17);
  }
  // Reeling in: a miniUGV away from the entry is dragged along its tether (it weighs
  // little and the line runs where it drove), so the line does not stretch.
  void set_reeling_in(bool on) { reeling_in_ = on; }
  // Closes the deployment still running when the simulation ends.
  void close() {
    if (!sim_) return;
    if (!sim_->mission().done()) sim_->mission().stop("the mission ended");
    deployments_.back().result = sim_->result(log_);
    deployments_.back().result.time_s = clock_.now_s() - deployments_.back().deployed_s;
    finished_.push_back(std::move(sim_));
  }
  // The true taut tether length from the winch (l_0 + floor part) while it works.
  [[nodiscard]] std::optional<double> true_required_m() const {
    if (!sim_ || !tether_ || reeling_in_) return std::nullopt;
    return settings_.uav.tether.entry_offset_m + tether_->length_m();
  }
  [[nodiscard]] const UgvMissionSim* active() const { return sim_.get(); }
  [[nodiscard]] std::vector<UgvDeployment>& deployments() { return deployments_; }
  [[nodiscard]] const std::vector<Eigen::Vector3d>& released_at() const { return released_at_; }

 private:
  [[nodiscard]] int nearest_space(const Eigen::Vector3d& p_W) const {
    int best = -1;
    double best_d = 3.0;  // the UAV's estimate of the opening is within a few metres, or nowhere
    for (std::size_t k = 0; k < spec_.hidden_spaces.size(); ++k) {
      const double d = (spec_.hidden_spaces[k].p_WE.head<2>() - p_W.head<2>()).norm();
      if (d < best_d) {
        best_d = d;
        best = static_cast<int>(k);
      }
    }
    return best;
  }

  const PlanningWorld& world_;
  const WorldSpec& spec_;
  const SensorSimulator& sensors_;
  const MissionRunSettings& settings_;
  const SimClock& clock_;
  TransitionLog& log_;
  std::uint64_t seed_;
  std::vector<UgvDeployment> deployments_;
  std::unique_ptr<UgvMissionSim> sim_;
  std::vector<std::unique_ptr<UgvMissionSim>> finished_;
  std::unique_ptr<TautTether> tether_;
  Eigen::Vector2d entry_W_ = Eigen::Vector2d::Zero();
  bool lonely_ = false;
  bool holding_ = false;
  bool reeling_in_ = false;
  ImuReading touchdown_;
  int touchdown_space_ = -1;  ///< the hidden space touchdown_ was read for
  Eigen::Vector3d last_uav_W_ = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> released_at_;
};

class MissionSimImpl {
 public:
  UavMission* uav = nullptr;
  SimFlightController* flight = nullptr;
  SimUgvLink* link = nullptr;
  tether::SimulatedWinch* winch = nullptr;
};

const UavMission& MissionSim::uav() const { return *impl_.uav; }
FlightState MissionSim::uav_truth() const { return impl_.flight->state(); }
const UgvMissionSim* MissionSim::ugv() const { return impl_.link->active(); }
double MissionSim::released_m() const { return impl_.winch->released_m(); }

MissionRunSettings mission_settings_for(const RobotDescription& uav, const RobotDescription& ugv,
                                        const MissionConfig& mission, const WorldSpec& world) {
  MissionRunSettings s;
  s.ugv.exploration = exploration_settings_for(ugv, mission);
  s.ugv.exploration.mission = mission;
  s.ugv.exploration.method = "cdos";
  s.ugv.exploration.record = true;
  // Tethered, the miniUGV drives no faster than the winch pays out (less a margin for
  // the controller), or it drags the line taut: the spool's 0.6 m/s against 2 m/s.
  const double spool_mps = s.uav.winch_control.limits.max_speed_mps;
  s.ugv.exploration.robot.max_velocity_mps = std::min(s.ugv.exploration.robot.max_velocity_mps, 0.8 * spool_mps);
  s.uav.landing = LandingZoneDetector::Options::for_robot(uav, &mission);
  s.uav_max_speed_mps = uav.limits.max_velocity_mps;
  s.uav_max_accel_mps2 = uav.limits.max_acceleration_mps2;
  s.uav_max_yaw_rate_radps = uav.limits.max_yaw_rate_radps;
  s.uav.search_area_m = {world.bounds_min_m.x() + 1.0, world.bounds_min_m.y() + 1.0,
                         world.bounds_max_m.x() - 1.0, world.bounds_max_m.y() - 1.0};
  return s;
}

MissionRunResult run_mission(const PlanningWorld& world, const RobotDescription& uav_robot,
                             const MissionRunSettings& settings_in, std::uint64_t seed, TransitionLog* log) {
  if (!world.spec)
    throw InputError(world.source.string(), "", "a world YAML (an OctoMap file names no hidden spaces)");
  const WorldSpec& spec = *world.spec;
  MissionRunSettings settings = settings_in;
  UavMissionOptions& uo = settings.uav;
  if (uo.openings.empty()) uo.openings = world_openings(spec);
  if (!spec.hidden_spaces.empty()) {
    uo.marker = marker_detector_options(spec.hidden_spaces.front().marker);
  }
  if (spec.drop_zone) uo.drop_zone_W = spec.drop_zone->center_m;
  uo.tether = settings.ugv.exploration.mission.tether;
  uo.validate("mission");

  const CameraSensor& marker_sensor = camera_for(uav_robot, false, "marker_camera");
  const CameraSensor& depth_sensor = camera_for(uav_robot, true, "depth_camera");
  const CameraModel marker_model = camera_model(marker_sensor, uav_robot.source);
  const CameraModel depth_model = camera_model(depth_sensor, uav_robot.source);

  SensorSimulator sensors(spec);
  SimClock clock;
  TransitionLog own_log;
  TransitionLog& transitions = log ? *log : own_log;

  // Home: the drop zone's edge if there is one, else the area's south-west corner.
  const Eigen::Vector2d home_xy = spec.drop_zone ? Eigen::Vector2d(spec.drop_zone->center_m + Eigen::Vector2d(spec.drop_zone->radius_m + 1.0, 0.0))
                                                 : Eigen::Vector2d(uo.search_area_m[0], uo.search_area_m[1]);
  double home_z = 0.0;
  if (const auto d = sensors.cast_ray({home_xy.x(), home_xy.y(), spec.bounds_max_m.z() - 0.01}, -Eigen::Vector3d::UnitZ(), 1e3))
    home_z = spec.bounds_max_m.z() - 0.01 - *d;
  SimFlightController flight(sensors, {home_xy.x(), home_xy.y(), home_z + settings.landed_height_m}, settings);
  SimUavCameras cameras(sensors, flight, marker_sensor, marker_model, depth_sensor, depth_model, seed);

  tether::SimulatedWinch::Options wo;
  wo.total_length_m = uo.tether.total_length_m;
  tether::SimulatedWinch winch(wo);
  SimUgvLink link(world, sensors, settings, clock, transitions, seed);

  // The flight planner: OMPL (RRT-Connect) in the world's OctoMap with FCL, for the UAV
  // alone and with the miniUGV hanging; a straight leg that the planner's own motion
  // check passes is taken as it is.
  const Aabb3 fence = default_uav_bounds(world);
  const auto map = CollisionMap::build(*world.tree, uav_map_options(world.spec, UnknownPolicy::kFree, fence));
  UavPlannerOptions po;
  po.geofence = fence;
  po.seed = seed;
  po.max_velocity_mps = settings.uav_max_speed_mps;
  seed_ompl_once(seed);
  const LoadedPlanRobot alone = load_plan_robot(PlanRobot::kUav, PlanRobotModel{uav_robot.source, false}, settings.ugv.exploration.mission, 0.0, "UAV");
  const LoadedPlanRobot loaded =
      load_plan_robot(PlanRobot::kUavWithUgv, PlanRobotModel{uav_robot.source, false}, settings.ugv.exploration.mission, 0.3, "UAV with miniUGV");
  UavPlanner plan_alone(map, alone.shape, po), plan_loaded(map, loaded.shape, po);
  auto si_alone = plan_alone.space_information(), si_loaded = plan_loaded.space_information();
  CollisionChecker truth_checker(map, alone.shape);
  int plans = 0;
  FlightPlanner planner = [&](const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                              bool carrying) -> std::optional<std::vector<Eigen::Vector3d>> {
    UavPlanner& p = carrying ? plan_loaded : plan_alone;
    auto& si = carrying ? si_loaded : si_alone;
    ++plans;
    Waypoint a, b;
    a.x_m = from.x(), a.y_m = from.y(), a.z_m = std::clamp(from.z(), fence.lo.z(), fence.hi.z());
    b.x_m = to.x(), b.y_m = to.y(), b.z_m = std::clamp(to.z(), fence.lo.z(), fence.hi.z());
    a.yaw_rad = b.yaw_rad = std::atan2(to.y() - from.y(), to.x() - from.x());
    ompl::base::State* sa = si->allocState();
    ompl::base::State* sb = si->allocState();
    p.to_ompl_state(a, sa);
    p.to_ompl_state(b, sb);
    const bool straight = si->isValid(sa) && si->isValid(sb) && si->checkMotion(sa, sb);
    si->freeState(sa);
    si->freeState(sb);
    if (straight) return std::vector<Eigen::Vector3d>{from, to};
    const UavPlan plan = p.plan(a, b);
    if (!plan.solved) return std::nullopt;
    std::vector<Eigen::Vector3d> out;
    for (const Waypoint& w : plan.states) out.push_back(w.position());
    out.back() = to;
    return out;
  };

  UavMission mission({flight, cameras, winch, link}, clock, planner, marker_model, depth_model, uo, &transitions);
  MissionSimImpl impl{&mission, &flight, &link, &winch};
  const MissionSim view(impl);

  MissionRunResult result;
  result.hidden_spaces_in_world = static_cast<int>(spec.hidden_spaces.size());
  for (const WorldObject& o : spec.objects) result.objects_in_world += o.hidden_space >= 0 ? 1 : 0;
  const tether::TensionModel tension_model = uo.winch_control.slack_estimator.tension;
  const auto ugv_every = static_cast<long>(std::lround(1.0 / settings.ugv.exploration.sensors.ir_rate_hz / kDt));
  const auto max_steps = static_cast<long>(std::ceil(settings.time_limit_s / kDt));
  bool over_tension = false;
  double tension_n = tension_model.hanging_weight_n;
  mission.start();
  long step = 0;
  for (; step < max_steps && !mission.done(); ++step) {
    clock.set(static_cast<double>(step) * kDt);
    if (step % kUavEvery == 0) {
      link.hang_over(flight.state().p_W);
      mission.tick();
      link.set_reeling_in(mission.state() == UavMissionState::kRetract);
    }
    if (step % ugv_every == 0) link.step(ugv_every * kDt);
    flight.step(kDt);
    // The tether: taut on the floor while the miniUGV works (its tension from the
    // stretch), the miniUGV's weight while it hangs, nothing while it is aboard.
    const auto required = link.true_required_m();
    for (int k = 0; k < static_cast<int>(std::lround(kDt / kWinchDt)); ++k) {
      const double l = winch.released_m();
      tension_n = required ? tension_model.tension_n(l, l - *required) + tension_model.hanging_weight_n
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
        truth_checker.in_collision(body_pose(fs))) {
      ++result.uav_collisions;
      ++result.collisions_in[std::string(to_string(mission.state()))];
      if (result.uav_collisions == 1) result.first_collision_W = fs.p_W;
    }
    if (step % 50 == 0) {
      MissionSample s;
      s.t_s = clock.now_s();
      s.p_W = fs.p_W;
      s.yaw_rad = fs.yaw_rad;
      s.state = std::string(to_string(mission.state()));
      s.battery = fs.battery_fraction;
      s.released_m = winch.released_m();
      s.required_m = required.value_or(0.0);
      s.tension_n = tension_n;
      s.ugv_battery = link.active() ? link.active()->base().status().battery_fraction : 1.0;
      result.samples.push_back(s);
    }
    if (settings.on_sample && step % 10 == 0) settings.on_sample(clock.now_s(), view);
  }
  if (!mission.done()) mission.stop("the simulation's time limit");
  link.close();
  result.outcome = mission.outcome();
  result.time_s = clock.now_s();
  result.visits = mission.visits();
  result.deployments = std::move(link.deployments());
  result.time_in_state = mission.time_in_state();
  result.flown_m = flight.flown_m();
  result.battery_left = flight.state().battery_fraction;
  result.leg_spacing_m = mission.leg_spacing_m();
  result.pattern_waypoints = mission.pattern().size();
  result.pattern_done = mission.pattern_done();
  result.first_pass_waypoints = mission.first_pass_waypoints();
  result.frames = mission.frames_processed();
  if (spec.drop_zone)
    for (const Eigen::Vector3d& p : link.released_at())
      result.objects_dropped += (p.head<2>() - spec.drop_zone->center_m).norm() <= spec.drop_zone->radius_m ? 1 : 0;
  result.transitions = transitions.all();
  return result;
}

}  // namespace ferret
