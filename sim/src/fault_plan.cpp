#include "ferret/sim/fault_plan.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <stdexcept>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/core/yaml_emit.hpp"

namespace ferret {
namespace {

using T = FaultTarget;
constexpr FaultTarget kLink[] = {T::kBothWays, T::kUavToUgv, T::kUgvToUav};
constexpr FaultTarget kRobots[] = {T::kUav, T::kUgv};
constexpr FaultTarget kUgvOnly[] = {T::kUgv};
constexpr FaultTarget kUavOnly[] = {T::kUav};
constexpr FaultTarget kCameras[] = {T::kMarkerCamera, T::kDepthCamera, T::kObjectCamera};
constexpr FaultTarget kDetectors[] = {T::kObjectDetector, T::kMarkerDetector};
constexpr FaultTarget kWheels[] = {T::kLeftWheel, T::kRightWheel};

constexpr double kLongest_s = 1e5;  // a bound on "how long" that no mission reaches

constexpr FaultNumber fraction(double fallback, double draw_lo, double draw_hi, double hi = 1.0) {
  return {"strength", "fraction", 0.0, hi, fallback, draw_lo, draw_hi};
}

// The one table of kinds. Durations: {lo, hi, default, draw lo, draw hi} in seconds.
const std::array<FaultKindSpec, 24>& table() {
  static const std::array<FaultKindSpec, 24> kinds{{
      {FaultKind::kLinkLoss, "link_loss", "datagrams of the robot link lost, in bursts", kLink,
       false, 0.1, kLongest_s, 60, 5, 300, true, fraction(0.3, 0.1, 0.7),
       FaultNumber{"burst_s", "s", 0.0, 60.0, 0.0, 0.0, 5.0}},
      {FaultKind::kLinkOutage, "link_outage", "nothing gets through the robot link", kLink, false,
       1, 120, 30, 1, 120, true, std::nullopt, std::nullopt},
      {FaultKind::kLinkLatency, "link_latency", "datagrams of the robot link late, with jitter",
       kLink, false, 0.1, kLongest_s, 60, 5, 300, true,
       FaultNumber{"strength", "s", 0.0, 10.0, 0.5, 0.05, 2.0},
       FaultNumber{"jitter_s", "s", 0.0, 10.0, 0.0, 0.0, 0.5}},
      {FaultKind::kLinkDuplicate, "link_duplicate", "datagrams of the robot link delivered twice",
       kLink, false, 0.1, kLongest_s, 60, 5, 300, true, fraction(0.2, 0.05, 0.5), std::nullopt},
      {FaultKind::kControllerStop, "controller_stop",
       "a robot's controller stops, and restarts after the duration", kRobots, false, 1, 600, 10, 1,
       60, true, std::nullopt, std::nullopt},
      {FaultKind::kIrDropout, "ir_dropout", "the miniUGV's IR readings missing", kUgvOnly, false,
       0.1, kLongest_s, 5, 1, 30, true, fraction(1.0, 0.3, 1.0), std::nullopt},
      {FaultKind::kIrStuck, "ir_stuck", "the miniUGV's IR readings frozen at their last value",
       kUgvOnly, false, 0.1, kLongest_s, 5, 1, 30, true, std::nullopt, std::nullopt},
      {FaultKind::kCameraBlackout, "camera_blackout", "a camera gives no frames", kCameras, false,
       0.1, kLongest_s, 10, 1, 60, true, std::nullopt, std::nullopt},
      {FaultKind::kDetectionMissed, "detection_missed", "a detector misses what is there",
       kDetectors, false, 0.1, kLongest_s, 30, 5, 120, true, fraction(1.0, 0.3, 1.0), std::nullopt},
      {FaultKind::kDetectionFalse, "detection_false", "a detector reports what is not there",
       kDetectors, false, 0.1, kLongest_s, 30, 5, 120, true,
       FaultNumber{"strength", "per frame", 0.0, 1.0, 0.05, 0.01, 0.2}, std::nullopt},
      {FaultKind::kImuSpike, "imu_spike", "the miniUGV's IMU spikes at its next touchdown",
       kUgvOnly, true, 0, 0, 0, 0, 0, false,
       FaultNumber{"strength", "m/s^2", 0.0, 200.0, 30.0, 10.0, 80.0}, std::nullopt},
      {FaultKind::kTetherSnag, "tether_snag",
       "the tether catches where it touches the floor, on a corner no map holds", kUgvOnly, false,
       0.1, kLongest_s, 60, 5, 300, true, std::nullopt, std::nullopt},
      {FaultKind::kWinchStall, "winch_stall", "the spool does not turn, whatever it is told",
       kUavOnly, false, 0.1, kLongest_s, 5, 1, 30, true, std::nullopt, std::nullopt},
      {FaultKind::kWinchServoError, "winch_servo_error",
       "the winch's servo reports an error and stops", kUavOnly, false, 0.1, kLongest_s, 2, 0.5, 10,
       true, std::nullopt, std::nullopt},
      {FaultKind::kWheelSlip, "wheel_slip", "the miniUGV's wheels slip", kUgvOnly, false, 0.1,
       kLongest_s, 10, 1, 60, true, fraction(0.3, 0.1, 0.6, 0.95), std::nullopt},
      {FaultKind::kMotorStall, "motor_stall", "one wheel's motor stalls", kWheels, false, 0.1,
       kLongest_s, 5, 1, 30, true, std::nullopt, std::nullopt},
      {FaultKind::kBatterySag, "battery_sag", "a battery loses charge at once", kRobots, true, 0, 0,
       0, 0, 0, false, fraction(0.2, 0.05, 0.4), std::nullopt},
      {FaultKind::kBatteryDrain, "battery_drain", "a battery drains faster", kRobots, false, 0.1,
       kLongest_s, 300, 60, 900, true, FaultNumber{"strength", "factor", 1.0, 20.0, 2.0, 1.2, 4.0},
       std::nullopt},
      {FaultKind::kGraspFail, "grasp_fail", "the next grasp does not hold the object", kUgvOnly,
       true, 0, 0, 0, 0, 0, false, std::nullopt, std::nullopt},
      {FaultKind::kObjectFalls, "object_falls", "the object falls off the magnet", kUgvOnly, true,
       0, 0, 0, 0, 0, false, std::nullopt, std::nullopt},
      {FaultKind::kMarkerOccluded, "marker_occluded", "the markers partly hidden", kUavOnly, false,
       0.1, kLongest_s, 60, 10, 300, true, fraction(1.0, 0.3, 1.0), std::nullopt},
      {FaultKind::kLandingZoneObstructed, "landing_zone_obstructed",
       "something appears on the landing zone the UAV chose", kUavOnly, true, 0, 0, 0, 0, 0, false,
       FaultNumber{"strength", "m high", 0.05, 3.0, 0.5, 0.2, 1.0}, std::nullopt},
      {FaultKind::kUavDrift, "uav_drift", "the UAV's position estimate drifts", kUavOnly, false,
       0.1, kLongest_s, 30, 5, 120, true, FaultNumber{"strength", "m/s", 0.0, 3.0, 0.3, 0.1, 0.8},
       std::nullopt},
      {FaultKind::kUavGust, "uav_gust", "gusts push the hovering UAV", kUavOnly, false, 0.1,
       kLongest_s, 5, 1, 15, false, FaultNumber{"strength", "m/s", 0.0, 20.0, 5.0, 2.0, 10.0},
       std::nullopt},
  }};
  return kinds;
}

constexpr std::array<std::string_view, 12> kTargetNames{"both_ways",
                                                        "uav_to_ugv",
                                                        "ugv_to_uav",
                                                        "uav",
                                                        "ugv",
                                                        "marker_camera",
                                                        "depth_camera",
                                                        "object_camera",
                                                        "object_detector",
                                                        "marker_detector",
                                                        "left_wheel",
                                                        "right_wheel"};

template <class Range, class Name>
std::string joined(const Range& items, Name name) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + std::string(name(item));
  return out;
}

const FaultKindSpec& kind_named(const yaml::MapReader& r) {
  const auto name = r.get<std::string>("kind");
  for (const FaultKindSpec& s : table())
    if (s.name == name) return s;
  r.fail("kind", "a fault kind: one of " + joined(table(), [](const auto& s) { return s.name; }),
         "'" + name + "'");
}

FaultTarget read_target(const yaml::MapReader& r, const FaultKindSpec& s) {
  if (!r.has("target")) return s.targets.front();
  const auto name = r.get<std::string>("target");
  for (const FaultTarget t : s.targets)
    if (to_string(t) == name) return t;
  r.fail("target",
         fmt::format("a target of {}: one of {}", s.name,
                     joined(s.targets, [](FaultTarget t) { return to_string(t); })),
         "'" + name + "'");
}

FaultStart read_start(const yaml::MapReader& r, const FaultStates& states) {
  FaultStart start;
  start.at_s = r.get_in_range_or("at_s", 0.0, kLongest_s, 0.0);
  if (!r.has("on")) return start;
  const auto on = r.get<std::string>("on");
  const auto dot = on.find('.');
  const std::string robot = on.substr(0, dot);
  const std::string state = dot == std::string::npos ? "" : on.substr(dot + 1);
  std::span<const std::string_view> names;
  if (robot == "uav") {
    start.robot = FaultRobot::kUav;
    names = states.uav;
  } else if (robot == "ugv") {
    start.robot = FaultRobot::kUgv;
    names = states.ugv;
  }
  const bool known = start.robot != FaultRobot::kNone &&
                     std::find(names.begin(), names.end(), state) != names.end();
  if (!known) {
    std::string list;
    for (const auto n : states.uav) list += (list.empty() ? "uav." : ", uav.") + std::string(n);
    for (const auto n : states.ugv) list += (list.empty() ? "ugv." : ", ugv.") + std::string(n);
    r.fail("on", "a robot's state, ROBOT.STATE: one of " + list, "'" + on + "'");
  }
  start.state = state;
  return start;
}

double read_number(const yaml::MapReader& r, const std::optional<FaultNumber>& n,
                   std::string_view key, const FaultKindSpec& s) {
  if (!n) {
    if (r.has(key)) r.fail(key, fmt::format("no {} for {} (it has none)", key, s.name));
    return 0.0;
  }
  return r.get_in_range_or(n->key, n->lo, n->hi, n->fallback);
}

Fault read_fault(const yaml::MapReader& r, const FaultStates& states) {
  r.allow_only({"kind", "target", "at_s", "on", "duration_s", "permanent", "strength", "burst_s",
                "jitter_s"});
  const FaultKindSpec& s = kind_named(r);
  Fault f;
  f.kind = s.kind;
  f.target = read_target(r, s);
  f.start = read_start(r, states);
  const bool permanent = r.get_or("permanent", false);
  if (s.instantaneous) {
    if (r.has("duration_s") || permanent)
      r.fail(r.has("duration_s") ? "duration_s" : "permanent",
             fmt::format("no duration: {} happens once, at its start", s.name));
    f.duration_s = 0.0;
  } else if (permanent) {
    if (!s.may_be_permanent) r.fail("permanent", fmt::format("false: {} cannot last", s.name));
    if (r.has("duration_s")) r.fail("duration_s", "no duration with permanent: true");
    f.duration_s = std::nullopt;
  } else {
    f.duration_s = r.get_in_range_or("duration_s", s.duration_lo_s, s.duration_hi_s, s.duration_s);
  }
  f.strength = read_number(r, s.strength, "strength", s);
  const std::string_view extra_key = s.extra ? s.extra->key : std::string_view{};
  for (const std::string_view key : {"burst_s", "jitter_s"})
    if (key != extra_key && r.has(key))
      r.fail(key, fmt::format("no {} for {} (it has none)", key, s.name));
  f.extra = s.extra ? read_number(r, s.extra, s.extra->key, s) : 0.0;
  return f;
}

double draw_in(Rng& rng, double lo, double hi) { return hi > lo ? rng.uniform(lo, hi) : lo; }

std::string seconds(double s) { return fmt::format("{:g} s", s); }

}  // namespace

