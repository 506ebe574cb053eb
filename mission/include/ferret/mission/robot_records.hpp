#pragma once
// Each robot process's own record of its run (docs/robots.md, "What each process
// writes"): what the robot knew, as mission_outputs.hpp's RunSide kUav and kUgv write it.
// The UAV's comes from its mission and from its flight controller's and winch's readings
// as the mission made them (recorded on their way, no extra request); the miniUGV's from
// its search controllers.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/transition_log.hpp"
#include "ferret/mission/mission_outputs.hpp"
#include "ferret/mission/mission_setup.hpp"
#include "ferret/sim/mission_run.hpp"
#include "ferret/tether_model/winch.hpp"
#include "ferret/uav/flight_controller.hpp"
#include "ferret/uav/uav_mission.hpp"
#include "ferret/ugv/mini_ugv_mission.hpp"

namespace ferret {

/// Hand flight() and winch() to the UAV's mission in place of the devices; call
/// after_tick() after each of its ticks.
class UavRunRecorder {
 public:
  UavRunRecorder(FlightController& flight, tether::Winch& winch);
  ~UavRunRecorder();
  UavRunRecorder(const UavRunRecorder&) = delete;
  UavRunRecorder& operator=(const UavRunRecorder&) = delete;

  [[nodiscard]] FlightController& flight();
  [[nodiscard]] tether::Winch& winch();
  /// A sample every 0.5 s (as `ferret mission`'s), the distance flown, l_t and tension.
  void after_tick(double t_s, const UavMission& mission);
  /// The record at `t_s`; `mission` null when it never started.
  [[nodiscard]] MissionRunResult result(const UavMission* mission, double t_s,
                                        const TransitionLog& log) const;

 private:
  class RecordedFlight;
  class RecordedWinch;
  std::unique_ptr<RecordedFlight> flight_;
  std::unique_ptr<RecordedWinch> winch_;
  std::vector<MissionSample> samples_;
  std::optional<Eigen::Vector3d> last_p_W_;
  double flown_m_ = 0.0, max_released_m_ = 0.0, max_tension_n_ = 0.0, next_sample_s_ = 0.0;
};

/// The miniUGV's searches as its controllers saw them.
class UgvRunRecorder {
 public:
  /// A search began at `t_s` with `mission` (kept by the caller for the run).
  void started(double t_s, const MiniUgvMission& mission);
  /// After a control step: the search's end time and its tether model's longest.
  void after_tick(double t_s);
  [[nodiscard]] MissionRunResult result(double t_s, const TransitionLog& log) const;

 private:
  struct Search {
    const MiniUgvMission* mission;
    double started_s;
    std::optional<double> ended_s;
    double max_tether_m = 0.0;
  };
  std::vector<Search> searches_;
};

/// Checks a process's --out before its run (InputError, exit 2: nothing is run, nothing
/// written); empty: no record asked for.
void check_record_target(const std::string& out);

/// Runs a robot's loop; when it fails on its peer (link::StreamError: lost, silent, or a
/// message it cannot follow), calls `record` with why before the error goes on: the
/// record of a failed run is the one an engineer most wants.
void recording_failures(const std::function<void()>& run,
                        const std::function<void(const std::string& why)>& record);

/// One process's side of a run: whose, its seed, why it ended early ("" it did not).
[[nodiscard]] RunOutputsInput robot_side(RunSide side, std::uint64_t seed, std::string ended_early);

/// Writes a process's record of its run into `out` (nothing when empty) and says so on
/// stdout.
void write_robot_record(const std::string& out, RunOutputsInput in, const MissionSetup& setup,
                        const MissionRunResult& r);

/// What a miniUGV search controller says of its search (its outcome, state, grasps,
/// decisions, maps), into `result`; the simulation's and the UGV process's record alike.
void report_ugv_controller(const MiniUgvMission& m, UgvMissionRunResult& result);

}  // namespace ferret
