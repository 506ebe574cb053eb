#pragma once
// The MCAP log of a simulated miniUGV mission (docs/mission.md), for Foxglove:
//   /tf            map -> ugv, every 0.1 s (foxglove.FrameTransform)
//   /ugv/path      the driven path, every second (foxglove.SceneUpdate)
//   /maps/G        G: 0 free, 50 unknown, 100 occupied, every 5 s and at the end
//   /maps/O        O: the object probability x 100, every 5 s and at the end (foxglove.Grid)
//   /objects       the object as found (and, the simulator's truth, where it is)
//   /log           every state transition, with its reason (foxglove.Log)
// Hook it into run_ugv_mission as its on_tick, recorder.hook(), and the
// transition log's listener; finish() gives the file's bytes.

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/foxglove_log.hpp"
#include "ferret/core/transition_log.hpp"
#include "ferret/mission/ugv_mission_run.hpp"

namespace ferret {

/// G (0 free, 50 unknown, 100 occupied) and O (probability x 100) as foxglove.Grid
/// messages on `prefix`/G and `prefix`/O in `frame`.
void log_search_maps(FoxgloveLog& log, double t_s, const IrGrid& g, const ObjectMap& o,
                     const std::string& prefix = "/maps", const std::string& frame = "map");

class UgvMissionRecorder {
 public:
  UgvMissionRecorder() = default;
  /// For run_ugv_mission's on_tick.
  [[nodiscard]] UgvMissionTickHook hook();
  /// For TransitionLog::on_transition (chain it after a printer if there is one).
  void transition(const Transition& t);
  /// Closes the log with the final maps and the objects; returns the MCAP bytes.
  [[nodiscard]] std::string finish(const UgvMissionRunResult& result,
                                   const std::optional<Eigen::Vector2d>& object_W);
  [[nodiscard]] std::uint64_t message_count() const { return log_.message_count(); }

 private:
  void maps(double t_s, const IrGrid& g, const ObjectMap& o);

  FoxgloveLog log_;
  std::vector<Eigen::Vector3d> path_;
  long ticks_ = 0;
  double last_t_s_ = 0.0;
};

}  // namespace ferret
