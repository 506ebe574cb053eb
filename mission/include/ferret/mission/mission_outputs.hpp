#pragma once
// What a mission run leaves behind (docs/mission.md): the summary on stdout and, in a
// directory, report.json, aerial.png, battery.png, tether.png, spaces/<name>/{G,O,G_O}.png,
// map.bt and mission.mcap. Written all or nothing (OutputSet).

#include <cstdint>
#include <filesystem>

#include "ferret/planning/planning_world.hpp"
#include "ferret/sim/mission_run.hpp"

namespace ferret {

/// What the outputs say besides the run's result.
struct MissionOutputsInput {
  const PlanningWorld& world;        ///< the world flown (its OctoMap: aerial.png, map.bt)
  std::filesystem::path world_path;  ///< as report.json names it
  std::uint64_t seed = 1;
  const UavMissionOptions& uav;        ///< the UAV's options (battery reserve, winch band)
  double tether_total_length_m = 0.0;  ///< L
};

/// The run's summary on stdout (`ferret mission`'s).
void print_mission_summary(const MissionRunResult& r);

/// Writes the run's files into `dir` (created; replaced only once all are written).
void write_mission_outputs(const std::filesystem::path& dir, const MissionOutputsInput& in,
                           const MissionRunResult& r);

}  // namespace ferret
