// `ferret explore`: one simulated object search in a map_server hidden space.
//   ferret explore --map examples/maps/sparse.yaml --start 1,4,0 --object 9,6
//                  --method cdos --seed 1 --out out/
// Prints the time to find, the path length and the number of decisions; with --out,
// writes G.png, O.png, G_O.png (the paper's map figure) and log.json. With --retrieve,
// the miniUGV's whole mission (docs/mission.md): the transitions, then the outcome.

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/mission/exploration_run.hpp"
#include "ferret/mission/search_robot.hpp"
#include "ferret/mission/ugv_mission_log.hpp"
#include "ferret/mission/ugv_mission_run.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::string map, start, object, method = "cdos", out, mission, robot;
  std::uint64_t seed = 1;
  // Unset: the robot's value (--robot), else the paper's miniUGV model (SensorOptions).
  std::optional<double> camera_fov_deg, ir_fov_deg, camera_range_m, ir_range_m;
  std::optional<double> max_velocity_mps, max_yaw_rate_radps;
  double time_limit_s = 300;
  std::string candidates = "fv";
  bool closest_approach = false;
  std::string planner =
      "grid";             // "ompl": the frontier valid-state sampler with PRM (docs/planning.md)
  bool retrieve = false;  // the miniUGV's whole mission (ugv/mini_ugv_mission.hpp)
};

void check_positive(double value, const char* option) {
  if (!(value > 0)) throw InputError(option, "", "a number > 0", std::to_string(value));
}

// --retrieve: search, servo, grasp, return, wait for the winch; the transitions print
// as they happen (simulated time), then the outcome.
void run_retrieval(const Options& o, const OccupancyMap2D& map, const Pose2& start,
                   const std::optional<Eigen::Vector2d>& object, const ExplorationSettings& s,
                   const std::string& robot_name) {
  UgvMissionRunSettings settings;
  settings.exploration = s;
  settings.ugv.explore_timeout_s = o.time_limit_s;
  UgvMissionRecorder recorder;  // mission.mcap, with --out
  TransitionLog log;
  log.on_transition([&](const Transition& t) {
    std::printf("%s\n", TransitionLog::format(t).c_str());
    std::fflush(stdout);
    if (!o.out.empty()) recorder.transition(t);
  });
  const UgvMissionRunResult r =
      run_ugv_mission(map, start, object, settings, o.seed, &log,
                      o.out.empty() ? UgvMissionTickHook{} : recorder.hook());
  std::printf(
      "method: %s\noutcome: %s\ntime_s: %.2f\npath_m: %.2f\nbattery_left: %.3f\n"
      "grasp_attempts: %d\ntether_max_m: %.2f\ntether_max_in: %s\n",
      s.method.c_str(), std::string(to_string(r.outcome)).c_str(), r.time_s, r.path_m,
      r.battery_left, r.grasp_attempts, r.max_tether_m,
      std::string(to_string(r.max_tether_state)).c_str());
  if (o.out.empty()) return;

  const fs::path out(o.out);
  OutputSet files(out, OutputKind::kDirectory);
  EpisodeResult figure;  // the figure of the search part, drawn from the mission's maps
  figure.found = r.found_right;
  figure.time_s = r.time_s;
  figure.path_m = r.path_m;
  figure.decisions = r.decisions;
  figure.end_reason = std::string(to_string(r.outcome));
  figure.found_W = r.found_W.value_or(Eigen::Vector2d::Zero());
  figure.trajectory = r.trajectory;
  figure.grid = r.grid;
  figure.objects = r.objects;
  // With no object the figure marks it outside the map, where nothing is drawn.
  const Eigen::Vector2d drawn = object.value_or(Eigen::Vector2d(-1e6, -1e6));
  write_exploration_images(
      map, drawn, figure, files.staging_dir(),
      fmt::format("{}, {} mission{}, seed {}: {}", fs::path(o.map).filename().string(), s.method,
                  robot_name.empty() ? std::string() : ", robot " + robot_name, o.seed,
                  to_string(r.outcome)));
  nlohmann::json j;
  j["map"] = o.map;
  j["method"] = s.method;
  j["seed"] = o.seed;
  j["start"] = {start.x_m, start.y_m, start.yaw_rad};
  j["object"] = object ? nlohmann::json{object->x(), object->y()} : nlohmann::json();
  j["result"] = {
      {"outcome", to_string(r.outcome)},
      {"final_state", to_string(r.final_state)},
      {"time_s", r.time_s},
      {"path_m", r.path_m},
      {"battery_left", r.battery_left},
      {"grasp_attempts", r.grasp_attempts},
      {"decisions", r.decisions},
      {"tether_max_m", r.max_tether_m},
      {"tether_max_in", to_string(r.max_tether_state)},
      {"found_at", r.found_W ? nlohmann::json{r.found_W->x(), r.found_W->y()} : nlohmann::json()}};
  auto& transitions = j["transitions"] = nlohmann::json::array();
  for (const auto& t : r.transitions)
    transitions.push_back({{"t_s", t.t_s}, {"from", t.from}, {"to", t.to}, {"reason", t.reason}});
  auto& trajectory = j["trajectory"] = nlohmann::json::array();  // every 0.1 s
  for (std::size_t k = 0; k < r.trajectory.size(); k += 2)
    trajectory.push_back({r.trajectory[k].x_m, r.trajectory[k].y_m, r.trajectory[k].yaw_rad});
  files.write_text("log.json", j.dump(1) + "\n");
  files.write_text("mission.mcap", recorder.finish(r, object));
  files.commit();
  std::printf("wrote: %s %s %s %s %s\n", (out / "G.png").c_str(), (out / "O.png").c_str(),
              (out / "G_O.png").c_str(), (out / "log.json").c_str(),
              (out / "mission.mcap").c_str());
}

