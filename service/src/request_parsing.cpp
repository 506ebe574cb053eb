// Request parsing for the planner service (request_parsing.hpp).

#include "request_parsing.hpp"

#include <fmt/format.h>

#include <Eigen/Core>

namespace ferret::internal {

void bad_request(const std::string& field, const std::string& expected, const std::string& got) {
  throw ApiError{400, "INVALID_REQUEST",
                 got.empty()
                     ? fmt::format("{}: expected {}", field, expected)
                     : fmt::format("{}: expected {} (got {})", field, expected, printable(got, 80)),
                 field};
}

json error_body(const ApiError& e) {
  // Every part may hold the request's bytes (an unknown key, a part's name): printable
  // ASCII, so the answer is JSON whatever the request held.
  json err{{"code", printable(e.code, 64)}, {"message", printable(e.message)}};
  if (!e.field.empty()) err["field"] = printable(e.field, 120);
  return json{{"error", err}};
}

// A library InputError about a request field, as the service's 400 (or 404 for a
// hidden space the map does not have: the client named something that is not there).
ApiError from_input_error(const InputError& e, const std::map<std::string, std::string>& fields) {
  const auto it = fields.find(e.field());
  const std::string field = it != fields.end() ? it->second : e.field();
  std::string message = e.what();
  // The library names its own request struct; the client knows its JSON field.
  const std::string head = e.source() + ": " + e.field() + ": ";
  if (message.rfind(head, 0) == 0) message = field + ": " + message.substr(head.size());
  return ApiError{400, "INVALID_REQUEST", printable(message), field};
}

void read_ugv_request(const Body& body, UgvPathRequest& r) {
  const auto s = body.numbers("start", 3, "[x, y, yaw] in metres and radians");
  const auto g = body.numbers("goal", 3, "[x, y, yaw] in metres and radians");
  r.start = {s[0], s[1], s[2]};
  r.goal = {g[0], g[1], g[2]};
  r.hidden_space = body.text("hidden_space");
  r.bounds = body.bounds();
  r.floor_z_m = body.optional_number("floor_z_m", -1e6, 1e6, "a height in metres");
  if (body.has("entry")) {
    const auto e = body.numbers("entry", 2, "[x, y] in metres");
    r.p_WE = Eigen::Vector2d(e[0], e[1]);
  }
  r.tether_budget_m = body.optional_number("tether_budget_m", 1e-3, 1000.0, "metres in (0, 1000]");
  if (body.has("driven")) {
    const json& d = body.at("driven");
    if (!d.is_array() || d.size() > 10000)
      bad_request("driven", "an array of at most 10000 [x, y] points");
    for (std::size_t k = 0; k < d.size(); ++k) {
      const auto p = Body::numbers_of(d[k], fmt::format("driven[{}]", k), 2, "[x, y] in metres");
      r.driven.emplace_back(p[0], p[1]);
    }
  }
  r.seed = body.seed();
}

void read_uav_request(const Body& body, UavApproachRequest& r) {
  const auto s = body.numbers("start", 4, "[x, y, z, yaw] in metres and radians");
  r.start.x_m = s[0];
  r.start.y_m = s[1];
  r.start.z_m = s[2];
  r.start.yaw_rad = s[3];
  if (body.has("goal")) {
    const auto g = body.numbers("goal", 4, "[x, y, z, yaw] in metres and radians");
    Waypoint w;
    w.x_m = g[0];
    w.y_m = g[1];
    w.z_m = g[2];
    w.yaw_rad = g[3];
    r.goal = w;
  }
  r.hidden_space = body.text("hidden_space");
  if (r.goal.has_value() == !r.hidden_space.empty())
    bad_request("goal", "either goal [x, y, z, yaw] or hidden_space (not both)");
  r.tether_released_m = body.optional_number("tether_released_m", 0.0, 100.0, "metres in [0, 100]");
  r.bounds = body.bounds();
  try {
    r.unknown = parse_unknown_policy(body.text("unknown", "free"), "unknown");
  } catch (const InputError&) {
    bad_request("unknown", "free or occupied", body.text("unknown"));
  }
  r.planner = body.text("planner", "rrtconnect");
  r.seed = body.seed();
}

PlanFile read_plan(const Body& body) {
  if (!body.has("plan") || !body.at("plan").is_object())
    bad_request("plan", "a plan JSON object (docs/planning.md)");
  PlanFile plan;
  try {
    plan = parse_plan(body.at("plan").dump(), "plan");
  } catch (const InputError& e) {
    throw ApiError{400, "INVALID_REQUEST", printable(e.what()),
                   e.field().empty() ? "plan" : "plan." + e.field()};
  }
  return plan;
}

void read_validate_request(const Body& body, ValidateRequest& v) {
  if (body.has("builtin_shapes")) {
    if (!body.at("builtin_shapes").is_boolean()) bad_request("builtin_shapes", "true or false");
    v.builtin_shapes = body.at("builtin_shapes").get<bool>();
  }
  v.bounds = body.bounds();
  v.tether_budget_m = body.optional_number("tether_budget_m", 1e-3, 1000.0, "metres in (0, 1000]");
  if (body.has("entry")) {
    const auto e = body.numbers("entry", 2, "[x, y] in metres");
    v.p_WE = Eigen::Vector2d(e[0], e[1]);
  }
  if (body.has("unknown")) {
    try {
      v.unknown = parse_unknown_policy(body.text("unknown"), "unknown");
    } catch (const InputError&) {
      bad_request("unknown", "free or occupied", body.text("unknown"));
    }
  }
  v.floor_z_m = body.optional_number("floor_z_m", -1e6, 1e6, "a height in metres");
}

void read_next_goal_request(const Body& body, NextGoalRequest& r) {
  if (!body.has("grid") || !body.at("grid").is_object())
    bad_request("grid", "an object: origin, resolution_m, width, height, occupancy");
  const json& grid = body.at("grid");
  for (const auto& [key, value] : grid.items())
    if (key != "origin" && key != "resolution_m" && key != "width" && key != "height" &&
        key != "occupancy")
      bad_request("grid." + key, "one of the fields origin, resolution_m, width, height, occupancy",
                  key);
  const auto dim = [&](const char* key) {
    if (!grid.contains(key) || !grid.at(key).is_number_integer() ||
        grid.at(key).get<long long>() < 1 || grid.at(key).get<long long>() > 4096)
      bad_request(std::string("grid.") + key, "an integer in [1, 4096]",
                  grid.value(key, json()).dump());
    return static_cast<int>(grid.at(key).get<long long>());
  };
  r.geometry.width = dim("width");
  r.geometry.height = dim("height");
  if (!grid.contains("resolution_m"))
    bad_request("grid.resolution_m", "metres in [0.005, 10] (required)");
  r.geometry.resolution_m = Body::number_of(grid.at("resolution_m"), "grid.resolution_m", 0.005,
                                            10.0, "metres in [0.005, 10]");
  if (!grid.contains("origin")) bad_request("grid.origin", "[x, y] in metres (required)");
  const auto o = Body::numbers_of(grid.at("origin"), "grid.origin", 2, "[x, y] in metres");
  r.geometry.origin_x_m = o[0];
  r.geometry.origin_y_m = o[1];
  const std::size_t n = r.geometry.size();
  if (!grid.contains("occupancy") || !grid.at("occupancy").is_array() ||
      grid.at("occupancy").size() != n)
    bad_request(
        "grid.occupancy",
        fmt::format("an array of width x height = {} cells, each -1 (unknown) or 0..100", n));
  r.occupancy.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    const json& v = grid.at("occupancy")[k];
    if (!v.is_number_integer() || v.get<long long>() < -1 || v.get<long long>() > 100)
      bad_request(fmt::format("grid.occupancy[{}]", k),
                  "-1 (unknown) or an integer 0..100 (percent occupied)", v.dump());
    const long long x = v.get<long long>();
    r.occupancy.push_back(x < 0 ? -1.0f : static_cast<float>(x) / 100.0f);
  }
  const auto per_cell = [&](const char* key, const char* what, std::vector<float>& out) {
    if (!body.has(key)) return;
    const json& q = body.at(key);
    if (!q.is_array() || q.size() != n)
      bad_request(key, fmt::format("an array of {} values, {} each", n, what));
    out.reserve(n);
    for (std::size_t k = 0; k < n; ++k)
      out.push_back(
          static_cast<float>(Body::number_of(q[k], fmt::format("{}[{}]", key, k), 0.0, 1.0, what)));
  };
  per_cell("object_probability", "a probability in [0, 1]", r.object_probability);
  per_cell("object_confidence", "a confidence in [0, 1]", r.object_confidence);
  const auto p = body.numbers("pose", 3, "[x, y, yaw] in metres and radians");
  r.pose = {p[0], p[1], p[2]};
  if (body.has("velocity")) {
    const auto v = body.numbers("velocity", 2, "[vx, vy] in m/s");
    r.velocity_W = {v[0], v[1]};
  }
  r.method = body.text("method", "cdos");
  if (auto v = body.optional_number("ir_fov_rad", 1e-3, 6.3, "radians in (0, 2 pi]"))
    r.ir_fov_rad = *v;
  if (auto v = body.optional_number("ir_range_m", 0.01, 100.0, "metres in (0, 100]"))
    r.ir_range_m = *v;
  if (auto v = body.optional_number("camera_range_m", 0.01, 100.0, "metres in (0, 100]"))
    r.camera_range_m = *v;
  r.seed = body.seed();
}

}  // namespace ferret::internal
