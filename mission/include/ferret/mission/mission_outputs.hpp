#pragma once
// What a mission run leaves behind (docs/mission.md): the summary on stdout and, in a
// directory, report.json, aerial.png, battery.png, tether.png, spaces/<name>/{G,O,G_O}.png,
// map.bt and mission.mcap. Written all or nothing (OutputSet). A run with one process a
// robot (docs/robots.md) leaves one such record a process, each of its own side.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

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

/// Whose record of a run: the whole simulated mission (`ferret mission`), or one
/// process's side of it: the simulated world's truth (`ferret sim-world`), the UAV's own
/// view (`ferret uav`: its mission, its state as its flight controller reported it, l_t
/// and tension as its winch measured them) or the miniUGV's (`ferret ugv`: each search
/// as its controller saw it). What a side cannot know is left out of its report, not
/// written as zero.
enum class RunSide { kMission, kWorld, kUav, kUgv };

struct RunOutputsInput {
  RunSide side = RunSide::kMission;
  const PlanningWorld* world = nullptr;  ///< aerial.png and map.bt (null: neither)
  std::filesystem::path world_path;      ///< as report.json names it
  std::uint64_t seed = 1;
  const UavMissionOptions* uav = nullptr;  ///< battery.png, tether.png (null: neither)
  double tether_total_length_m = 0.0;      ///< L
  /// Why the run ended before the mission did (a peer lost, the process stopped); empty
  /// when it did not. Not in `ferret mission`'s report.
  std::string ended_early;
  /// sim-world: each robot's end-of-run summary (JSON) as it said it, by role.
  std::map<std::string, std::string> robot_summaries;
};

/// The run's summary on stdout (`ferret mission`'s).
void print_mission_summary(const MissionRunResult& r);

/// Writes the run's files into `dir` (created; replaced only once all are written).
void write_mission_outputs(const std::filesystem::path& dir, const MissionOutputsInput& in,
                           const MissionRunResult& r);

/// Writes one side's record of a run into `dir` (as write_mission_outputs: created,
/// replaced only once all of it is written): report.json, and the pictures and the
/// MCAP log the side has the data for.
void write_run_outputs(const std::filesystem::path& dir, const RunOutputsInput& in,
                       const MissionRunResult& r);

}  // namespace ferret
