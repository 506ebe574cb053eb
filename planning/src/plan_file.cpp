#include "ferret/planning/plan_file.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ferret/core/atomic_file.hpp"
#include "ferret/core/error.hpp"

namespace ferret {
namespace {

using json = nlohmann::json;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

// Typed access with errors that name the file and the field.
struct Reader {
  const std::string& source;

  const json& need(const json& obj, const std::string& key, const std::string& path) const {
    if (!obj.is_object() || !obj.contains(key))
      throw InputError(source, path + key, "a value (required field missing)");
    return obj.at(key);
  }
  double number(const json& v, const std::string& path) const {
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      throw InputError(source, path, "a finite number", v.dump());
    return v.get<double>();
  }
  double number_at(const json& obj, const std::string& key, const std::string& path) const {
    return number(need(obj, key, path), path + key);
  }
  std::string string_at(const json& obj, const std::string& key, const std::string& path) const {
    const json& v = need(obj, key, path);
    if (!v.is_string()) throw InputError(source, path + key, "a string", v.dump());
    return v.get<std::string>();
  }
  Eigen::VectorXd numbers(const json& v, std::size_t n, const std::string& path) const {
    if (!v.is_array() || v.size() != n)
      throw InputError(source, path, "a list of " + std::to_string(n) + " numbers", v.dump());
    Eigen::VectorXd out(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i)
      out[static_cast<Eigen::Index>(i)] = number(v[i], path + "[" + std::to_string(i) + "]");
    return out;
  }
};

void read_states(const Reader& r, const json& doc, PlanFile& plan) {
  const json& states = r.need(doc, "states", "");
  if (!states.is_array() || states.empty())
    throw InputError(r.source, "states", "a non-empty list of states");
  for (std::size_t i = 0; i < states.size(); ++i) {
    const std::string path = "states[" + std::to_string(i) + "].";
    Waypoint w;
    w.t_s = r.number_at(states[i], "t_s", path);
    w.x_m = r.number_at(states[i], "x_m", path);
    w.y_m = r.number_at(states[i], "y_m", path);
    w.z_m = r.number_at(states[i], "z_m", path);
    w.yaw_rad = r.number_at(states[i], "yaw_rad", path);
    if (states[i].contains("tether_length_m") && !states[i]["tether_length_m"].is_null())
      w.tether_length_m = r.number_at(states[i], "tether_length_m", path);
    plan.states.push_back(w);
  }
}

PlanFile parse_json(const std::string& text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw InputError(source, "", "valid JSON", e.what());
  }
  const Reader r{source};
  if (!doc.is_object()) throw InputError(source, "", "a JSON object (a ferret plan)");
  PlanFile plan;
  if (!doc.contains("format")) {
    // Another tool's plan: its states, nothing else (the robot is the command line's).
    if (!doc.contains("states"))
      throw InputError(source, "",
                       "a ferret plan (\"format\": \"ferret-plan\") or an object with \"states\"");
    plan.robot_known = false;
    read_states(r, doc, plan);
    return plan;
  }
  if (r.string_at(doc, "format", "") != "ferret-plan")
    throw InputError(source, "format", "\"ferret-plan\"", doc["format"].dump());
  const double version = r.number_at(doc, "version", "");
  if (version != 1.0) throw InputError(source, "version", "1", doc["version"].dump());
  const std::string robot = r.string_at(doc, "robot", "");
  if (robot == "uav")
    plan.robot = PlanRobot::kUav;
  else if (robot == "uav_with_ugv")
    plan.robot = PlanRobot::kUavWithUgv;
  else if (robot == "ugv")
    plan.robot = PlanRobot::kUgv;
  else
    throw InputError(source, "robot", "\"uav\", \"uav_with_ugv\" or \"ugv\"", robot);
  if (doc.contains("frame")) plan.frame = r.string_at(doc, "frame", "");
  if (plan.frame != "world") throw InputError(source, "frame", "\"world\"", plan.frame);
  if (doc.contains("unknown_policy")) {
    const std::string policy = r.string_at(doc, "unknown_policy", "");
    if (policy != "free" && policy != "occupied")
      throw InputError(source, "unknown_policy", "\"free\" or \"occupied\"", policy);
    plan.unknown_policy = parse_unknown_policy(policy, source);
  }
  if (doc.contains("bounds")) {
    const json& b = doc["bounds"];
    Aabb3 box{r.numbers(r.need(b, "min", "bounds."), 3, "bounds.min"),
              r.numbers(r.need(b, "max", "bounds."), 3, "bounds.max")};
    if ((box.lo.array() > box.hi.array()).any())
      throw InputError(source, "bounds", "min <= max on every axis");
    plan.bounds = box;
  }
  if (doc.contains("limits")) {
    const json& l = doc["limits"];
    if (l.contains("max_velocity_mps"))
      plan.max_velocity_mps = r.number_at(l, "max_velocity_mps", "limits.");
    if (l.contains("max_acceleration_mps2"))
      plan.max_acceleration_mps2 = r.number_at(l, "max_acceleration_mps2", "limits.");
    if (l.contains("max_yaw_rate_radps"))
      plan.max_yaw_rate_radps = r.number_at(l, "max_yaw_rate_radps", "limits.");
  }
  if (doc.contains("robot_model")) plan.robot_model = r.string_at(doc, "robot_model", "");
  if (doc.contains("released_length_m")) {
    plan.released_length_m = r.number_at(doc, "released_length_m", "");
    if (plan.released_length_m < 0) throw InputError(source, "released_length_m", "a length >= 0");
  }
  if (doc.contains("tether")) {
    const json& t = doc["tether"];
    PlanTether tether;
    tether.p_WE = r.numbers(r.need(t, "entry", "tether."), 2, "tether.entry");
    tether.total_length_m = r.number_at(t, "total_length_m", "tether.");
    tether.entry_offset_m = r.number_at(t, "entry_offset_m", "tether.");
    if (tether.total_length_m <= 0 || tether.entry_offset_m < 0 ||
        tether.entry_offset_m > tether.total_length_m)
      throw InputError(source, "tether",
                       "0 <= entry_offset_m <= total_length_m and total_length_m > 0");
    if (t.contains("initial_wraps")) {
      const json& w = t["initial_wraps"];
      if (!w.is_array()) throw InputError(source, "tether.initial_wraps", "a list", w.dump());
      for (std::size_t i = 0; i < w.size(); ++i) {
        const std::string path = "tether.initial_wraps[" + std::to_string(i) + "].";
        WrapPoint wp;
        wp.p_W = r.numbers(r.need(w[i], "p", path), 2, path + "p");
        const double side = r.number_at(w[i], "side", path);
        if (side != 1.0 && side != -1.0)
          throw InputError(source, path + "side", "1 or -1", w[i]["side"].dump());
        wp.side = static_cast<int>(side);
        tether.initial_wraps.push_back(wp);
      }
    }
    plan.tether = tether;
  }
  if (plan.robot == PlanRobot::kUgv && !plan.tether)
    throw InputError(source, "tether", "a tether section for a miniUGV plan");
  read_states(r, doc, plan);
  if (doc.contains("planner") && doc["planner"].is_object()) {
    const json& p = doc["planner"];
    if (p.contains("name") && p["name"].is_string()) plan.planner = p["name"];
    if (p.contains("planning_time_s") && p["planning_time_s"].is_number())
      plan.planning_time_s = p["planning_time_s"];
    if (p.contains("seed") && p["seed"].is_number_unsigned()) plan.seed = p["seed"];
    if (p.contains("world") && p["world"].is_string()) plan.world = p["world"];
  }
  return plan;
}

PlanFile parse_csv(const std::string& text, const std::string& source) {
  PlanFile plan;
  plan.robot_known = false;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  bool seen_content = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    const std::string where = "line " + std::to_string(line_no);
    if (!seen_content && line.find_first_of("0123456789") == std::string::npos) {
      seen_content = true;
      continue;  // the header: the first line that is not a comment, without numbers
    }
    seen_content = true;
    if (cells.size() != 5)
      throw InputError(source, where, "5 comma-separated numbers: t,x,y,z,yaw", line);
    double v[5];
    for (int k = 0; k < 5; ++k) {
      std::size_t used = 0;
      try {
        v[k] = std::stod(cells[k], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || cells[k].find_first_not_of(" \t", used) != std::string::npos ||
          !std::isfinite(v[k]))
        throw InputError(source, where, "5 comma-separated numbers: t,x,y,z,yaw", line);
    }
    Waypoint w;
    w.t_s = v[0];
    w.x_m = v[1];
    w.y_m = v[2];
    w.z_m = v[3];
    w.yaw_rad = v[4];
    plan.states.push_back(w);
  }
  if (plan.states.empty()) throw InputError(source, "", "at least one t,x,y,z,yaw line");
  return plan;
}

}  // namespace

