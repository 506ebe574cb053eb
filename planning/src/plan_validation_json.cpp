// The validation report as JSON: the schema is docs/validate.schema.json, described in
// docs/validate.md. Numbers that do not exist (no limit for a collision, no clearance
// with nothing in reach) are null, never NaN or inf (which JSON cannot hold).
#include <cmath>
#include <nlohmann/json.hpp>

#include "ferret/planning/plan_validation.hpp"

namespace ferret {
namespace {

using json = nlohmann::json;

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
json box(const std::optional<Aabb3>& b) {
  return b ? json{{"min", vec(b->lo)}, {"max", vec(b->hi)}} : json(nullptr);
}

json violation(const Violation& v) {
  json o = {{"kind", to_string(v.kind)},
            {"segment", {{"from", v.from_index}, {"to", v.to_index}, {"s", v.s}}},
            {"t_s", v.t_s},
            {"position_m", vec(v.p_W)},
            {"yaw_rad", v.yaw_rad},
            {"part", v.part.empty() ? json(nullptr) : json(v.part)},
            {"obstacle", nullptr},
            {"value", number(v.value)},
            {"limit", number(v.limit)},
            {"message", v.describe()}};
  if (v.obstacle)
    o["obstacle"] = {{"position_m", vec(v.obstacle->p_W)},
                     {"name", v.obstacle->name.empty() ? json(nullptr) : json(v.obstacle->name)}};
  return o;
}

}  // namespace

std::string validation_report_to_json(const ValidationReport& report) {
  const ValidationInputs& in = report.inputs;
  const ValidationMargins& m = report.margins;
  json violations = json::array();
  for (const Violation& v : report.violations) violations.push_back(violation(v));
  json doc = {
      {"format", "ferret-validation"},
      {"version", 1},
      {"verdict", report.valid() ? "valid" : "invalid"},
      {"violation_count", report.violations.size()},
      {"violations", violations},
      {"margins",
       {{"min_clearance_m", number(m.min_clearance_m)},
        {"peak_speed_mps", m.peak_speed_mps},
        {"peak_acceleration_mps2", m.peak_acceleration_mps2},
        {"peak_yaw_rate_radps", m.peak_yaw_rate_radps},
        {"peak_tether_m", m.peak_tether_m ? json(*m.peak_tether_m) : json(nullptr)},
        {"tether_budget_m", m.tether_budget_m ? number(*m.tether_budget_m) : json(nullptr)}}},
      {"inputs",
       {{"plan", in.plan},
        {"world", in.world},
        {"robot", to_string(in.robot)},
        {"robot_model", in.robot_model},
        {"parts", in.parts},
        {"states", in.states},
        {"limits",
         {{"max_velocity_mps", number(in.limits.max_velocity_mps)},
          {"max_acceleration_mps2", number(in.limits.max_acceleration_mps2)},
          {"max_yaw_rate_radps", number(in.limits.max_yaw_rate_radps)},
          {"source", in.limits_source}}},
        {"unknown_policy", to_string(in.unknown)},
        {"geofence", box(in.geofence)},
        {"geofence_source", in.geofence ? json(in.geofence_source) : json(nullptr)},
        {"floor_z_m", in.floor_z_m ? json(*in.floor_z_m) : json(nullptr)},
        {"floor_source", in.floor_z_m ? json(in.floor_source) : json(nullptr)},
        {"entry_m", in.p_WE ? json::array({in.p_WE->x(), in.p_WE->y()}) : json(nullptr)},
        {"resolution", {{"step_m", in.resolution.step_m}, {"step_rad", in.resolution.step_rad}}}}}};
  return doc.dump(2) + "\n";
}

}  // namespace ferret
