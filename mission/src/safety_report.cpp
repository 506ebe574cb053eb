#include "ferret/mission/safety_report.hpp"

#include <array>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace ferret {

nlohmann::json safety_json(const std::vector<InvariantViolation>& violations) {
  nlohmann::json counts = nlohmann::json::object();
  std::array<int, kInvariantKinds> n{};
  for (const InvariantViolation& v : violations) ++n[static_cast<std::size_t>(v.kind)];
  for (std::size_t k = 0; k < kInvariantKinds; ++k)
    counts[std::string(to_string(static_cast<InvariantKind>(k)))] = n[k];
  nlohmann::json list = nlohmann::json::array();
  for (const InvariantViolation& v : violations)
    list.push_back({{"kind", std::string(to_string(v.kind))},
                    {"t_s", v.t_s},
                    {"until_s", v.until_s},
                    {"uav_state", v.uav_state},
                    {"ugv_state", v.ugv_state},
                    {"value", v.value},
                    {"limit", v.limit},
                    {"detail", v.detail}});
  return {{"safe", violations.empty()}, {"counts", counts}, {"violations", list}};
}

std::string safety_summary(const std::vector<InvariantViolation>& violations) {
  if (violations.empty()) return "safe (every invariant held at every step)";
  std::array<int, kInvariantKinds> n{};
  std::array<const InvariantViolation*, kInvariantKinds> first{};
  for (const InvariantViolation& v : violations) {
    const auto k = static_cast<std::size_t>(v.kind);
    if (n[k]++ == 0) first[k] = &v;
  }
  std::string out = "UNSAFE:";
  const char* sep = " ";
  for (std::size_t k = 0; k < kInvariantKinds; ++k) {
    if (n[k] == 0) continue;
    const InvariantViolation& v = *first[k];
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s%d %s (first at %.1f s in %s/%s%s%s, %.3g vs limit %.3g)",
                  sep, n[k], std::string(to_string(v.kind)).c_str(), v.t_s,
                  v.uav_state.empty() ? "-" : v.uav_state.c_str(),
                  v.ugv_state.empty() ? "-" : v.ugv_state.c_str(), v.detail.empty() ? "" : ", ",
                  v.detail.c_str(), v.value, v.limit);
    out += buf;
    sep = "; ";
  }
  return out;
}

}  // namespace ferret