const char* to_string(PlanRobot robot) {
  switch (robot) {
    case PlanRobot::kUav:
      return "uav";
    case PlanRobot::kUavWithUgv:
      return "uav_with_ugv";
    case PlanRobot::kUgv:
      return "ugv";
  }
  return "?";
}

std::string plan_to_json(const PlanFile& plan) {
  json doc;
  doc["format"] = "ferret-plan";
  doc["version"] = 1;
  doc["robot"] = to_string(plan.robot);
  doc["frame"] = plan.frame;
  if (!plan.robot_model.empty()) doc["robot_model"] = plan.robot_model;
  // No planning time: a plan file depends only on its inputs and seed (same bytes).
  doc["planner"] = {{"name", plan.planner}, {"seed", plan.seed}, {"world", plan.world}};
  if (plan.unknown_policy) doc["unknown_policy"] = to_string(*plan.unknown_policy);
  if (plan.bounds) doc["bounds"] = {{"min", vec(plan.bounds->lo)}, {"max", vec(plan.bounds->hi)}};
  if (plan.max_velocity_mps || plan.max_acceleration_mps2 || plan.max_yaw_rate_radps) {
    doc["limits"] = json::object();
    if (plan.max_velocity_mps) doc["limits"]["max_velocity_mps"] = *plan.max_velocity_mps;
    if (plan.max_acceleration_mps2)
      doc["limits"]["max_acceleration_mps2"] = *plan.max_acceleration_mps2;
    if (plan.max_yaw_rate_radps) doc["limits"]["max_yaw_rate_radps"] = *plan.max_yaw_rate_radps;
  }
  if (plan.robot == PlanRobot::kUavWithUgv) doc["released_length_m"] = plan.released_length_m;
  if (plan.tether) {
    json wraps = json::array();
    for (const auto& w : plan.tether->initial_wraps)
      wraps.push_back({{"p", {w.p_W.x(), w.p_W.y()}}, {"side", w.side}});
    doc["tether"] = {{"entry", {plan.tether->p_WE.x(), plan.tether->p_WE.y()}},
                     {"total_length_m", plan.tether->total_length_m},
                     {"entry_offset_m", plan.tether->entry_offset_m},
                     {"initial_wraps", wraps}};
  }
  json states = json::array();
  for (const Waypoint& w : plan.states) {
    json s = {
        {"t_s", w.t_s}, {"x_m", w.x_m}, {"y_m", w.y_m}, {"z_m", w.z_m}, {"yaw_rad", w.yaw_rad}};
    if (std::isfinite(w.tether_length_m)) s["tether_length_m"] = w.tether_length_m;
    states.push_back(s);
  }
  doc["states"] = states;
  return doc.dump(1) + "\n";
}

void save_plan(const PlanFile& plan, const std::filesystem::path& path) {
  write_text_atomically(path, plan_to_json(plan));
}

PlanFile parse_plan(const std::string& text, const std::string& source) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos)
    throw InputError(source, "", "a plan (JSON or CSV of t,x,y,z,yaw)", "an empty file");
  return text[first] == '{' || text[first] == '[' ? parse_json(text, source)
                                                  : parse_csv(text, source);
}

PlanFile load_plan(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "a readable plan file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_plan(ss.str(), path.string());
}

}  // namespace ferret
