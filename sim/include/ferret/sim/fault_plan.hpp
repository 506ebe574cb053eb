#pragma once
// What goes wrong in a simulated mission, on purpose (docs/safety.md): the faults of a
// mission YAML's `faults:` section, or a random mix drawn from a seed for a campaign.
// Each fault says what breaks (its kind and target), when (a time from the start, or a
// delay after a robot first enters a state), for how long, and how strongly. The
// simulated backends and the link's network apply a plan; the controllers only see what
// real hardware would show them (a silent link, a stuck reading, a motor that stalls).
//
//   faults:
//     - {kind: link_outage, on: ugv.explore, at_s: 20, duration_s: 60}
//     - {kind: link_loss, at_s: 0, permanent: true, strength: 0.5, burst_s: 2}
//     - {kind: battery_drain, target: ugv, at_s: 300, strength: 3}
//
// The kinds, their targets, units and ranges are one table (fault_kinds()); the
// reader, the emitter, the random draw and docs/safety.md all follow it.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace YAML {
class Node;
class Emitter;
}  // namespace YAML

namespace ferret {

enum class FaultKind : std::uint8_t {
  kLinkLoss,               ///< datagrams lost (strength: fraction), in bursts (burst_s)
  kLinkOutage,             ///< nothing gets through
  kLinkLatency,            ///< datagrams late (strength: s), with jitter (jitter_s)
  kLinkDuplicate,          ///< datagrams delivered twice (strength: fraction)
  kControllerStop,         ///< a robot's controller stops; restarts after the duration
  kIrDropout,              ///< IR readings missing (strength: fraction)
  kIrStuck,                ///< IR readings frozen at their last value
  kCameraBlackout,         ///< a camera gives no frames
  kDetectionMissed,        ///< a detector misses what is there (strength: fraction)
  kDetectionFalse,         ///< a detector reports what is not there (strength: per frame)
  kImuSpike,               ///< the miniUGV's IMU spikes at touchdown (strength: m/s^2)
  kTetherSnag,             ///< the tether catches on a corner no map holds
  kWinchStall,             ///< the spool does not turn whatever it is told
  kWinchServoError,        ///< the winch's servo reports an error and stops
  kWheelSlip,              ///< the wheels slip (strength: fraction of motion lost)
  kMotorStall,             ///< one wheel's motor stalls
  kBatterySag,             ///< a battery loses charge at once (strength: fraction)
  kBatteryDrain,           ///< a battery drains faster (strength: factor)
  kGraspFail,              ///< the next grasp does not hold the object
  kObjectFalls,            ///< the object falls off the magnet
  kMarkerOccluded,         ///< the markers partly hidden (strength: fraction)
  kLandingZoneObstructed,  ///< something appears on the chosen zone (strength: m high)
  kUavDrift,               ///< the UAV's position estimate drifts (strength: m/s)
  kUavGust,                ///< gusts push the hovering UAV (strength: m/s)
};

/// What a fault acts on. Each kind allows some (the first is its default).
enum class FaultTarget : std::uint8_t {
  kBothWays,  ///< the robot link, both directions
  kUavToUgv,
  kUgvToUav,
  kUav,
  kUgv,
  kMarkerCamera,
  kDepthCamera,
  kObjectCamera,
  kObjectDetector,
  kMarkerDetector,
  kLeftWheel,
  kRightWheel,
};

/// Which robot's state starts a fault.
enum class FaultRobot : std::uint8_t { kNone, kUav, kUgv };

/// A fault's number in a range, with the narrower range a random draw takes it from.
struct FaultNumber {
  std::string_view key;  ///< its YAML key ("strength", "burst_s", "jitter_s")
  std::string_view unit;
  double lo, hi, fallback;
  double draw_lo, draw_hi;
};

/// One row of the kinds' table.
struct FaultKindSpec {
  FaultKind kind;
  std::string_view name;  ///< in YAML, reports and CSVs
  std::string_view what;  ///< one line for errors and the docs
  std::span<const FaultTarget> targets;
  /// Instantaneous kinds happen once at their start: no duration.
  bool instantaneous;
  /// Duration range (s), default and draw range; kinds that allow it may last to the end.
  double duration_lo_s, duration_hi_s, duration_s, draw_duration_lo_s, draw_duration_hi_s;
  bool may_be_permanent;
  std::optional<FaultNumber> strength;
  std::optional<FaultNumber> extra;  ///< a kind's second number (burst_s, jitter_s)
};

[[nodiscard]] std::span<const FaultKindSpec> fault_kinds();
[[nodiscard]] const FaultKindSpec& spec(FaultKind kind);
[[nodiscard]] std::string_view to_string(FaultKind kind);
[[nodiscard]] std::string_view to_string(FaultTarget target);
[[nodiscard]] std::string_view to_string(FaultRobot robot);

/// When a fault starts: `at_s` of simulated time after the mission starts, or after the
/// robot first enters `state` (one of the names FaultStates lists for it).
struct FaultStart {
  FaultRobot robot = FaultRobot::kNone;
  std::string state;
  double at_s = 0.0;

