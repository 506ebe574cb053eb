#pragma once
// A fault plan on the simulation's clock: which faults have started (at their time, or
// after their robot first entered their state), which act now, and which instantaneous
// ones are due to fire. The simulated backends ask it each step what to break; the
// link's two directions get their impairment from it.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ferret/link/lossy_channel.hpp"
#include "ferret/sim/fault_plan.hpp"

namespace ferret {

/// Whether the simulation applies `fault` (its kind on its target). The others are read,
/// drawn and written, but a mission refuses them until their injector exists
/// (docs/safety.md lists which do).
[[nodiscard]] bool simulation_injects(const Fault& fault);
/// InputError naming `source` and `faults[i].kind` for the first fault the simulation
/// does not inject.
void check_injectable(const FaultPlan& plan, const std::string& source);
/// Whether a plan breaks the robot link (its faults act on the link's messages).
[[nodiscard]] bool breaks_link(const FaultPlan& plan);

class FaultSchedule {
 public:
  explicit FaultSchedule(FaultPlan plan);

  /// A robot's controller is in `state` at `t_s` (called every step, or on each change):
  /// faults started by the first entry of that state start their delay now.
  void note_state(FaultRobot robot, const std::string& state, double t_s);
  /// Moves to `t_s` (non-decreasing): faults whose start has come start.
  void advance(double t_s);

  /// The strongest of the faults of `kind` on `target` acting now (none: no such fault).
  /// "Strongest": the largest strength (for kinds without one, the first).
  [[nodiscard]] const Fault* acting(FaultKind kind, FaultTarget target) const;
  [[nodiscard]] bool acts(FaultKind kind, FaultTarget target) const {
    return acting(kind, target) != nullptr;
  }
  /// Instantaneous faults of `kind` on `target` that started and have not fired yet;
  /// each is returned once (the caller fires it, or keeps it for when it can: an IMU
  /// spike waits for the touchdown).
  [[nodiscard]] std::vector<Fault> take_due(FaultKind kind, FaultTarget target);

  /// What the link's faults do now to one direction (kUavToUgv or kUgvToUav), with one
  /// delivery every `delivery_s`: outages, loss and bursts, latency and jitter,
  /// duplicates from the faults on that direction and on both ways.
  [[nodiscard]] link::LinkImpairment link_impairment(FaultTarget direction,
                                                     double delivery_s) const;

  /// When each fault started (none: not yet), in the plan's order.
  [[nodiscard]] const std::vector<std::optional<double>>& started_s() const { return started_s_; }
  [[nodiscard]] const FaultPlan& plan() const { return plan_; }
  [[nodiscard]] double now_s() const { return now_s_; }

 private:
  FaultPlan plan_;
  std::vector<std::optional<double>> started_s_;
  std::vector<std::optional<double>> state_entered_s_;  ///< per fault, its state's first entry
  std::vector<bool> fired_;
  double now_s_ = 0.0;
};

}  // namespace ferret
