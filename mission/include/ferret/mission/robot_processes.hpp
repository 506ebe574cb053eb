#pragma once
// One process a robot (docs/robots.md, "One process a robot"): `ferret sim-world` serves
// the simulated world to a `ferret uav` and a `ferret ugv` process, which run their
// mission controllers against it in lockstep (the client side of sim/sim_world_server.hpp's
// protocol), or, with the mission YAML's backends hw, on the robots' own hardware
// (robots_on_hardware.hpp). Each prints its summary on stdout and, with --out, writes its
// own record of the run (robot_records.hpp).

#include <cstdint>
#include <string>

#include "ferret/mission/mission_setup.hpp"

namespace ferret {

/// Where `ferret sim-world` listens and the robots look for it unless told otherwise.
inline constexpr const char* kDefaultSimWorld = "127.0.0.1:47830";

struct RobotProcessOptions {
  MissionSetupOptions setup;
  std::uint64_t seed = 1;
  std::string address = kDefaultSimWorld;  ///< sim-world: --listen; robots: --sim-world
  double link_loss = 0.0, link_reorder = 0.0;
  bool render_every_frame = false;
  bool quiet = false;
  // A robot on its hardware (docs/robots.md, "On the robots"):
  std::string link_bind, link_peer;
  double duration_s = 0.0;
  bool sim_world_given = false;  ///< --sim-world on the command line
  /// --out: the directory for the process's record of the run (mission_outputs.hpp's
  /// RunSide); empty: the summary only.
  std::string out;
};

/// The world: waits for both robots' hello, runs the mission with them, prints what the
/// world saw and the robots' summaries. Throws link::StreamError when a robot goes away
/// (after writing its record of the run so far).
void run_sim_world_process(const RobotProcessOptions& o);
/// The UAV's mission controller, against sim-world or on its hardware.
void run_uav_process(const RobotProcessOptions& o);
/// The miniUGV's, against sim-world or on its hardware.
void run_ugv_process(const RobotProcessOptions& o);

}  // namespace ferret