std::span<const FaultKindSpec> fault_kinds() { return table(); }

const FaultKindSpec& spec(FaultKind kind) {
  const auto i = static_cast<std::size_t>(kind);
  if (i >= table().size()) throw std::out_of_range("fault kind");
  return table()[i];
}

std::string_view to_string(FaultKind kind) { return spec(kind).name; }

std::string_view to_string(FaultTarget target) {
  const auto i = static_cast<std::size_t>(target);
  return i < kTargetNames.size() ? kTargetNames[i] : "?";
}

std::string_view to_string(FaultRobot robot) {
  switch (robot) {
    case FaultRobot::kUav:
      return "uav";
    case FaultRobot::kUgv:
      return "ugv";
    case FaultRobot::kNone:
      break;
  }
  return "";
}

bool Fault::active(std::optional<double> started_s, double t_s) const {
  if (!started_s || t_s < *started_s) return false;
  if (!duration_s) return true;
  return t_s < *started_s + *duration_s;
}

FaultPlan fault_plan_from_yaml(const YAML::Node& node, const std::string& source,
                               const FaultStates& states) {
  FaultPlan plan;
  if (!node.IsDefined() || node.IsNull()) return plan;
  if (!node.IsSequence())
    throw InputError(source, "faults", "a list of faults ({kind: ..., at_s: ..., ...})",
                     yaml::internal::describe(node));
  if (node.size() > kMaxFaults)
    throw InputError(source, "faults", fmt::format("at most {} faults", kMaxFaults),
                     std::to_string(node.size()));
  for (std::size_t i = 0; i < node.size(); ++i)
    plan.faults.push_back(
        read_fault(yaml::MapReader(node[i], source, fmt::format("faults[{}]", i)), states));
  return plan;
}

