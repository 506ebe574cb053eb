#pragma once
// The safety invariants of a mission, checked at every simulation step from the
// world's truth (docs/safety.md), never by the controllers themselves: the tether's
// tension under its limit, l_t within L, the UAV in free space, the miniUGV's body off
// every wall, no battery empty, every controller state left within its timeout, and at
// the end no miniUGV left in a hidden space without a recorded reason. A violation is
// one episode (from the step it starts to the step it ends) with its time, the robots'
// states then, and its worst value; any violation makes the run `unsafe`.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ferret {

enum class InvariantKind : std::uint8_t {
  kTensionOverLimit,  ///< tension (N) above max_tension_n
  kTetherOverLength,  ///< l_t (m) beyond the tether's length L
  kUavCollision,      ///< the UAV's shape in an occupied voxel (value: 1)
  kUgvBodyContact,    ///< the miniUGV's body into a wall (value: depth, m)
  kBatteryEmpty,      ///< a battery at or below its floor (value: fraction left)
  kStateTimeout,      ///< a controller state held past its timeout (value: s in it)
  kUgvLeftBehind,     ///< the mission over, the miniUGV in a hidden space, no reason
  kNoEnd,             ///< the mission did not end within the simulation's bound (a hang)
};
inline constexpr std::size_t kInvariantKinds = 8;
[[nodiscard]] std::string_view to_string(InvariantKind kind);

struct InvariantLimits {
  double max_tension_n = 10.0;
  double tether_length_m = 15.0;  ///< L
  /// A body contact counts when at least this deep (0: every contact, also a body
  /// stopped at the wall's face).
  double contact_tolerance_m = 0.0;
  double battery_floor = 0.0;  ///< a battery at or below this fraction is empty
  /// Per robot ("uav", "ugv"), per state name: the longest the controller may stay in it
  /// (s). A state without an entry has none.
  std::map<std::string, std::map<std::string, double>> state_timeout_s;
};

/// What the truth says at one step.
struct InvariantSample {
  double t_s = 0.0;
  double tension_n = 0.0;
  double released_m = 0.0;  ///< l_t
  bool uav_collision = false;
  /// The miniUGV's body against a wall (SimUgvBase::in_contact), and how deep.
  bool ugv_body_contact = false;
  double ugv_contact_depth_m = 0.0;
  double uav_battery = 1.0;
  std::optional<double> ugv_battery;  ///< none: the miniUGV reports none (aboard, off)
  std::string uav_state;              ///< the controllers' state names ("" when none)
  std::string ugv_state;
};

struct InvariantViolation {
  InvariantKind kind = InvariantKind::kTensionOverLimit;
  double t_s = 0.0;       ///< when it started
  double until_s = 0.0;   ///< the last step it held
  std::string uav_state;  ///< the states when it started
  std::string ugv_state;
  double value = 0.0;  ///< the worst over the episode, in the kind's unit
  double limit = 0.0;
  std::string detail;  ///< which robot (a battery) or robot.state (a timeout)
};

class InvariantMonitor {
 public:
  explicit InvariantMonitor(InvariantLimits limits);

  /// One step of the truth; steps come in time order.
  void observe(const InvariantSample& sample);
  /// The mission's end: `ugv_left_in_space` when the miniUGV is in a hidden space, with
  /// `reason` what the mission recorded for leaving it there (empty: none); `ended` false
  /// when the simulation stopped at its own bound instead of the mission ending.
  void finish(const InvariantSample& last, bool ugv_left_in_space, const std::string& reason,
              bool ended);

  [[nodiscard]] const std::vector<InvariantViolation>& violations() const { return violations_; }
  [[nodiscard]] int count(InvariantKind kind) const;
  [[nodiscard]] bool safe() const { return violations_.empty(); }
  [[nodiscard]] const InvariantLimits& limits() const { return limits_; }

 private:
  struct Episode {
    std::optional<std::size_t> open;  ///< index into violations_ while it holds
  };
  struct StateClock {
    std::string state;
    double entered_s = 0.0;
    bool reported = false;
  };
  void check(InvariantKind kind, bool violated, double value, double limit,
             const InvariantSample& s, bool higher_is_worse, const std::string& detail = {});
  void check_timeout(const std::string& robot, const std::string& state, StateClock& clock,
                     const InvariantSample& s);

  InvariantLimits limits_;
  std::vector<InvariantViolation> violations_;
  std::map<std::pair<InvariantKind, std::string>, Episode> episodes_;  ///< by kind, detail
  StateClock uav_clock_, ugv_clock_;
  bool started_ = false;
};

}  // namespace ferret
