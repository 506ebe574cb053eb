#include "ferret/planning/plan_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "ferret/core/atomic_file.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"

namespace ferret {
namespace {

using json = nlohmann::json;

json vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

// The one place numbers are judged (the shared number type replaces it): finite, and a
// coordinate within kMaxCoordinate_m so that no check does work proportional to an
// unchecked length.
constexpr double kMaxCoordinate_m = 1e5;
constexpr std::size_t kMaxStates = 1'000'000;
constexpr int kMaxJsonDepth = 64;
const std::string kFinite = "a finite number";
const std::string kCoordinate = "a coordinate within +-100000 m";
// Times differ by at most 2e12 s, so no duration overflows (Unix times fit).
constexpr double kMaxTime_s = 1e12;
const std::string kTime = "a time within +-1e12 s";

std::string show(double v) { return fmt::format("{}", v); }

// Messages are one printable line: control and non-ASCII bytes of a file's text are
// escaped, and an echoed value is cut short (a whole array could be megabytes).
std::string printable(const std::string& text, std::size_t max_chars = 80) {
  std::string out;
  for (const char c : text) {
    if (out.size() >= max_chars) return out + "...";
    const auto u = static_cast<unsigned char>(c);
    out += u >= 0x20 && u < 0x7f ? std::string(1, c) : fmt::format("\\x{:02x}", u);
  }
  return out;
}
InputError input_error(const std::string& source, const std::string& field,
                       const std::string& expected, const std::string& got = {}) {
  return InputError(source, printable(field, 200), expected, printable(got));
}

// Strict CSV cells: core's one number parser (no hex, nan/inf, trailing text, 1e400).
std::optional<double> strict_number(const std::string& cell) { return parse_finite(cell); }

// Nesting deeper than kMaxJsonDepth is refused before nlohmann (which recurses) sees it.
void check_depth(const std::string& text, const std::string& source) {
  int depth = 0, line = 1;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (c == '\n') ++line;
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        throw input_error(source, fmt::format("line {}", line),
                          fmt::format("JSON nested at most {} levels deep", kMaxJsonDepth),
                          "deeper nesting");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

// Where the parser is, for messages: the dotted path of the value being read, and
// every object's keys (nlohmann keeps the last of a duplicate silently).
class PathTracker {
 public:
  explicit PathTracker(const std::string& source) : source_(source) {}

  bool event(int /*depth*/, json::parse_event_t ev, json& parsed) {
    switch (ev) {
      case json::parse_event_t::object_start:
        frames_.push_back({false, {}, {}, 0});
        break;
      case json::parse_event_t::array_start:
        frames_.push_back({true, {}, {}, 0});
        break;
      case json::parse_event_t::key: {
        Frame& f = frames_.back();
        f.key = parsed.get<std::string>();
        if (!f.keys.insert(f.key).second)
          throw input_error(source_, path(), "each key once in an object", "a duplicate key");
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        next();
        break;
      case json::parse_event_t::value:
        next();
        break;
    }
    return true;
  }
  // The dotted path of the current value ("states[3].x_m").
  [[nodiscard]] std::string path() const {
    std::string p;
    for (const Frame& f : frames_) {
      if (f.array)
        p += fmt::format("[{}]", f.index);
      else if (!f.key.empty())
        p += (p.empty() ? "" : ".") + f.key;
    }
    return p;
  }

 private:
  struct Frame {
    bool array;
    std::set<std::string> keys;
    std::string key;
    std::size_t index;
  };
  void next() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
  }
  const std::string& source_;
  std::vector<Frame> frames_;
};

json parse_json_text(const std::string& text, const std::string& source) {
  check_depth(text, source);
  PathTracker tracker(source);
  try {
    return json::parse(text, [&](int depth, json::parse_event_t ev, json& parsed) {
      return tracker.event(depth, ev, parsed);
    });
  } catch (const json::out_of_range& e) {
    // nlohmann refuses a number beyond double's range ("1e400"): name the number.
    const std::string what = e.what();
    const auto a = what.find('\''), b = what.rfind('\'');
    throw input_error(source, tracker.path(), kFinite,
                      a != std::string::npos && b > a ? what.substr(a + 1, b - a - 1) : what);
  } catch (const json::parse_error& e) {
    // The byte offset as line and column (nlohmann counts from 1, past the fault).
    const std::size_t at = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + at, '\n'));
    const std::size_t bol = text.rfind('\n', at == 0 ? 0 : at - 1);
    const std::size_t column = at - (bol == std::string::npos || at == 0 ? 0 : bol + 1) + 1;
    std::string what = e.what();
    if (const auto k = what.find("syntax error"); k != std::string::npos) what = what.substr(k);
    throw input_error(source, fmt::format("line {} column {}", line, column), "valid JSON", what);
  }
}

// Typed access with errors that name the file and the field.
struct Reader {
  const std::string& source;

