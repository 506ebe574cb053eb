#pragma once
// `ferret uav` and `ferret ugv` on their robots (docs/robots.md, "On the robots"): the
// same mission controllers as under `ferret sim-world`, on the machine's steady clock,
// against the backends the mission YAML names `hw`, and talking to each other over the
// robot link on UDP.

#include <cstdint>
#include <string>

#include "ferret/mission/mission_setup.hpp"

namespace ferret {

class TransitionLog;
class UavMission;

struct RobotOnHardwareOptions {
  std::string mission_path;  ///< the mission YAML the backends came from (for messages)
  std::string link_bind;     ///< this robot's link address (empty: its default)
  std::string link_peer;     ///< the other robot's (empty: its default)
  double duration_s = 0.0;   ///< stop after this long (0: when done or interrupted)
  std::uint64_t seed = 1;    ///< the planners' and searches' tie-breaks
  bool quiet = false;
  std::string out;  ///< the directory for the robot's record of the run (empty: none)
};

/// The miniUGV: HwUgvBase, a MiniUgvMission for each search the UAV asks for (from
/// where the winch set the robot down), telemetry at 20 Hz, the watchdog's hold. Runs
/// until interrupted or the duration is over; prints each search's outcome.
void run_ugv_on_hardware(const MissionSetup& setup, const RobotOnHardwareOptions& o);

/// The UAV: the flight adapter at uav.flight_controller.address, the winch of uav.winch,
/// the miniUGV over the link; the mission from take-off to its end at 50 Hz. Prints the
/// outcome as the simulated `ferret uav` does.
void run_uav_on_hardware(const MissionSetup& setup, const RobotOnHardwareOptions& o);

/// Prints each transition on stderr as it happens (unless quiet): a robot process's log.
void print_transitions(TransitionLog& log, bool quiet);

/// Prints the UAV mission's outcome (the summary both `ferret uav` modes end with);
/// returns the objects retrieved.
int print_uav_outcome(const UavMission& mission, double time_s);

/// Throws InputError(mission_path, "<field>.backend", ...) when the robot's interfaces
/// are neither all `sim` (served by ferret sim-world) nor all `hw` (its own loop).
/// Returns true for all `hw`.
[[nodiscard]] bool uav_on_hardware(const MissionSetup& setup, const std::string& mission_path);
[[nodiscard]] bool ugv_on_hardware(const MissionSetup& setup);

}  // namespace ferret
