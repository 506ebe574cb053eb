#pragma once
// The miniUGV in a simulated hidden space: its SimUgvBase on the truth, stepped by its
// owner, with the controller a factory gives it (MissionAssembly's, in mission/; or
// none, when a robot process drives the base). The settings and the result of a
// deployment. Only the simulation knows where the object really is.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/clock.hpp"
#include "ferret/core/transition_log.hpp"
#include "ferret/sim/exploration_settings.hpp"
#include "ferret/sim/sim_ugv_base.hpp"
#include "ferret/ugv/mini_ugv_mission_options.hpp"

namespace ferret {

struct UgvMissionRunSettings {
  /// Method, sensors, robot, mission (ExplorationSettings::time_limit_s is not used:
  /// the mission's explore_timeout_s bounds the search).
  ExplorationSettings exploration;
  UgvMissionOptions ugv;  ///< its `explore` is filled from `exploration`, but for its `planner`
  SimUgvOptions base;     ///< its `robot` is filled from `exploration`
  double retract_time_s = 10.0;  ///< the winch lifting the robot out of the hidden space
  /// The controller's maps: a window of this size (x, y, m) centred on the start, as a
  /// robot that knows nothing of the space is configured; none: the truth map's own
  /// extent (the paper's experiment, where the map is given).
  std::optional<Eigen::Vector2d> map_window_m;
  double time_limit_s = 3600.0;  ///< the simulation's own bound (a mission that never ends)
};

struct UgvMissionRunResult {
  UgvMissionOutcome outcome = UgvMissionOutcome::kNone;
  UgvMissionState final_state = UgvMissionState::kIdle;
  double time_s = 0.0;
  double path_m = 0.0;
  double battery_left = 1.0;
  bool object_held = false;  ///< the truth: the object on the magnet at the end
  /// Where O confirmed the object, and whether that was where it is (the truth).
  std::optional<Eigen::Vector2d> found_W;
  bool found_right = false;
  int grasp_attempts = 0;
  int decisions = 0;  ///< the search's decisions (goals chosen)
  /// The simulated base's body contacts with the truth (SimUgvBase::body_contacts) and
  /// the deepest, beyond the truth's half-cell raster.
  int body_contacts = 0;
  double deepest_contact_m = 0.0;
  double max_tether_m = 0.0;  ///< the controller's taut tether model, longest over the run
  UgvMissionState max_tether_state = UgvMissionState::kIdle;  ///< the state it was in then
  std::vector<Transition> transitions;
  std::vector<Pose2> trajectory;  ///< one pose a tick
  std::shared_ptr<const IrGrid> grid;
  std::shared_ptr<const ObjectMap> objects;
};

/// The miniUGV's controller as the simulated world steps it: what the world calls on it
/// and reads from it. The simulation knows no controller; mission/ implements this over
/// the miniUGV's mission controller (MissionAssembly::ugv_controllers).
class SimUgvController {
 public:
  virtual ~SimUgvController() = default;
  /// At the entry: the search begins.
  virtual void start() = 0;
  /// One control step at the clock's time.
  virtual void tick() = 0;
  /// Ends the mission (the simulation's end, or the UAV's).
  virtual void stop(const std::string& reason) = 0;
  [[nodiscard]] virtual UgvMissionState state() const = 0;
  [[nodiscard]] virtual bool done() const = 0;
  /// Waiting at the entry to be lifted out: the world no longer steps the base.
  [[nodiscard]] virtual bool wants_retraction() const = 0;
  /// The controller's taut tether model, now (m).
  [[nodiscard]] virtual double tether_length_m() const = 0;
  /// Fills the controller's part of a result: outcome, final state, where it found the
  /// object, grasp attempts, decisions, its maps.
  virtual void report(UgvMissionRunResult& result) const = 0;
};

/// The miniUGV's controller for a deployment, built elsewhere (MissionAssembly, in
/// mission/): on `base`, its maps over `map`, its search seeded from `seed`; `object_W`
/// the oracle's object (none: an empty space).
using UgvControllerFactory = std::function<std::unique_ptr<SimUgvController>(
    SimUgvBase& base, const GridGeometry& map, std::uint64_t seed,
    const std::optional<Eigen::Vector2d>& object_W)>;

/// One miniUGV mission in a simulated hidden space, stepped by its owner: the
/// harness run_ugv_mission (mission/ugv_mission_run.hpp) uses, and the whole mission's
/// simulation (sim/mission_world.hpp), which steps it on the clock it shares with the
/// UAV. Holds the truth (the map, the object); the controller inside sees only the
/// simulated base.
class UgvMissionSim {
 public:
  /// `truth` (the simulator keeps a reference) must outlive the simulation; the
  /// controller comes from `make_controller`. Throws std::invalid_argument as
  /// run_exploration for a bad start or method.
  UgvMissionSim(const OccupancyMap2D& truth, const Pose2& start,
                const std::optional<Eigen::Vector2d>& object_W,
                const UgvMissionRunSettings& settings, std::uint64_t seed,
                const UgvControllerFactory& make_controller);
  /// The simulated base alone: its controller runs elsewhere (a robot process) and
  /// drives it through its UgvBase.
  UgvMissionSim(const OccupancyMap2D& truth, const Pose2& start,
                const std::optional<Eigen::Vector2d>& object_W,
                const UgvMissionRunSettings& settings, std::uint64_t seed);
  ~UgvMissionSim();
  UgvMissionSim(const UgvMissionSim&) = delete;
  UgvMissionSim& operator=(const UgvMissionSim&) = delete;

  void start() { controller_->start(); }
  /// The controller's tick at the clock's time (when it has one), then the robot moves
  /// by `dt_s`. `hold`: the controller does not tick and the wheels stop (the robot
  /// link's watchdog).
  void step(double dt_s, bool hold = false);
  [[nodiscard]] bool has_controller() const { return controller_ != nullptr; }
  /// The control period (the IR rate).
  [[nodiscard]] double tick_s() const { return tick_s_; }
  /// The controller (has_controller()).
  [[nodiscard]] SimUgvController& controller() { return *controller_; }
  [[nodiscard]] const SimUgvController& controller() const { return *controller_; }
  [[nodiscard]] const SimUgvBase& base() const { return *base_; }
  [[nodiscard]] SimUgvBase& base() { return *base_; }
  /// The result so far (outcome kNone while running); `log` fills transitions.
  [[nodiscard]] UgvMissionRunResult result(const TransitionLog& log) const;

 private:
  std::optional<Eigen::Vector2d> object_W_;
  double object_radius_m_ = 0.0;
  bool record_ = false;
  double tick_s_ = 0.05;
  std::unique_ptr<HiddenSpaceSim> sim_;
  std::unique_ptr<SimUgvBase> base_;
  std::unique_ptr<SimUgvController> controller_;
  std::vector<Pose2> trajectory_;
  double max_tether_m_ = 0.0;
  UgvMissionState max_tether_state_ = UgvMissionState::kIdle;
};

/// The controller's map for a mission from `start`: the settings' window, or the truth's extent.
[[nodiscard]] GridGeometry ugv_mission_map(const GridGeometry& truth, const Pose2& start,
                                           const UgvMissionRunSettings& settings);

}  // namespace ferret