  // Every key of an object one the schema knows.
  void known_keys(const json& obj, const std::string& path,
                  std::initializer_list<const char*> keys) const {
    if (!obj.is_object())
      throw input_error(source, path.empty() ? "" : path.substr(0, path.size() - 1), "an object",
                        obj.dump());
    for (const auto& item : obj.items()) {
      const std::string& key = item.key();  // not a structured binding: clang 14 lambdas
      if (std::find_if(keys.begin(), keys.end(), [&](const char* k) { return key == k; }) !=
          keys.end())
        continue;
      std::string list;
      for (const char* k : keys) list += std::string(list.empty() ? "" : ", ") + k;
      throw input_error(source, path + key, "one of the keys " + list, "an unknown key");
    }
  }
  const json& need(const json& obj, const std::string& key, const std::string& path) const {
    if (!obj.is_object() || !obj.contains(key))
      throw input_error(source, path + key, "a value (required field missing)");
    return obj.at(key);
  }
  double number(const json& v, const std::string& path) const {
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      throw input_error(source, path, kFinite, v.dump());
    return v.get<double>();
  }
  double coordinate(const json& v, const std::string& path) const {
    const double x = number(v, path);
    if (!(std::abs(x) <= kMaxCoordinate_m)) throw input_error(source, path, kCoordinate, show(x));
    return x;
  }
  double number_at(const json& obj, const std::string& key, const std::string& path) const {
    return number(need(obj, key, path), path + key);
  }
  double positive_at(const json& obj, const std::string& key, const std::string& path) const {
    const double x = number_at(obj, key, path);
    if (!(x > 0)) throw input_error(source, path + key, "a number > 0", show(x));
    return x;
  }
  double coordinate_at(const json& obj, const std::string& key, const std::string& path) const {
    return coordinate(need(obj, key, path), path + key);
  }
  std::string string_at(const json& obj, const std::string& key, const std::string& path) const {
    const json& v = need(obj, key, path);
    if (!v.is_string()) throw input_error(source, path + key, "a string", v.dump());
    return v.get<std::string>();
  }
  Eigen::VectorXd coordinates(const json& v, std::size_t n, const std::string& path) const {
    if (!v.is_array() || v.size() != n)
      throw input_error(source, path, "a list of " + std::to_string(n) + " numbers", v.dump());
    Eigen::VectorXd out(static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i)
      out[static_cast<Eigen::Index>(i)] = coordinate(v[i], path + "[" + std::to_string(i) + "]");
    return out;
  }
};

void check_state_count(std::size_t n, const std::string& source) {
  if (n > kMaxStates)
    throw input_error(source, "states", fmt::format("at most {} states", kMaxStates),
                      fmt::format("{} states", n));
}

void read_states(const Reader& r, const json& doc, PlanFile& plan) {
  const json& states = r.need(doc, "states", "");
  if (!states.is_array() || states.empty())
    throw input_error(r.source, "states", "a non-empty list of states",
                      states.is_array() ? "[]" : states.type_name());
  check_state_count(states.size(), r.source);
  plan.states.reserve(states.size());
  for (std::size_t i = 0; i < states.size(); ++i) {
    const std::string path = "states[" + std::to_string(i) + "].";
    r.known_keys(states[i], path, {"t_s", "x_m", "y_m", "z_m", "yaw_rad", "tether_length_m"});
    Waypoint w;
    w.t_s = r.number_at(states[i], "t_s", path);
    if (!(std::abs(w.t_s) <= kMaxTime_s))
      throw input_error(r.source, path + "t_s", kTime, show(w.t_s));
    w.x_m = r.coordinate_at(states[i], "x_m", path);
    w.y_m = r.coordinate_at(states[i], "y_m", path);
    w.z_m = r.coordinate_at(states[i], "z_m", path);
    w.yaw_rad = r.number_at(states[i], "yaw_rad", path);
    if (states[i].contains("tether_length_m") && !states[i]["tether_length_m"].is_null())
      w.tether_length_m = r.number_at(states[i], "tether_length_m", path);
    plan.states.push_back(w);
  }
}

PlanFile parse_json(const std::string& text, const std::string& source) {
  const json doc = parse_json_text(text, source);
  const Reader r{source};
  if (!doc.is_object())
    throw input_error(source, "", "a JSON object (a ferret plan)", doc.type_name());
  PlanFile plan;
  if (!doc.contains("format")) {
    // Another tool's plan: its states, nothing else (the robot is the command line's).
    if (!doc.contains("states"))
      throw input_error(source, "",
                        "a ferret plan (\"format\": \"ferret-plan\") or an object with \"states\"");
    r.known_keys(doc, "", {"comment", "states"});
    if (doc.contains("comment")) (void)r.string_at(doc, "comment", "");
    plan.robot_known = false;
    read_states(r, doc, plan);
    return plan;
  }
  r.known_keys(doc, "",
               {"comment", "format", "version", "robot", "frame", "robot_model", "planner",
                "unknown_policy", "bounds", "limits", "released_length_m", "tether", "states"});
  // JSON has no comments: a "comment" string is the plan's note to its reader.
  if (doc.contains("comment")) (void)r.string_at(doc, "comment", "");
  if (r.string_at(doc, "format", "") != "ferret-plan")
    throw input_error(source, "format", "\"ferret-plan\"", doc["format"].dump());
  const double version = r.number_at(doc, "version", "");
  if (version != 1.0) throw input_error(source, "version", "1", doc["version"].dump());
  const std::string robot = r.string_at(doc, "robot", "");
  if (robot == "uav")
    plan.robot = PlanRobot::kUav;
  else if (robot == "uav_with_ugv")
    plan.robot = PlanRobot::kUavWithUgv;
  else if (robot == "ugv")
    plan.robot = PlanRobot::kUgv;
  else
    throw input_error(source, "robot", "\"uav\", \"uav_with_ugv\" or \"ugv\"", robot);
  if (doc.contains("frame")) plan.frame = r.string_at(doc, "frame", "");
  if (plan.frame != "world") throw input_error(source, "frame", "\"world\"", plan.frame);
  if (doc.contains("unknown_policy")) {
    const std::string policy = r.string_at(doc, "unknown_policy", "");
    if (policy != "free" && policy != "occupied")
      throw input_error(source, "unknown_policy", "\"free\" or \"occupied\"", policy);
    plan.unknown_policy = parse_unknown_policy(policy, source);
  }
  if (doc.contains("bounds")) {
    const json& b = doc["bounds"];
    r.known_keys(b, "bounds.", {"min", "max"});
    Aabb3 box{r.coordinates(r.need(b, "min", "bounds."), 3, "bounds.min"),
              r.coordinates(r.need(b, "max", "bounds."), 3, "bounds.max")};
    if ((box.lo.array() > box.hi.array()).any())
      throw input_error(source, "bounds", "min <= max on every axis");
    plan.bounds = box;
  }
  if (doc.contains("limits")) {
    const json& l = doc["limits"];
    r.known_keys(l, "limits.", {"max_velocity_mps", "max_acceleration_mps2", "max_yaw_rate_radps"});
    if (l.contains("max_velocity_mps"))
      plan.max_velocity_mps = r.positive_at(l, "max_velocity_mps", "limits.");
    if (l.contains("max_acceleration_mps2"))
      plan.max_acceleration_mps2 = r.positive_at(l, "max_acceleration_mps2", "limits.");
    if (l.contains("max_yaw_rate_radps"))
      plan.max_yaw_rate_radps = r.positive_at(l, "max_yaw_rate_radps", "limits.");
  }
  if (doc.contains("robot_model")) plan.robot_model = r.string_at(doc, "robot_model", "");
  if (doc.contains("released_length_m")) {
    plan.released_length_m = r.coordinate_at(doc, "released_length_m", "");
    if (plan.released_length_m < 0)
      throw input_error(source, "released_length_m", "a length >= 0", show(plan.released_length_m));
  }
  if (doc.contains("tether")) {
    const json& t = doc["tether"];
    r.known_keys(t, "tether.", {"entry", "total_length_m", "entry_offset_m", "initial_wraps"});
    PlanTether tether;
    tether.p_WE = r.coordinates(r.need(t, "entry", "tether."), 2, "tether.entry");
    tether.total_length_m = r.coordinate_at(t, "total_length_m", "tether.");
    tether.entry_offset_m = r.coordinate_at(t, "entry_offset_m", "tether.");
    if (tether.total_length_m <= 0 || tether.entry_offset_m < 0 ||
        tether.entry_offset_m > tether.total_length_m)
      throw input_error(source, "tether",
                        "0 <= entry_offset_m <= total_length_m and total_length_m > 0");
    if (t.contains("initial_wraps")) {
      const json& w = t["initial_wraps"];
      if (!w.is_array()) throw input_error(source, "tether.initial_wraps", "a list", w.dump());
      if (w.size() > kMaxStates)
        throw input_error(source, "tether.initial_wraps",
                          fmt::format("at most {} wrap points", kMaxStates),
                          std::to_string(w.size()));
      for (std::size_t i = 0; i < w.size(); ++i) {
        const std::string path = "tether.initial_wraps[" + std::to_string(i) + "].";
        r.known_keys(w[i], path, {"p", "side"});
        WrapPoint wp;
        wp.p_W = r.coordinates(r.need(w[i], "p", path), 2, path + "p");
        const double side = r.number_at(w[i], "side", path);
        if (side != 1.0 && side != -1.0)
          throw input_error(source, path + "side", "1 or -1", w[i]["side"].dump());
        wp.side = static_cast<int>(side);
        tether.initial_wraps.push_back(wp);
      }
    }
    plan.tether = tether;
  }
  if (plan.robot == PlanRobot::kUgv && !plan.tether)
    throw input_error(source, "tether", "a tether section for a miniUGV plan");
  read_states(r, doc, plan);
  if (doc.contains("planner")) {
    const json& p = doc["planner"];
    r.known_keys(p, "planner.", {"name", "planning_time_s", "seed", "world"});
    if (p.contains("name")) plan.planner = r.string_at(p, "name", "planner.");
    if (p.contains("planning_time_s")) {
      plan.planning_time_s = r.number_at(p, "planning_time_s", "planner.");
      if (plan.planning_time_s < 0)
        throw input_error(source, "planner.planning_time_s", "a time >= 0 s",
                          show(plan.planning_time_s));
    }
    if (p.contains("seed")) {
      if (!p["seed"].is_number_unsigned())
        throw input_error(source, "planner.seed", "an unsigned integer", p["seed"].dump());
      plan.seed = p["seed"];
    }
    if (p.contains("world")) plan.world = r.string_at(p, "world", "planner.");
  }
  return plan;
}

// The CSV columns by name: the short names or the unit-suffixed ones of the JSON.
constexpr std::array<std::array<const char*, 2>, 5> kCsvColumns{
    {{"t", "t_s"}, {"x", "x_m"}, {"y", "y_m"}, {"z", "z_m"}, {"yaw", "yaw_rad"}}};
const std::string kCsvHeader =
    "a header naming the columns t,x,y,z,yaw (or t_s,x_m,y_m,z_m,yaw_rad)";

std::vector<std::string> split_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string::size_type from = 0;
  for (;;) {
    const auto comma = line.find(',', from);
    cells.push_back(
        line.substr(from, comma == std::string::npos ? std::string::npos : comma - from));
    if (comma == std::string::npos) return cells;
    from = comma + 1;
  }
}

