#pragma once
// The mission YAML, parsed once: every section read from the one document by the reader
// beside the component that owns it (docs/configuration.md):
//  - the common sections (curiosity, object_search, tether, ugv_limits, uav_limits,
//    roles): MissionConfig, planning/mission_config.hpp;
//  - the robots' backends (ugv.base, uav.winch, uav.flight_controller): RobotBackends,
//    sim/robot_backends.hpp;
//  - the UAV mission's keys in `uav`: uav/uav_mission_config.hpp;
//  - the miniUGV mission's keys in `ugv` (its search's under `ugv.explore`):
//    ugv/ugv_mission_config.hpp;
//  - what a simulated run breaks on purpose, `faults`: sim/fault_plan.hpp.
// Commands load it once and take each section from here.

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <set>
#include <string>

#include "ferret/planning/mission_config.hpp"
#include "ferret/sim/fault_plan.hpp"
#include "ferret/sim/robot_backends.hpp"
#include "ferret/sim/ugv_mission_run.hpp"
#include "ferret/uav/uav_mission.hpp"
#include "ferret/ugv/mini_ugv_mission_options.hpp"

namespace ferret {

struct MissionDocument {
  MissionConfig config;    ///< the common sections, with their provenance
  RobotBackends backends;  ///< all sim without a file
  /// The UAV mission's keys of the file over the defaults (the tether from `config`),
  /// and the keys the file set: what `ferret config --dump` shows.
  UavMissionOptions uav_mission;
  std::set<std::string> uav_mission_given;

  /// Reads the file's UAV mission keys over `options` (what the world set, such as the
  /// search area from its bounds): the file's keys win, the rest keep their values.
  /// InputError as read_uav_mission_options.
  void apply_uav_mission(UavMissionOptions& options) const;

  /// The faults a simulated run injects (docs/safety.md); empty without a `faults` key.
  FaultPlan faults;

  /// The miniUGV mission's keys of the file over the defaults, and the keys the file set
  /// (its search's as `explore.KEY`): what `ferret config --dump` shows.
  UgvMissionOptions ugv_mission;
  std::set<std::string> ugv_mission_given;

  /// The miniUGV mission's keys of the file into a simulated deployment's settings: the
  /// mission's into `settings.ugv`, the search's tuning into `settings.exploration` (the
  /// controller's search takes it from there, explore_options). What the file leaves out
  /// keeps its value (what the robot and the winch set: the line's catch, the stall time).
  void apply_ugv_mission(UgvMissionRunSettings& settings) const;

  /// The document's `uav` and `ugv` sections (undefined without one) and the file it
  /// came from.
  YAML::Node uav_section;
  YAML::Node ugv_section;
  std::string source;
};

/// Reads every section of a parsed mission YAML (`root`; an empty document means all
/// defaults): the common sections first, then the backends, then the UAV mission's keys,
/// then the miniUGV mission's.
/// Throws InputError naming `source` and the field, as each section's reader does.
[[nodiscard]] MissionDocument mission_document_from_yaml(const YAML::Node& root,
                                                         const std::string& source);
/// The states a fault may start on (`on: uav.<state>` / `ugv.<state>`): the two mission
/// controllers' state names, and the miniUGV's `link_hold` (its watchdog holding).
[[nodiscard]] const FaultStates& mission_fault_states();
/// A `faults:` list from a file of its own (`ferret mission --faults`): the file's
/// `faults` key, InputError naming the file for anything else.
[[nodiscard]] FaultPlan load_fault_plan(const std::filesystem::path& path);

/// The same from a mission YAML file, loaded once.
[[nodiscard]] MissionDocument load_mission_document(const std::filesystem::path& path);

}  // namespace ferret
