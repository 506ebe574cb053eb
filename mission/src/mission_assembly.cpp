#include "ferret/mission/mission_assembly.hpp"

#include <stdexcept>

#include "ferret/core/error.hpp"
#include "ferret/mission/exploration_run.hpp"
#include "ferret/mission/robot_records.hpp"
#include "ferret/sim/sensor_sim.hpp"

namespace ferret {

UgvMissionOptions ugv_mission_options(const UgvMissionRunSettings& settings, std::uint64_t seed,
                                      const std::optional<Eigen::Vector2d>& object_W,
                                      const GridGeometry& truth) {
  // An empty hidden space: the object far outside the map (the oracle's option only).
  const Eigen::Vector2d far_W(truth.origin_x_m - 1e6, truth.origin_y_m - 1e6);
  UgvMissionOptions options = settings.ugv;
  options.explore = explore_options(settings.exploration, seed, object_W.value_or(far_W));
  options.explore.planner = settings.ugv.explore.planner;  // grid or the OMPL frontier planner
  if (!object_W) options.explore.oracle_object_W.reset();
  return options;
}

MissionAssembly::MissionAssembly(const PlanningWorld& world, const RobotDescription& uav_robot,
                                 const MissionRunSettings& settings, std::uint64_t seed,
                                 const std::string& source)
    : uav_options_(settings.uav) {
  if (!world.spec)
    throw InputError(world.source.string(), "",
                     "a world YAML (an OctoMap file names no hidden spaces)");
  fill_uav_mission_from_world(uav_options_, *world.spec, settings.ugv.exploration.mission);
  uav_options_.validate(source);
  marker_model_ = camera_model(camera_for(uav_robot, false, "marker_camera"), uav_robot.source);
  depth_model_ = camera_model(camera_for(uav_robot, true, "depth_camera"), uav_robot.source);
  planner_ = make_flight_planner(world, uav_robot, settings.ugv.exploration.mission,
                                 settings.uav_max_speed_mps, seed);
}

std::unique_ptr<UavMission> MissionAssembly::uav_mission(const UavBackends& hardware,
                                                         const Clock& clock,
                                                         TransitionLog* log) const {
  return std::make_unique<UavMission>(hardware, clock, planner_, marker_model_, depth_model_,
                                      uav_options_, log);
}

std::unique_ptr<MiniUgvMission> MissionAssembly::ugv_mission(
    const UgvMissionRunSettings& settings, UgvBase& base, const Clock& clock,
    const GridGeometry& map, std::uint64_t seed, const std::optional<Eigen::Vector2d>& object_W,
    TransitionLog* log) {
  return std::make_unique<MiniUgvMission>(base, clock, map,
                                          ugv_mission_options(settings, seed, object_W, map), log);
}

void SimMiniUgvMission::report(UgvMissionRunResult& result) const {
  report_ugv_controller(*mission_, result);
}

namespace {
[[noreturn]] void no_ugv_mission() {
  throw std::logic_error("the simulated deployment has no miniUGV mission controller");
}
}  // namespace

MiniUgvMission& ugv_mission_of(UgvMissionSim& sim) {
  auto* c = sim.has_controller() ? dynamic_cast<SimMiniUgvMission*>(&sim.controller()) : nullptr;
  if (!c) no_ugv_mission();
  return c->mission();
}

const MiniUgvMission& ugv_mission_of(const UgvMissionSim& sim) {
  const auto* c =
      sim.has_controller() ? dynamic_cast<const SimMiniUgvMission*>(&sim.controller()) : nullptr;
  if (!c) no_ugv_mission();
  return c->mission();
}

UgvControllerFactory MissionAssembly::ugv_controllers(const UgvMissionRunSettings& settings,
                                                      const Clock& clock, TransitionLog* log) {
  return [settings, &clock, log](SimUgvBase& base, const GridGeometry& map, std::uint64_t seed,
                                 const std::optional<Eigen::Vector2d>& object_W) {
    return std::make_unique<SimMiniUgvMission>(
        ugv_mission(settings, base, clock, map, seed, object_W, log));
  };
}

}  // namespace ferret