void emit_fault_plan(YAML::Emitter& e, const FaultPlan& plan) {
  e << YAML::BeginSeq;
  for (const Fault& f : plan.faults) {
    const FaultKindSpec& s = spec(f.kind);
    e << YAML::Flow << YAML::BeginMap;
    e << YAML::Key << "kind" << YAML::Value << std::string(s.name);
    e << YAML::Key << "target" << YAML::Value << std::string(to_string(f.target));
    if (f.start.robot != FaultRobot::kNone)
      e << YAML::Key << "on" << YAML::Value
        << std::string(to_string(f.start.robot)) + "." + f.start.state;
    internal::emit_key_number(e, "at_s", f.start.at_s);
    if (!s.instantaneous) {
      if (f.duration_s)
        internal::emit_key_number(e, "duration_s", *f.duration_s);
      else
        e << YAML::Key << "permanent" << YAML::Value << true;
    }
    if (s.strength) internal::emit_key_number(e, "strength", f.strength);
    if (s.extra) internal::emit_key_number(e, std::string(s.extra->key).c_str(), f.extra);
    e << YAML::EndMap;
  }
  e << YAML::EndSeq;
}

std::string fault_plan_to_yaml(const FaultPlan& plan) {
  YAML::Emitter e;
  e << YAML::BeginMap << YAML::Key << "faults" << YAML::Value;
  emit_fault_plan(e, plan);
  e << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

std::string describe(const Fault& f) {
  const FaultKindSpec& s = spec(f.kind);
  std::string out = fmt::format("{} {}", s.name, to_string(f.target));
  if (s.strength) out += fmt::format(" {:g} {}", f.strength, s.strength->unit);
  if (s.extra) out += fmt::format(" ({} {:g})", s.extra->key, f.extra);
  if (f.start.robot != FaultRobot::kNone)
    out += fmt::format(" on {}.{} +{}", to_string(f.start.robot), f.start.state,
                       seconds(f.start.at_s));
  else
    out += " at " + seconds(f.start.at_s);
  if (!s.instantaneous) out += f.duration_s ? " for " + seconds(*f.duration_s) : " to the end";
  return out;
}

FaultPlan draw_fault_plan(std::uint64_t seed, const FaultDrawOptions& o,
                          const FaultStates& states) {
  if (o.min_faults < 0 || o.max_faults < o.min_faults ||
      static_cast<std::size_t>(o.max_faults) > kMaxFaults)
    throw std::invalid_argument("draw_fault_plan: fault counts");
  std::vector<FaultKind> kinds = o.kinds;
  if (kinds.empty())
    for (const FaultKindSpec& s : table()) kinds.push_back(s.kind);
  Rng rng(derive_seed(seed, {stable_hash("faults")}));
  FaultPlan plan;
  const auto n = rng.uniform_int(o.min_faults, o.max_faults);
  const bool any_state = !states.uav.empty() || !states.ugv.empty();
  for (std::int64_t i = 0; i < n; ++i) {
    const FaultKindSpec& s = spec(kinds[static_cast<std::size_t>(
        rng.uniform_int(0, static_cast<std::int64_t>(kinds.size()) - 1))]);
    Fault f;
    f.kind = s.kind;
    f.target = s.targets[static_cast<std::size_t>(
        rng.uniform_int(0, static_cast<std::int64_t>(s.targets.size()) - 1))];
    if (any_state && rng.bernoulli(o.state_start_fraction)) {
      const auto all = static_cast<std::int64_t>(states.uav.size() + states.ugv.size());
      const auto k = static_cast<std::size_t>(rng.uniform_int(0, all - 1));
      const bool uav = k < states.uav.size();
      f.start.robot = uav ? FaultRobot::kUav : FaultRobot::kUgv;
      f.start.state = std::string(uav ? states.uav[k] : states.ugv[k - states.uav.size()]);
      f.start.at_s = draw_in(rng, 0.0, o.max_delay_after_state_s);
    } else {
      f.start.at_s = draw_in(rng, 0.0, o.horizon_s);
    }
    if (s.instantaneous)
      f.duration_s = 0.0;
    else if (s.may_be_permanent && rng.bernoulli(o.permanent_fraction))
      f.duration_s = std::nullopt;
    else
      f.duration_s = draw_in(rng, s.draw_duration_lo_s, s.draw_duration_hi_s);
    if (s.strength) f.strength = draw_in(rng, s.strength->draw_lo, s.strength->draw_hi);
    if (s.extra) f.extra = draw_in(rng, s.extra->draw_lo, s.extra->draw_hi);
    plan.faults.push_back(std::move(f));
  }
  return plan;
}

}  // namespace ferret