  bool operator==(const FaultStart&) const = default;
};

struct Fault {
  FaultKind kind = FaultKind::kLinkLoss;
  FaultTarget target = FaultTarget::kBothWays;
  FaultStart start;
  /// How long it lasts (s); none: to the end of the mission. 0 for instantaneous kinds.
  std::optional<double> duration_s = 0.0;
  double strength = 0.0;  ///< in the kind's unit (0 when the kind has none)
  double extra = 0.0;     ///< the kind's second number (0 when it has none)

  bool operator==(const Fault&) const = default;
  /// Whether a lasting fault acts at `t_s`, given when it started (none: not yet). An
  /// instantaneous one never "acts": its injector fires it once, at its start.
  [[nodiscard]] bool active(std::optional<double> started_s, double t_s) const;
};

/// The faults of one mission, in the order written (or drawn).
struct FaultPlan {
  std::vector<Fault> faults;
  bool operator==(const FaultPlan&) const = default;
  [[nodiscard]] bool empty() const { return faults.empty(); }
};

/// The state names a fault may start on, per robot (the controllers' own names, as the
/// mission assembly passes them; sim/ knows no controller).
struct FaultStates {
  std::span<const std::string_view> uav;
  std::span<const std::string_view> ugv;
};

/// Reads a `faults:` section: a list of faults (an undefined or null node: none).
/// Throws InputError naming `source` and the field (`faults[2].strength`) for an unknown
/// kind, key, target or state, a number out of its kind's range, a number the kind does
/// not have, a duration on an instantaneous kind, or more than kMaxFaults faults.
[[nodiscard]] FaultPlan fault_plan_from_yaml(const YAML::Node& node, const std::string& source,
                                             const FaultStates& states);
inline constexpr std::size_t kMaxFaults = 256;

/// The plan as the value of a `faults:` key (an open YAML emitter), which
/// fault_plan_from_yaml reads back to the same plan.
void emit_fault_plan(YAML::Emitter& e, const FaultPlan& plan);
/// The plan as a YAML document `faults: [...]`, newline-terminated.
[[nodiscard]] std::string fault_plan_to_yaml(const FaultPlan& plan);

/// One line: "link_outage both_ways on ugv.explore +20 s for 60 s".
[[nodiscard]] std::string describe(const Fault& fault);

struct FaultDrawOptions {
  int min_faults = 1;
  int max_faults = 4;
  /// Time-started faults start in [0, horizon_s).
  double horizon_s = 1500.0;
  /// State-started faults start within this after the state is entered.
  double max_delay_after_state_s = 30.0;
  /// The share of faults started by a state (when `states` lists any).
  double state_start_fraction = 0.5;
  /// The share of faults that may last to the end and do.
  double permanent_fraction = 0.1;
  /// Kinds to draw from; empty: every kind.
  std::vector<FaultKind> kinds;
};

/// A random mix of faults, the same for the same seed on every machine: the count in
/// [min_faults, max_faults], each kind, target, start, duration and numbers drawn from
/// the kind's draw ranges.
[[nodiscard]] FaultPlan draw_fault_plan(std::uint64_t seed, const FaultDrawOptions& options,
                                        const FaultStates& states);

}  // namespace ferret
