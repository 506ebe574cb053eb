#pragma once
// The one place the mission's controllers are put together (docs/architecture.md): from
// the loaded mission document and the hardware interfaces of a backend set (the
// in-process simulation, the sim-world client, the robots' own devices), the UAV's
// mission controller with its options filled from the world and checked, its cameras'
// models from its URDF, its flight planner and its transition log, and the miniUGV's
// mission controller for each deployment. `ferret mission`, `ferret uav`, `ferret ugv`
// (against sim-world or on the robots) build their controllers here; a new backend or
// telemetry sink is added here once.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "ferret/core/clock.hpp"
#include "ferret/core/transition_log.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/sim/mission_run.hpp"
#include "ferret/sim/ugv_mission_run.hpp"
#include "ferret/uav/flight_planner.hpp"
#include "ferret/uav/uav_mission.hpp"
#include "ferret/ugv/mini_ugv_mission.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {

/// The controller's options for a deployment with `seed` (the search's own, derived
/// from it); `truth` only places the oracle's object of an empty space out of reach.
[[nodiscard]] UgvMissionOptions ugv_mission_options(const UgvMissionRunSettings& settings,
                                                    std::uint64_t seed,
                                                    const std::optional<Eigen::Vector2d>& object_W,
                                                    const GridGeometry& truth);

/// A deployment's miniUGV mission controller as the simulated world steps it
/// (sim/ugv_mission_run.hpp): the world calls it through SimUgvController, the mission
/// module reaches the controller itself (ugv_mission_of).
class SimMiniUgvMission final : public SimUgvController {
 public:
  explicit SimMiniUgvMission(std::unique_ptr<MiniUgvMission> mission)
      : mission_(std::move(mission)) {}
  [[nodiscard]] MiniUgvMission& mission() { return *mission_; }
  [[nodiscard]] const MiniUgvMission& mission() const { return *mission_; }

  void start() override { mission_->start(); }
  void tick() override { mission_->tick(); }
  void stop(const std::string& reason) override { mission_->stop(reason); }
  [[nodiscard]] UgvMissionState state() const override { return mission_->state(); }
  [[nodiscard]] bool done() const override { return mission_->done(); }
  [[nodiscard]] bool wants_retraction() const override { return mission_->wants_retraction(); }
  [[nodiscard]] double tether_length_m() const override {
    return mission_->started() ? mission_->explore_controller().tether_length_m() : 0.0;
  }
  void report(UgvMissionRunResult& result) const override;

 private:
  std::unique_ptr<MiniUgvMission> mission_;
};

/// The miniUGV mission controller of a simulated deployment whose controller came from
/// MissionAssembly::ugv_controllers. Throws std::logic_error for one without (the base
/// alone) or with another controller.
[[nodiscard]] MiniUgvMission& ugv_mission_of(UgvMissionSim& sim);
[[nodiscard]] const MiniUgvMission& ugv_mission_of(const UgvMissionSim& sim);

/// The UAV's hardware interfaces as a backend set provides them.
using UavBackends = UavMission::Hardware;

class MissionAssembly {
 public:
  /// Fills the UAV's options from the world (openings, marker, drop zone, tether) over
  /// `settings.uav` and validates them (InputError naming `source`), takes its cameras'
  /// models from `uav_robot` (InputError without a marker or a depth camera) and builds
  /// its flight planner on the world's collision map (OMPL seeded with `seed`). `world`
  /// must outlive the assembly and the controllers it builds.
  MissionAssembly(const PlanningWorld& world, const RobotDescription& uav_robot,
                  const MissionRunSettings& settings, std::uint64_t seed,
                  const std::string& source);

  /// The UAV's options the controller runs with (filled from the world).
  [[nodiscard]] const UavMissionOptions& uav_options() const { return uav_options_; }

  /// The UAV's mission controller on `hardware` and `clock`, not started; `log` (may be
  /// null) receives its transitions.
  [[nodiscard]] std::unique_ptr<UavMission> uav_mission(const UavBackends& hardware,
                                                        const Clock& clock,
                                                        TransitionLog* log) const;

  /// The miniUGV's mission controller for one deployment, not started: on `base` and
  /// `clock`, its maps over `map`, its search seeded from `seed`; `object_W` is the
  /// oracle's object (in a simulation only; none: an empty space or a real one).
  [[nodiscard]] static std::unique_ptr<MiniUgvMission> ugv_mission(
      const UgvMissionRunSettings& settings, UgvBase& base, const Clock& clock,
      const GridGeometry& map, std::uint64_t seed, const std::optional<Eigen::Vector2d>& object_W,
      TransitionLog* log);

  /// The same as a factory for the simulated world (UgvMissionSim, SimHiddenSpaces):
  /// each deployment's controller on `clock` with `settings` (copied), its transitions
  /// to `log` (may be null). `clock` must outlive the factory.
  [[nodiscard]] static UgvControllerFactory ugv_controllers(const UgvMissionRunSettings& settings,
                                                            const Clock& clock, TransitionLog* log);

 private:
  UavMissionOptions uav_options_;
  CameraModel marker_model_, depth_model_;
  FlightPlanner planner_;
};

}  // namespace ferret
