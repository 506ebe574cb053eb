#pragma once
// The simulated world of a whole mission, shared by `ferret mission` (both controllers
// in this process, mission/mission_run.hpp), `ferret sim-world` (sim_world_server.hpp)
// and the reference flight adapter (sim_flight_adapter.hpp): the M100 as its position
// loop flies it, its rendered cameras, the winch and the true taut tether, the hidden
// spaces where the miniUGV is set down, and the truth checks (collisions, tension, l_t).
// The controllers plug into its loop through MissionControllers; only mission/ and sim/
// include this header.

#include <octomap/OcTree.h>

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/clock.hpp"
#include "ferret/core/transition_log.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/colour.hpp"
#include "ferret/planning/collision_checker.hpp"
#include "ferret/planning/collision_map.hpp"
#include "ferret/sim/fault_schedule.hpp"
#include "ferret/sim/mission_run.hpp"
#include "ferret/sim/sensor_sim.hpp"
#include "ferret/sim/ugv_mission_run.hpp"
#include "ferret/tether_model/simulated_winch.hpp"
#include "ferret/tether_model/taut_tether.hpp"
#include "ferret/uav/flight_controller.hpp"

namespace ferret::internal {

constexpr double kDt = 0.01;        // the simulation's step
constexpr int kUavEvery = 2;        // UAV control (and winch control) at 50 Hz
constexpr double kWinchDt = 0.001;  // spool physics: the tether is stiff

inline Pose3 body_pose(const FlightState& s) {
  return pose_from_xyz_rpy(s.p_W, 0.0, 0.0, s.yaw_rad);
}

// The M100 as its flight controller's position loop flies it: a point mass whose
// velocity follows a proportional command within speed and acceleration limits, the
// heading within the yaw-rate limit; landing descends until it rests on what is under it.
class SimFlightController final : public FlightController {
 public:
  SimFlightController(const SensorSimulator& world, const Eigen::Vector3d& start,
                      const MissionRunSettings& s)
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
  /// The adapter protocol's velocity set-point: held until the next command.
  void command_velocity(const Eigen::Vector3d& v_W, double yaw_rate_radps) {
    if (state_.on_ground) return;
    mode_ = Mode::kVelocity;
    velocity_sp_ = v_W;
    yaw_rate_sp_ = yaw_rate_radps;
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
      const double cap =
          std::min({speed_ > 0 ? speed_ : 0.5, settings_.uav_max_speed_mps, brake, 1.2 * d.norm()});
      v_cmd = d.norm() > 1e-9 ? Eigen::Vector3d(d.normalized() * cap) : Eigen::Vector3d::Zero();
    } else if (mode_ == Mode::kVelocity) {
      v_cmd = velocity_sp_;
      if (v_cmd.norm() > settings_.uav_max_speed_mps)
        v_cmd *= settings_.uav_max_speed_mps / v_cmd.norm();
      yaw_sp_ = state_.yaw_rad + std::clamp(yaw_rate_sp_, -settings_.uav_max_yaw_rate_radps,
                                            settings_.uav_max_yaw_rate_radps) *
                                     dt;
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
    state_.yaw_rad = std::remainder(state_.yaw_rad + std::clamp(dyaw, -max_dyaw, max_dyaw),
                                    2 * std::numbers::pi);
    // Battery: hover power plus a share growing with speed (the M100 with its payload).
    state_.battery_fraction =
        std::max(0.0, state_.battery_fraction -
                          dt * (1.0 + 0.15 * state_.v_W.norm() / settings_.uav_max_speed_mps) /
                              settings_.uav.flight_endurance_s * drain_factor_);
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
  /// Faults: the battery drains `factor` times as fast, or loses `fraction` at once.
  void set_battery_drain_factor(double factor) { drain_factor_ = factor; }
  void sag_battery(double fraction) {
    state_.battery_fraction = std::max(0.0, state_.battery_fraction - fraction);
  }
  [[nodiscard]] double ground_below() const {
    const auto d = world_.cast_ray(state_.p_W, -Eigen::Vector3d::UnitZ(), 100.0);
    return d ? state_.p_W.z() - *d : 0.0;
  }

 private:
  enum class Mode { kPosition, kLand, kVelocity };
  const SensorSimulator& world_;
  const MissionRunSettings& settings_;
  FlightState state_;
  Mode mode_ = Mode::kPosition;
  Eigen::Vector3d setpoint_ = Eigen::Vector3d::Zero();
  double yaw_sp_ = 0.0;
  double speed_ = 0.0;
  double flown_m_ = 0.0;
  double drain_factor_ = 1.0;
  Eigen::Vector3d velocity_sp_ = Eigen::Vector3d::Zero();
  double yaw_rate_sp_ = 0.0;
};

class SimUavCameras final : public UavCameras {
 public:
  SimUavCameras(const SensorSimulator& world, const SimFlightController& flight,
                const CameraSensor& marker, CameraModel marker_model, const CameraSensor& depth,
                CameraModel depth_model, std::uint64_t seed, bool render_markerless_frames)
      : world_(world),
        flight_(flight),
        marker_(marker),
        depth_(depth),
        marker_model_(std::move(marker_model)),
        depth_model_(std::move(depth_model)),
        seed_(seed),
        render_markerless_(render_markerless_frames) {}
  /// A camera blackout (sim/fault_plan.hpp): its frames come empty, as dropped frames.
  void set_blackout(bool marker, bool depth) {
    marker_blackout_ = marker;
    depth_blackout_ = depth;
  }
  CameraShot<GrayImage> marker_frame() override {
    const Pose3 X_WC = optical_pose(body_pose(flight_.state()), marker_);
    const std::uint64_t frame_seed =
        seed_ + 2 * frame_++;  // drawn either way: later frames keep their noise
    // No marker's quad in the image: a detector has nothing to find, so the frame is not
    // rendered (MissionRunSettings::render_markerless_frames).
    if (marker_blackout_ || (!render_markerless_ && !world_.markers_in_frame(marker_model_, X_WC)))
      return {GrayImage{}, X_WC};
    ++marker_frames_rendered_;
    return {world_.render_gray(marker_model_, X_WC, CameraFrameOptions{}, frame_seed), X_WC};
  }
  [[nodiscard]] std::uint64_t marker_frames_rendered() const { return marker_frames_rendered_; }
  CameraShot<DepthImageMm> depth_frame() override {
    const Pose3 X_WC = optical_pose(body_pose(flight_.state()), depth_);
    if (depth_blackout_) {
      ++frame_;  // drawn either way: later frames keep their noise
      return {DepthImageMm{}, X_WC};
    }
    return {world_.render_depth(depth_model_, X_WC, DepthFrameOptions{}, seed_ + 2 * frame_++ + 1),
            X_WC};
  }

