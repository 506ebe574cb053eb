#pragma once
// The simulated world as a process of its own (`ferret sim-world`, docs/robots.md "One
// process a robot"): it owns the world of `ferret mission` (the M100, its cameras, the
// winch, the tether, the hidden spaces and the miniUGV's base in each) and serves it to
// two robot processes, `ferret uav` and `ferret ugv`, each over a TCP message stream.
// The robots' controllers run in their processes against the same hardware interfaces
// as on the robots; the world keeps them in lockstep with its clock, and the robot link
// between them runs through its simulated network. Same seed, same outcome as
// `ferret mission --link messages`.
//
// The lockstep protocol (sim-world -> robot; the robot may make its hardware requests
// before it answers, each answered at once):
//   {"op": "start"}                                  -> {"op": "start_done", "state", "done"}
//   UAV  {"op": "tick", "t_s", "lonely"}             -> {"op": "tick_done", "state", "done"}
//   UAV  {"op": "link", "t_s"} + datagrams           -> {"op": "link_done"} + datagrams
//   UGV  {"op": "step", "t_s", "set_down", "attitude_rad": [roll, pitch]} + datagrams
//                                                    -> {"op": "step_done", "hold", "stopped"}
//   UGV  {"op": "report", "t_s"}                     -> {"op": "report_done"} + datagrams
//   {"op": "end", "t_s"}                             -> {"op": "end_done", ...its summary}
// Hardware requests: the UAV's the flight adapter protocol's ops (docs/flight_adapter.md)
// and the winch's (uav/remote_winch.hpp), and what the winch does to the miniUGV
// ("ugv_put_down" {"p_WE", "entry_yaw_rad"}, "ugv_lift", "ugv_release": each answers
// "lonely"); the miniUGV's the base protocol's (ugv/remote_ugv_base.hpp) and
// "ugv_deployment" (where it was set down, its seed and its map's extent).

#include <cstdint>
#include <string>

#include "ferret/core/transition_log.hpp"
#include "ferret/link/message_stream.hpp"
#include "ferret/sim/mission_run.hpp"

namespace ferret {

/// The protocol's version: robot processes of another version are refused at their hello.
inline constexpr int kSimWorldProtocol = 1;

struct SimWorldReport {
  MissionRunResult truth;  ///< what the world saw (collisions, tether, objects dropped, ...)
  std::string uav_summary, ugv_summary;  ///< the robots' own end-of-mission summaries (JSON)
  /// Why the run ended when a robot process was lost (the link::StreamError's message;
  /// the truth then runs up to that step and a summary it did not send is empty);
  /// empty when the run ended.
  std::string lost_peer;
};

/// Runs the mission against the two robot processes. The streams are connected and each
/// has said its hello (`robot_hello` with its role, answered by the caller). The link's
/// faults come from settings.link_channel (none: a perfect network). A robot process that
/// goes away or stops answering for `reply_timeout_ms` ends the run there, with
/// SimWorldReport::lost_peer saying so.
[[nodiscard]] SimWorldReport run_sim_world(const PlanningWorld& world,
                                           const RobotDescription& uav_robot,
                                           const MissionRunSettings& settings, std::uint64_t seed,
                                           link::MessageStream& uav, link::MessageStream& ugv,
                                           TransitionLog& log, int reply_timeout_ms = 60'000);

}  // namespace ferret
