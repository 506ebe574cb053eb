#pragma once
// A robot's own control loop (`ferret uav` / `ferret ugv` on their hardware): one step
// every period of the machine's monotonic clock, until the step says it is done, SIGINT
// or SIGTERM arrives, or a duration has passed. Steps that overrun their period are
// counted, not caught up: a late control step is run once, then the schedule resumes
// from now.

#include <cstdint>
#include <functional>
#include <string>

namespace ferret {

struct PeriodicLoopResult {
  std::uint64_t steps = 0;
  std::uint64_t overruns = 0;  ///< steps that ended after the next one was due
  double worst_step_s = 0.0;   ///< the longest step
  std::string why_stopped;     ///< "done", "SIGINT", "SIGTERM" or "duration"
  /// One line for the run's summary.
  [[nodiscard]] std::string summary(double period_s) const;
};

/// Runs `step` every period_s (> 0) until it returns false, a signal, or duration_s (0:
/// none) has passed. SIGINT and SIGTERM are caught only while it runs (their previous
/// handlers are restored): a robot ends its loop and stops its actuators itself.
PeriodicLoopResult run_periodic(double period_s, double duration_s,
                                const std::function<bool()>& step);

}  // namespace ferret