 private:
  const SensorSimulator& world_;
  const SimFlightController& flight_;
  const CameraSensor& marker_;
  const CameraSensor& depth_;
  CameraModel marker_model_, depth_model_;
  std::uint64_t seed_;
  bool render_markerless_;
  std::uint64_t frame_ = 0;
  std::uint64_t marker_frames_rendered_ = 0;
  bool marker_blackout_ = false, depth_blackout_ = false;
};

// The hidden spaces as the miniUGV meets them: where it is set down, the truth there
// (the slice of the world, the object), its simulated base, the true taut tether.
class SimHiddenSpaces {
 public:
  SimHiddenSpaces(const PlanningWorld& world, const SensorSimulator& sensors,
                  const MissionRunSettings& settings, const SimClock& clock, TransitionLog& log,
                  std::uint64_t seed)
      : world_(world),
        spec_(*world.spec),
        sensors_(sensors),
        settings_(settings),
        clock_(clock),
        log_(log),
        seed_(seed) {}

  /// Where an in-process deployment's controller comes from (MissionAssembly's).
  void set_ugv_controllers(UgvControllerFactory make_controller) {
    ugv_controllers_ = std::move(make_controller);
  }
  /// The miniUGV set down at the entry of the hidden space nearest p_WE (within 3 m):
  /// its simulated base there and, in-process, its controller too (not started; from
  /// set_ugv_controllers()). Set down where no hidden space is, it searches nothing
  /// (lonely()).
  void put_down(const Eigen::Vector3d& p_WE, bool with_controller) {
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
          if (!h.interior_contains({c.x(), c.y(), h.floor_z_m + 0.03}))
            dep.truth.at({i, j}) = CellState::kOccupied;
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
          if (g.contains(c) && dep.truth.at(c) == CellState::kOccupied)
            dep.truth.at(c) = CellState::kFree;
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
    const Pose2 start_pose{start.x(), start.y(), h.entry_yaw_rad};
    const std::uint64_t seed = seed_ + 7919 * deployments_.size();
    start_pose_ = start_pose;
    deployment_seed_ = seed;
    sim_ = with_controller ? std::make_unique<UgvMissionSim>(dep.truth, start_pose, dep.object_W,
                                                             settings_.ugv, seed, ugv_controllers_)
                           : std::make_unique<UgvMissionSim>(dep.truth, start_pose, dep.object_W,
                                                             settings_.ugv, seed);
  }
  /// Aboard again (the winch reeled it in): the deployment's result is kept, and what
  /// the magnet holds comes along.
  /// Returns the deployment's index (none when it searched nothing).
  std::optional<std::size_t> lift() {
    std::optional<std::size_t> index;
    if (sim_) {
      deployments_.back().result = sim_->result(log_);
      deployments_.back().result.time_s = clock_.now_s() - deployments_.back().deployed_s;
      holding_ = sim_->base().object_held();
      index = deployments_.size() - 1;
      searched_[*index] = sim_.get();
      finished_.push_back(std::move(sim_));
    }
    tether_.reset();
    return index;
  }
  /// A deployment's result again, once its controller has heard over the robot link
  /// that it was lifted out, after the winch did it (its time stays the lift's).
  void update_result(std::size_t index) {
    const auto it = searched_.find(index);
    if (it == searched_.end()) return;
    UgvDeployment& d = deployments_[index];
    const double time_s = d.result.time_s;
    d.result = it->second->result(log_);
    d.result.time_s = time_s;
  }
  /// The EPM off under the UAV: what it held falls where the UAV is.
  void release_object() {
    if (!holding_) return;
    holding_ = false;
    released_at_.push_back(last_uav_W_);
  }
  // The world's step for the miniUGV (every UgvMissionSim::tick_s()).
  // `hold`: the controller holds (its link silent): the base stands, nothing ticks.
  void step(double dt, bool hold = false) {
    if (!sim_) return;
    if (sim_->has_controller() &&
        (sim_->controller().done() || sim_->controller().wants_retraction()))
      return;
    sim_->step(dt, hold);
    const Pose2& p = sim_->base().true_pose();
    tether_->move_to({p.x_m, p.y_m});
    deployments_.back().max_true_tether_m =
        std::max(deployments_.back().max_true_tether_m,
                 settings_.uav.tether.entry_offset_m + tether_->length_m());
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
    const Eigen::Vector2d e = h.p_WE.head<2>() + 0.1 * Eigen::Vector2d(std::cos(h.entry_yaw_rad),
                                                                       std::sin(h.entry_yaw_rad));
    if (const auto rest = sensors_.resting_pose(e, h.entry_yaw_rad, h.floor_z_m + 0.3))
      touchdown_ = sensors_.imu(*rest, ImuOptions{}, seed_ + 17);
  }
  // Reeling in: a miniUGV away from the entry is dragged along its tether (it weighs
  // little and the line runs where it drove), so the line does not stretch.
  void set_reeling_in(bool on) { reeling_in_ = on; }
  // Closes the deployment still running when the simulation ends.
  void close() {
    if (!sim_) return;
    if (sim_->has_controller() && !sim_->controller().done())
      sim_->controller().stop("the mission ended");
    deployments_.back().result = sim_->result(log_);
    deployments_.back().result.time_s = clock_.now_s() - deployments_.back().deployed_s;
    finished_.push_back(std::move(sim_));
  }
  // The true taut tether length from the winch (l_0 + floor part) while it works.
  [[nodiscard]] std::optional<double> true_required_m() const {
    if (!sim_ || !tether_ || reeling_in_) return std::nullopt;
    return settings_.uav.tether.entry_offset_m + tether_->length_m();
  }
  /// The base of the deployment under way, or of the last one lifted out (what a robot
  /// process's link endpoint still talks to aboard); null before the first.
  [[nodiscard]] SimUgvBase* last_base() {
    if (sim_) return &sim_->base();
    return finished_.empty() ? nullptr : &finished_.back()->base();
  }
  [[nodiscard]] const UgvMissionSim* active() const { return sim_.get(); }
  [[nodiscard]] UgvMissionSim* active() { return sim_.get(); }
  [[nodiscard]] bool lonely() const { return lonely_; }
  /// The deployment under way: where the miniUGV was set down, its search's seed, the
  /// extent of the world's slice (a robot process builds its controller from these).
  [[nodiscard]] const Pose2& start_pose() const { return start_pose_; }
  [[nodiscard]] std::uint64_t deployment_seed() const { return deployment_seed_; }
  [[nodiscard]] const GridGeometry& truth_geometry() const {
    return deployments_.back().truth.geometry;
  }
  [[nodiscard]] bool holding() const { return holding_; }
  [[nodiscard]] const ImuReading& touchdown() const { return touchdown_; }
  [[nodiscard]] const Eigen::Vector2d& entry_W() const { return entry_W_; }
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
  UgvControllerFactory ugv_controllers_;
  std::unique_ptr<UgvMissionSim> sim_;
  std::vector<std::unique_ptr<UgvMissionSim>> finished_;
  std::unique_ptr<TautTether> tether_;
  Eigen::Vector2d entry_W_ = Eigen::Vector2d::Zero();
  bool lonely_ = false;
  Pose2 start_pose_;
  std::uint64_t deployment_seed_ = 0;
  bool holding_ = false;
  bool reeling_in_ = false;
  ImuReading touchdown_;
  int touchdown_space_ = -1;                        ///< the hidden space touchdown_ was read for
  std::map<std::size_t, UgvMissionSim*> searched_;  ///< lifted deployments' controllers, by index
  Eigen::Vector3d last_uav_W_ = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> released_at_;
};

/// The world and its loop. The controllers plug in through MissionControllers (today
/// in this process, `ferret mission`), so the loop does not know where they run.
struct MissionControllers {
  std::function<void()> uav_tick;  ///< the UAV controller's tick at the clock's time
  std::function<bool()> uav_done;
  std::function<std::string()> uav_state;  ///< its state's name (samples, collisions)
  std::function<void()> ugv_tick;          ///< the miniUGV controller's tick, while it is set down
  /// True when a controller elsewhere (a robot process) is done or waits to be lifted
  /// out: the world does not step its base (as it does not for one in this process).
  std::function<bool()> ugv_stopped;
  /// The robot link's messages at the miniUGV's control rate, set down or not: those
  /// that arrived, before its step (true while the miniUGV holds, its link silent), and
  /// the ones it sends, after it. Empty: no link (one process).
  std::function<bool()> link_receive;
  std::function<void()> link_send;
  /// The miniUGV controller's state name when it runs elsewhere (a robot process);
  /// empty: the world asks the controller it steps, if any.
  std::function<std::string()> ugv_state;
};

class MissionWorld {
 public:
  /// Fills the UAV's options from the world (openings, marker, drop zone, tether) and
  /// validates them; throws InputError for a world without a world YAML's hidden spaces,
  /// a robot without its cameras, or bad options.
  MissionWorld(const PlanningWorld& world, const RobotDescription& uav_robot,
               const MissionRunSettings& settings, std::uint64_t seed, TransitionLog& log);
  MissionWorld(const MissionWorld&) = delete;
  MissionWorld& operator=(const MissionWorld&) = delete;

