#pragma once
// Request parsing for the planner service: a request's JSON body into the library's
// typed request (UgvPathRequest, UavApproachRequest, ValidateRequest, NextGoalRequest),
// strictly (an unknown key is an error, so a typo is not ignored), and the errors a
// client gets back, one JSON shape for every failure. No HTTP types here.

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/planning/collision_map.hpp"
#include "ferret/planning/next_goal.hpp"
#include "ferret/planning/plan_file.hpp"
#include "ferret/planning/plan_validation.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/planning/uav_approach.hpp"
#include "ferret/planning/ugv_path.hpp"

namespace ferret::internal {

using json = nlohmann::json;

// ---------------------------------------------------------------------------------
// Errors: one JSON shape for every failure, {"error": {"code", "message", "field"}}.

struct ApiError {
  int http = 400;
  std::string code;  // docs/service.md's set
  std::string message;
  std::string field;
};

/// A 400 INVALID_REQUEST naming `field`: "FIELD: expected EXPECTED (got GOT)".
[[noreturn]] void bad_request(const std::string& field, const std::string& expected,
                              const std::string& got = {});

/// {"error": {"code", "message", "field"}}, every part printable ASCII.
json error_body(const ApiError& e);

/// A library InputError about a request field, as the service's 400; `fields` maps the
/// library's field names to the request's.
ApiError from_input_error(const InputError& e, const std::map<std::string, std::string>& fields);

// ---------------------------------------------------------------------------------
// Request bodies: strict JSON (unknown keys are errors, so a typo is not ignored).

class Body {
 public:
  Body(const std::string& text, std::vector<std::string> known) {
    try {
      j_ = json::parse(text);
    } catch (const json::exception&) {
      bad_request("body", "a JSON object");
    }
    if (!j_.is_object()) bad_request("body", "a JSON object");
    for (const auto& [key, value] : j_.items())
      if (std::find(known.begin(), known.end(), key) == known.end())
        bad_request(key, fmt::format("one of the fields {}", fmt::join(known, ", ")), key);
  }
  [[nodiscard]] bool has(const std::string& key) const {
    return j_.contains(key) && !j_.at(key).is_null();
  }
  [[nodiscard]] const json& at(const std::string& key) const { return j_.at(key); }
  [[nodiscard]] std::string text(const std::string& key, const std::string& fallback = {}) const {
    if (!has(key)) return fallback;
    if (!at(key).is_string()) bad_request(key, "a string");
    return at(key).get<std::string>();
  }
  [[nodiscard]] std::string required_text(const std::string& key) const {
    if (!has(key)) bad_request(key, "a string (required)");
    return text(key);
  }
  [[nodiscard]] double number(const std::string& key, double lo, double hi,
                              const std::string& what) const {
    return number_of(at(key), key, lo, hi, what);
  }
  [[nodiscard]] std::optional<double> optional_number(const std::string& key, double lo, double hi,
                                                      const std::string& what) const {
    if (!has(key)) return std::nullopt;
    return number(key, lo, hi, what);
  }
  [[nodiscard]] std::vector<double> numbers(const std::string& key, std::size_t n,
                                            const std::string& what) const {
    if (!has(key)) bad_request(key, what + " (required)");
    return numbers_of(at(key), key, n, what);
  }
  [[nodiscard]] std::uint64_t seed() const {
    if (!has("seed")) return 1;
    const json& v = at("seed");
    if (!v.is_number_unsigned()) bad_request("seed", "an unsigned integer");
    return v.get<std::uint64_t>();
  }
  [[nodiscard]] std::optional<Aabb3> bounds() const {
    if (!has("bounds")) return std::nullopt;
    const auto v = numbers_of(at("bounds"), "bounds", 6, "[x0, y0, z0, x1, y1, z1] in metres");
    Aabb3 b{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    if (!(b.lo.array() < b.hi.array()).all())
      bad_request("bounds", "[x0, y0, z0, x1, y1, z1] with min < max on every axis");
    return b;
  }

  static double number_of(const json& v, const std::string& field, double lo, double hi,
                          const std::string& what) {
    if (!v.is_number()) bad_request(field, what, v.dump());
    const double x = v.get<double>();
    if (!(std::isfinite(x) && x >= lo && x <= hi)) bad_request(field, what, v.dump());
    return x;
  }
  static std::vector<double> numbers_of(const json& v, const std::string& field, std::size_t n,
                                        const std::string& what) {
    if (!v.is_array() || v.size() != n) bad_request(field, what, v.dump());
    std::vector<double> out;
    for (std::size_t k = 0; k < n; ++k)
      out.push_back(number_of(v[k], fmt::format("{}[{}]", field, k), -1e6, 1e6, what));
    return out;
  }

 private:
  json j_;
};

// Each reads the body's fields of one route into `r`, which holds the service's
// defaults; bad_request() on the first bad field.

/// POST /v1/plan/ugv and /v1/plan/ugv/return.
void read_ugv_request(const Body& body, UgvPathRequest& r);
/// POST /v1/plan/uav.
void read_uav_request(const Body& body, UavApproachRequest& r);
/// POST /v1/validate: the plan, then the checks' settings into `v`.
PlanFile read_plan(const Body& body);
void read_validate_request(const Body& body, ValidateRequest& v);
/// POST /v1/explore/next-goal.
void read_next_goal_request(const Body& body, NextGoalRequest& r);

}  // namespace ferret::internal