PlanFile parse_csv(const std::string& text, const std::string& source) {
  PlanFile plan;
  plan.robot_known = false;
  std::istringstream in(text);
  std::string line;
  std::size_t line_no = 0;
  std::vector<int> column_of;  // cell index -> field 0..4 (t, x, y, z, yaw)
  std::vector<std::string> names;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    const std::string where = fmt::format("line {}", line_no);
    std::vector<std::string> cells = split_cells(line);
    if (column_of.empty()) {
      // The header: every column named once, by name, in any order.
      std::array<bool, 5> seen{};
      for (std::size_t c = 0; c < cells.size(); ++c) {
        std::string name = cells[c];
        name.erase(0, name.find_first_not_of(" \t"));
        name.erase(name.find_last_not_of(" \t") + 1);
        const std::string at = fmt::format("{} column {}", where, c + 1);
        int field = -1;
        for (int k = 0; k < 5; ++k)
          if (name == kCsvColumns[k][0] || name == kCsvColumns[k][1]) field = k;
        if (field < 0)
          throw input_error(source, at, kCsvHeader,
                            strict_number(name) ? "a number (no header line)" : "'" + name + "'");
        if (seen[field])
          throw input_error(source, at, kCsvHeader + ", each once",
                            fmt::format("'{}' again", name));
        seen[field] = true;
        column_of.push_back(field);
        names.push_back(name);
      }
      for (int k = 0; k < 5; ++k)
        if (!seen[k])
          throw input_error(source, where, kCsvHeader,
                            fmt::format("no column '{}'", kCsvColumns[k][0]));
      continue;
    }
    if (cells.size() != column_of.size())
      throw input_error(
          source, where,
          fmt::format("{} comma-separated numbers (the header's columns)", column_of.size()),
          fmt::format("{} cells", cells.size()));
    double v[5];
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const auto x = strict_number(cells[c]);
      const std::string at = fmt::format("{} column {} ({})", where, c + 1, names[c]);
      if (!x) throw input_error(source, at, kFinite, "'" + cells[c] + "'");
      const int field = column_of[c];
      if (field >= 1 && field <= 3 && !(std::abs(*x) <= kMaxCoordinate_m))
        throw input_error(source, at, kCoordinate, cells[c]);
      if (field == 0 && !(std::abs(*x) <= kMaxTime_s))
        throw input_error(source, at, kTime, cells[c]);
      v[field] = *x;
    }
    check_state_count(plan.states.size() + 1, source);
    Waypoint w;
    w.t_s = v[0];
    w.x_m = v[1];
    w.y_m = v[2];
    w.z_m = v[3];
    w.yaw_rad = v[4];
    plan.states.push_back(w);
  }
  if (column_of.empty()) throw input_error(source, "", kCsvHeader, "no header line");
  if (plan.states.empty())
    throw input_error(source, "", "at least one state after the header", "none");
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
    throw input_error(source, "", "a plan (JSON, or CSV with a header t,x,y,z,yaw)",
                      "an empty file");
  return text[first] == '{' || text[first] == '[' ? parse_json(text, source)
                                                  : parse_csv(text, source);
}

PlanFile load_plan(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw input_error(path.string(), "", "a readable plan file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_plan(ss.str(), path.string());
}

}  // namespace ferret