  [[nodiscard]] const MissionRunSettings& settings() const { return settings_; }
  [[nodiscard]] SimClock& clock() { return clock_; }
  [[nodiscard]] SimFlightController& flight() { return *flight_; }
  [[nodiscard]] SimUavCameras& cameras() { return *cameras_; }
  [[nodiscard]] tether::SimulatedWinch& winch() { return *winch_; }
  [[nodiscard]] SimHiddenSpaces& spaces() { return *spaces_; }
  [[nodiscard]] const CameraModel& marker_model() const { return marker_model_; }
  [[nodiscard]] const CameraModel& depth_model() const { return depth_model_; }
  [[nodiscard]] const SensorSimulator& sensors() const { return sensors_; }

  /// Runs until the UAV's controller is done or the simulation's time limit; the
  /// hook (every 0.1 s) sees the world. Fills the truth side of result().
  void run(const MissionControllers& controllers, const std::function<void(double t_s)>& on_sample);
  [[nodiscard]] MissionRunResult& result() { return result_; }
  /// The settings' fault plan on the clock (null without faults): the link's ends ask
  /// it for their impairment.
  [[nodiscard]] const FaultSchedule* faults() const { return faults_ ? &*faults_ : nullptr; }
  /// The mission's end for the invariants: whether the UAV's controller ended (not the
  /// simulation's bound), and, should the miniUGV still be in a hidden space, the reason
  /// the mission recorded for leaving it (empty: none). Fills result()'s violations.
  void finish_invariants(bool ended, const std::string& ugv_left_reason);

 private:
  const PlanningWorld& world_;
  MissionRunSettings settings_;
  SensorSimulator sensors_;
  SimClock clock_;
  CameraModel marker_model_, depth_model_;
  std::unique_ptr<SimFlightController> flight_;
  std::unique_ptr<SimUavCameras> cameras_;
  std::unique_ptr<tether::SimulatedWinch> winch_;
  std::unique_ptr<SimHiddenSpaces> spaces_;
  std::unique_ptr<CollisionChecker> truth_checker_;
  std::shared_ptr<const CollisionMap> map_;
  MissionRunResult result_;
  InvariantMonitor invariants_;
  std::optional<FaultSchedule> faults_;
  /// Applies the faults acting at the step's time to the simulated backends.
  void inject_faults(const std::string& uav_state, const std::string& ugv_state);
  InvariantSample last_sample_;
};

}  // namespace ferret::internal