void run(const Options& o) {
  const auto start_v = parse_number_list(o.start, 3, "--start");
  // "none": an empty hidden space (only for --retrieve, where "no object" is a result).
  const bool no_object = o.retrieve && o.object == "none";
  const auto object_v =
      no_object ? std::vector<double>{0.0, 0.0} : parse_number_list(o.object, 2, "--object");
  // The method and the frontier planner that runs it, or an InputError naming why not.
  const std::string policy =
      exploration_policy_for(o.method, parse_frontier_planner(o.planner, "--planner"));
  if (o.candidates != "fv" && o.candidates != "fg")
    throw InputError("--cdos-candidates", "", "fv or fg", o.candidates);
  for (const auto& [v, name] : {std::pair{o.camera_fov_deg, "--camera-fov-deg"},
                                {o.ir_fov_deg, "--ir-fov-deg"},
                                {o.camera_range_m, "--camera-range-m"},
                                {o.ir_range_m, "--ir-range-m"},
                                {o.max_velocity_mps, "--max-velocity-mps"},
                                {o.max_yaw_rate_radps, "--max-yaw-rate-radps"},
                                {std::optional<double>(o.time_limit_s), "--time-limit"}})
    if (v) {
      check_positive(*v, name);
      if (!std::isfinite(*v) || *v > 1e6)
        throw InputError(name, "", "a finite number <= 1e6", std::to_string(*v));
    }
  for (const auto& [v, name] :
       {std::pair{o.camera_fov_deg, "--camera-fov-deg"}, {o.ir_fov_deg, "--ir-fov-deg"}})
    if (v && *v >= 360)
      throw InputError(name, "", "a field of view below 360 degrees", std::to_string(*v));

  // The output directory is checked before the search runs.
  if (!o.out.empty()) (void)check_output_target(o.out, OutputKind::kDirectory, "--out");
  const OccupancyMap2D map = load_map_server(o.map);
  const Pose2 start{start_v[0], start_v[1], start_v[2]};
  const Eigen::Vector2d object(object_v[0], object_v[1]);
  if (!map.is_free(map.geometry.cell_at(start.x_m, start.y_m)))
    throw InputError("--start", "", "a position on a free cell of " + o.map, o.start);
  if (!no_object && !map.is_free(map.geometry.cell_at(object.x(), object.y())))
    throw InputError("--object", "", "a position on a free cell of " + o.map, o.object);

  const MissionConfig mission = load_mission_or_defaults(o.mission);
  std::optional<RobotDescription> robot;
  if (!o.robot.empty()) robot = load_robot_description(resolve_robot(o.robot, ""), mission);
  ExplorationSettings s = robot ? exploration_settings_for(*robot, mission) : ExplorationSettings{};
  s.mission = mission;
  s.method = policy;
  // The mission's ugv_limits, as a robot's limits would be.
  if (!robot) s.robot.set_limits(mission.ugv_limits);
  if (o.camera_fov_deg) s.sensors.camera_fov_rad = deg_to_rad(*o.camera_fov_deg);
  if (o.ir_fov_deg) {
    s.sensors.ir_fov_rad = deg_to_rad(*o.ir_fov_deg);
    s.sensors.ir_bearings_rad.clear();  // the robot's beams, spread evenly over the new fov
  }
  if (o.camera_range_m) s.sensors.camera_range_m = *o.camera_range_m;
  if (o.ir_range_m) s.sensors.ir_range_m = *o.ir_range_m;
  if (o.max_velocity_mps) s.robot.max_velocity_mps = *o.max_velocity_mps;
  if (o.max_yaw_rate_radps) s.robot.max_yaw_rate_radps = *o.max_yaw_rate_radps;
  s.time_limit_s = o.time_limit_s;
  s.cdos_candidates_global = o.candidates == "fg";
  s.cdos_closest_approach = o.closest_approach;
  s.record = !o.out.empty();

  if (o.retrieve) {
    run_retrieval(o, map, start, no_object ? std::nullopt : std::optional(object), s,
                  robot ? robot->name : std::string());
    return;
  }
  const EpisodeResult r = run_exploration(map, start, object, s, o.seed);

  std::printf("method: %s\nfound: %s\ntime_s: %.2f\npath_m: %.2f\ndecisions: %d\nend: %s\n",
              s.method.c_str(), r.found ? "yes" : "no", r.time_s, r.path_m, r.decisions,
              r.end_reason.c_str());
  if (o.out.empty()) return;

  const fs::path out(o.out);
  OutputSet files(out, OutputKind::kDirectory);  // the images and the log: all or none
  write_exploration_images(
      map, object, r, files.staging_dir(),
      fmt::format("{}, {}{}, object at ({:g}, {:g}), seed {}", fs::path(o.map).filename().string(),
                  s.method, robot ? ", robot " + robot->name : std::string(), object.x(),
                  object.y(), o.seed));
  nlohmann::json log;
  log["map"] = o.map;
  log["method"] = o.method;
  log["seed"] = o.seed;
  log["start"] = {start.x_m, start.y_m, start.yaw_rad};
  log["object"] = {object.x(), object.y()};
  // The values the simulator and the search used, wherever they came from.
  auto deg = [](double rad) { return std::round(rad_to_deg(rad) * 1e9) / 1e9; };  // no 29.999..
  log["sensors"] = {{"camera_fov_deg", deg(s.sensors.camera_fov_rad)},
                    {"camera_range_m", s.sensors.camera_range_m},
                    {"image_width_px", s.sensors.image_width_px},
                    {"ir_fov_deg", deg(s.sensors.ir_fov_rad)},
                    {"ir_range_m", s.sensors.ir_range_m},
                    {"ir_beams", s.sensors.ir_bearings_rad.empty()
                                     ? nlohmann::json(s.sensors.ir_beams)
                                     : nlohmann::json(s.sensors.ir_bearings_rad.size())}};
  log["robot"] = {{"urdf", robot ? nlohmann::json(robot->source) : nlohmann::json()},
                  {"max_velocity_mps", s.robot.max_velocity_mps},
                  {"max_yaw_rate_radps", s.robot.max_yaw_rate_radps},
                  {"max_acceleration_mps2", s.robot.max_acceleration_mps2},
                  {"clearance_m", s.robot.clearance_m}};
  log["dt_s"] = 1.0 / s.sensors.ir_rate_hz;
  log["result"] = {{"found", r.found},    {"time_s", r.time_s},
                   {"path_m", r.path_m},  {"decisions", r.decisions},
                   {"end", r.end_reason}, {"found_at", {r.found_W.x(), r.found_W.y()}}};
  auto& decisions = log["decisions"] = nlohmann::json::array();
  for (const auto& d : r.decision_log)
    decisions.push_back({{"t_s", d.time_s},
                         {"pose", {d.pose.x_m, d.pose.y_m, d.pose.yaw_rad}},
                         {"goal", {d.goal_W.x(), d.goal_W.y()}},
                         {"reason", d.reason},
                         {"score", d.score},
                         {"frontier_global", d.frontier_global},
                         {"frontier_visible", d.frontier_visible},
                         {"evidence_cells", d.evidence_cells}});
  auto& trajectory = log["trajectory"] = nlohmann::json::array();  // every 0.1 s
  for (std::size_t k = 0; k < r.trajectory.size(); k += 2)
    trajectory.push_back({r.trajectory[k].x_m, r.trajectory[k].y_m, r.trajectory[k].yaw_rad});
  files.write_text("log.json", log.dump(1) + "\n");
  files.commit();
  std::printf("wrote: %s %s %s %s\n", (out / "G.png").c_str(), (out / "O.png").c_str(),
              (out / "G_O.png").c_str(), (out / "log.json").c_str());
}

