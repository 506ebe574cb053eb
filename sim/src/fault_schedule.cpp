#include "ferret/sim/fault_schedule.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "ferret/core/error.hpp"

namespace ferret {

FaultSchedule::FaultSchedule(FaultPlan plan)
    : plan_(std::move(plan)),
      started_s_(plan_.faults.size()),
      state_entered_s_(plan_.faults.size()),
      fired_(plan_.faults.size(), false) {
  advance(0.0);
}

void FaultSchedule::note_state(FaultRobot robot, const std::string& state, double t_s) {
  for (std::size_t k = 0; k < plan_.faults.size(); ++k) {
    const FaultStart& s = plan_.faults[k].start;
    if (s.robot == robot && s.state == state && !state_entered_s_[k]) state_entered_s_[k] = t_s;
  }
  advance(std::max(now_s_, t_s));
}

void FaultSchedule::advance(double t_s) {
  now_s_ = t_s;
  for (std::size_t k = 0; k < plan_.faults.size(); ++k) {
    if (started_s_[k]) continue;
    const FaultStart& s = plan_.faults[k].start;
    const std::optional<double> from =
        s.robot == FaultRobot::kNone ? std::optional<double>(0.0) : state_entered_s_[k];
    if (from && t_s >= *from + s.at_s) started_s_[k] = *from + s.at_s;
  }
}

const Fault* FaultSchedule::acting(FaultKind kind, FaultTarget target) const {
  const Fault* best = nullptr;
  for (std::size_t k = 0; k < plan_.faults.size(); ++k) {
    const Fault& f = plan_.faults[k];
    if (f.kind != kind || f.target != target || !f.active(started_s_[k], now_s_)) continue;
    if (!best || f.strength > best->strength) best = &f;
  }
  return best;
}

std::vector<Fault> FaultSchedule::take_due(FaultKind kind, FaultTarget target) {
  std::vector<Fault> due;
  for (std::size_t k = 0; k < plan_.faults.size(); ++k) {
    const Fault& f = plan_.faults[k];
    if (f.kind != kind || f.target != target || !started_s_[k] || fired_[k]) continue;
    if (!spec(kind).instantaneous) continue;
    fired_[k] = true;
    due.push_back(f);
  }
  return due;
}

link::LinkImpairment FaultSchedule::link_impairment(FaultTarget direction,
                                                    double delivery_s) const {
  link::LinkImpairment i;
  const auto deliveries = [&](double s) {
    return static_cast<int>(std::lround(std::max(0.0, s) / std::max(delivery_s, 1e-9)));
  };
  for (const FaultTarget t : {FaultTarget::kBothWays, direction}) {
    if (acts(FaultKind::kLinkOutage, t)) i.outage = true;
    if (const Fault* f = acting(FaultKind::kLinkLoss, t)) {
      // Two losses at once: a datagram gets through only if it escapes both.
      i.drop_fraction = 1.0 - (1.0 - i.drop_fraction) * (1.0 - f->strength);
      i.burst_deliveries = std::max(i.burst_deliveries, f->extra / std::max(delivery_s, 1e-9));
    }
    if (const Fault* f = acting(FaultKind::kLinkLatency, t)) {
      i.latency_deliveries = std::max(i.latency_deliveries, deliveries(f->strength));
      i.jitter_deliveries = std::max(i.jitter_deliveries, deliveries(f->extra));
    }
    if (const Fault* f = acting(FaultKind::kLinkDuplicate, t))
      i.duplicate_fraction = std::max(i.duplicate_fraction, f->strength);
  }
  return i;
}

bool simulation_injects(const Fault& fault) {
  switch (fault.kind) {
    case FaultKind::kLinkLoss:
    case FaultKind::kLinkOutage:
    case FaultKind::kLinkLatency:
    case FaultKind::kLinkDuplicate:
    case FaultKind::kBatterySag:
    case FaultKind::kBatteryDrain:
      return true;
    case FaultKind::kCameraBlackout:  // the UAV's cameras (the miniUGV's: not yet)
      return fault.target == FaultTarget::kMarkerCamera ||
             fault.target == FaultTarget::kDepthCamera;
    default:
      return false;
  }
}

void check_injectable(const FaultPlan& plan, const std::string& source) {
  // "link_loss, ..., camera_blackout (marker_camera, depth_camera), ...": a kind's
  // targets are named when only some of them are injected.
  std::string injected;
  for (const FaultKindSpec& k : fault_kinds()) {
    std::vector<std::string_view> targets;
    for (const FaultTarget t : k.targets) {
      Fault probe;
      probe.kind = k.kind;
      probe.target = t;
      if (simulation_injects(probe)) targets.push_back(to_string(t));
    }
    if (targets.empty()) continue;
    injected += std::string(injected.empty() ? "" : ", ") + std::string(k.name);
    if (targets.size() < k.targets.size())
      injected += " (" + fmt::format("{}", fmt::join(targets, ", ")) + ")";
  }
  for (std::size_t i = 0; i < plan.faults.size(); ++i)
    if (!simulation_injects(plan.faults[i]))
      throw InputError(source, "faults[" + std::to_string(i) + "]",
                       "a fault the simulation injects: " + injected,
                       std::string(to_string(plan.faults[i].kind)) + " on " +
                           std::string(to_string(plan.faults[i].target)));
}

bool breaks_link(const FaultPlan& plan) {
  return std::any_of(plan.faults.begin(), plan.faults.end(), [](const Fault& f) {
    return f.kind == FaultKind::kLinkLoss || f.kind == FaultKind::kLinkOutage ||
           f.kind == FaultKind::kLinkLatency || f.kind == FaultKind::kLinkDuplicate;
  });
}

}  // namespace ferret
