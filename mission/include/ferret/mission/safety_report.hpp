#pragma once
// The run's safety as report.json and the summary give it (docs/safety.md): whether any
// invariant was violated, how often each kind was, and each violation's episode.

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "ferret/sim/invariant_monitor.hpp"

namespace ferret {

/// {"safe": bool, "counts": {kind: n, ... every kind}, "violations": [{kind, t_s,
/// until_s, uav_state, ugv_state, value, limit, detail}, ...]}.
[[nodiscard]] nlohmann::json safety_json(const std::vector<InvariantViolation>& violations);

/// One line: "safe (every invariant held)" or "UNSAFE: 2 tension_over_limit (first at
/// 412.3 s in ugv_ops/explore, 28.1 N > 10 N), 1 state_timeout".
[[nodiscard]] std::string safety_summary(const std::vector<InvariantViolation>& violations);

}  // namespace ferret