const CommandRegistration kExplore{
    "explore", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      auto* sub = app.add_subcommand("explore", "Simulate one object search in a hidden-space map");
      sub->add_option("--map", o->map, "Hidden space, map_server YAML")->required();
      sub->add_option("--start", o->start, "Start pose x,y,yaw (m, m, rad)")->required();
      sub->add_option("--object", o->object, "Object position x,y (m)")->required();
      std::string methods;
      for (const auto& n : exploration_policy_names()) methods += (methods.empty() ? "" : ", ") + n;
      sub->add_option("--method", o->method, "one of " + methods + " (--list-methods)")
          ->capture_default_str();
      // Before the required options are checked, so it needs none.
      sub->add_flag_callback(
          "--list-methods",
          [] {
            for (const auto& n : exploration_policy_names()) std::printf("%s\n", n.c_str());
            throw CLI::Success();
          },
          "Print the registered search methods, one a line, and exit");
      add_seed_option(sub, o->seed, "Seed of the sensor noise");
      sub->add_option("-o,--out", o->out,
                      "Directory for G.png, O.png, G_O.png and log.json (default: none, the "
                      "summary only)");
      add_hidden_alias(sub, "--output", o->out);
      add_hidden_alias(sub, "--output-dir", o->out);
      add_mission_option(sub, o->mission);
      add_robot_option(sub, o->robot,
                       "none: the paper's miniUGV sensor model, 90 deg / 4 m camera, 30 deg / "
                       "4 m IR, 2 m/s");
      // Each overrides the robot's value (docs/object_search.md); old spellings hidden.
      auto override_option = [&](const std::string& name, const std::string& old,
                                 std::optional<double>& value, const std::string& help) {
        sub->add_option(name, value, help);
        add_hidden_alias(sub, old, value);
      };
      override_option("--camera-fov-deg", "--camera-fov", o->camera_fov_deg,
                      "Camera fov alpha, degrees (default: the robot's, else 90)");
      override_option("--ir-fov-deg", "--ir-fov", o->ir_fov_deg,
                      "IR fov beta, degrees (default: the robot's, else 30)");
      override_option("--camera-range-m", "--camera-range", o->camera_range_m,
                      "D_cam, metres (default: the robot's, else 4)");
      override_option("--ir-range-m", "--ir-range", o->ir_range_m,
                      "D_IR, metres (default: the robot's, else 4)");
      override_option("--max-velocity-mps", "--max-velocity", o->max_velocity_mps,
                      "v_max, m/s (default: the robot's limit, else the mission's ugv_limits, 2)");
      override_option("--max-yaw-rate-radps", "--max-yaw-rate", o->max_yaw_rate_radps,
                      "rad/s (default: the robot's limit, else the mission's ugv_limits, 2)");
      sub->add_option("--time-limit", o->time_limit_s, "Simulated seconds before giving up")
          ->capture_default_str();
      sub->add_option("--planner", o->planner,
                      "grid, or ompl: PRM with the frontier valid-state sampler (cdos, rapid)")
          ->capture_default_str();
      sub->add_option("--cdos-candidates", o->candidates, "cdos: score fv (F_v) or fg (F_g)")
          ->capture_default_str();
      sub->add_flag("--closest-approach", o->closest_approach,
                    "cdos: d_{t+1} is the closest approach on the way");
      sub->add_flag("--retrieve", o->retrieve,
                    "The miniUGV's whole mission: search, servo to the object, grasp it with "
                    "the EPM, return to the start and wait for the winch (--object none: an "
                    "empty hidden space); --time-limit bounds the search");
      sub->callback([o, sub] {
        refuse_empty_out(sub, o->out);
        run(*o);
      });
    }};

}  // namespace
}  // namespace ferret::cli
