#include "cli_options.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <utility>

#include "ferret/core/error.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/mission/mission_setup.hpp"
#include "ferret/perception/camera_info.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::cli {

CLI::Option* add_world_option(CLI::App* cmd, std::string& world, bool required,
                              std::string_view what) {
  auto* opt = cmd->add_option("--world", world, std::string(what));
  if (required) opt->required();
  return opt;
}

CLI::Option* add_robot_option(CLI::App* cmd, std::string& robot, std::string_view default_text) {
  return cmd->add_option("--robot", robot,
                         fmt::format("robot URDF, or a shipped model: {} (default: {})",
                                     fmt::join(shipped_model_names(), ", "), default_text));
}

CLI::Option* add_mission_option(CLI::App* cmd, std::string& mission, bool config_alias) {
  auto* opt = cmd->add_option("--mission", mission,
                              "mission YAML: motion limits, tether L and l_0, object search "
                              "(default: the built-in values, docs/configuration.md)");
  if (config_alias) add_hidden_alias(cmd, "--config", mission);
  return opt;
}

CLI::Option* add_out_option(CLI::App* cmd, std::string& out, std::string_view what) {
  auto* opt = cmd->add_option("-o,--out", out, std::string(what) + " (required)");
  add_hidden_alias(cmd, "--output", out);
  add_hidden_alias(cmd, "--output-dir", out);
  return opt;
}

void require_out(const std::string& out, std::string_view what) {
  if (out.empty()) throw InputError("--out", "", std::string(what) + " (-o/--out is required)");
}

std::filesystem::path checked_out_file(const std::string& out, std::string_view what) {
  require_out(out, what);
  return check_output_target(out, OutputKind::kFile, "--out");
}

std::filesystem::path checked_out_dir(const std::string& out, std::string_view what) {
  require_out(out, what);
  return check_output_target(out, OutputKind::kDirectory, "--out");
}

void refuse_empty_out(const CLI::App* cmd, const std::string& out) {
  if (!out.empty()) return;
  for (const char* name : {"--out", "--output", "--output-dir"})
    if (cmd->get_option_no_throw(name) != nullptr && cmd->count(name) > 0)
      throw InputError("--out", "", "a non-empty output path", "''");
}

CLI::Option* add_tether_budget_option(CLI::App* cmd, std::optional<double>& budget_m,
                                      std::string_view default_text) {
  auto* opt = cmd->add_option(
      "--tether-budget", budget_m,
      fmt::format("taut tether length the miniUGV may use on the floor, L - l_0, metres "
                  "(default: {})",
                  default_text));
  add_hidden_alias(cmd, "--tether", budget_m);
  add_hidden_alias(cmd, "--tether-max", budget_m);
  return opt;
}

std::optional<double> checked_tether_budget(const std::optional<double>& budget_m) {
  if (budget_m && !(std::isfinite(*budget_m) && *budget_m > 0.0 && *budget_m <= 1000.0))
    throw InputError("--tether-budget", "", "a taut tether length in (0, 1000] m",
                     fmt::format("{}", *budget_m));
  return budget_m;
}

CLI::Option* add_bounds_option(CLI::App* cmd, std::string& bounds, std::string_view meaning) {
  return cmd->add_option("--bounds", bounds,
                         fmt::format("x0,y0,z0,x1,y1,z1 in metres: {}", meaning));
}

std::optional<Aabb3> parse_bounds(const std::string& text, const std::string& option) {
  if (text.empty()) return std::nullopt;
  const auto b = parse_number_list(text, 6, option);
  Aabb3 box{{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
  if ((box.lo.array() >= box.hi.array()).any())
    throw InputError(option, "", "x0,y0,z0,x1,y1,z1 (metres) with x0 < x1, y0 < y1, z0 < z1", text);
  return box;
}

CLI::Option* add_seed_option(CLI::App* cmd, std::uint64_t& seed, std::string_view what) {
  return cmd->add_option("--seed", seed, std::string(what))->capture_default_str();
}

CLI::Option* add_camera_option(CLI::App* cmd, std::string& camera_yaml, std::string_view role) {
  return cmd->add_option("--camera", camera_yaml,
                         fmt::format("camera_info YAML of the camera (ROS calibration file); "
                                     "required unless --robot gives the URDF's {}",
                                     role));
}

CameraModel resolve_camera(const std::string& camera_yaml, const std::string& robot,
                           std::string_view role, const MissionConfig& mission) {
  if (camera_yaml.empty() == robot.empty())
    throw InputError("--camera", "",
                     fmt::format("exactly one of --camera CAM.yaml (a camera_info file) or "
                                 "--robot URDF (its {})",
                                 role),
                     camera_yaml.empty() ? "neither" : "both --camera and --robot");
  if (!camera_yaml.empty()) return load_camera_info(camera_yaml);
  const std::filesystem::path urdf = resolve_robot(robot, "");
  const RobotDescription description = load_robot_description(urdf, mission);
  const CameraSensor* sensor = nullptr;
  if (role == kRoleMarkerCamera)
    sensor = &description.marker_camera();
  else if (role == kRoleDepthCamera)
    sensor = &description.depth_camera();
  else if (role == kRoleObjectCamera)
    sensor = &description.object_camera();
  else
    throw std::logic_error("resolve_camera: not a camera role: " + std::string(role));
  return camera_model(*sensor, description.source);
}

std::pair<int, int> parse_shard(const std::string& text, bool given) {
  std::string shard = text;
  std::string option = "--shard";
  const char* id = std::getenv("SLURM_ARRAY_TASK_ID");
  const char* count = std::getenv("SLURM_ARRAY_TASK_COUNT");
  if (!given && id && count) {
    const char* min = std::getenv("SLURM_ARRAY_TASK_MIN");
    try {
      shard = std::to_string(std::stoll(id) - (min ? std::stoll(min) : 0)) + "/" + count;
    } catch (const std::exception&) {
      shard = std::string(id) + "/" + count;
    }
    option = "SLURM_ARRAY_TASK_ID/SLURM_ARRAY_TASK_COUNT";
  }
  const auto slash = shard.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument(shard);
    std::size_t u1 = 0, u2 = 0;
    const int i = std::stoi(shard.substr(0, slash), &u1);
    const int n = std::stoi(shard.substr(slash + 1), &u2);
    if (u1 != slash || u2 != shard.size() - slash - 1 || n < 1 || i < 0 || i >= n)
      throw std::invalid_argument(shard);
    return {i, n};
  } catch (const std::exception&) {
    throw InputError(option, "", "I/N with integers 0 <= I < N", shard);
  }
}

void add_mission_setup_options(CLI::App* sub, MissionSetupOptions& o) {
  sub->add_option("--world", o.world, "World YAML (default: the shipped default world)");
  sub->add_option("--robot-uav", o.robot_uav, "The UAV's URDF (default: the shipped m100)");
  sub->add_option("--robot-ugv", o.robot_ugv, "The miniUGV's URDF (default: the shipped miniugv)");
  sub->add_option("--mission", o.mission, "Mission YAML (default: the built-in defaults)");
  sub->add_option("--method", o.method,
                  "The miniUGV's search: cdos, rapid, nearest, ... (default: cdos)");
  sub->add_option("--planner", o.planner,
                  "The miniUGV's goals: grid (Dijkstra on G) or ompl (the CDOS frontier sampler "
                  "with PRM) (default: grid)");
  sub->add_option("--no-landing-zone", o.no_landing_zone,
                  "No safe landing zone by an opening: hover (lower from a hover) or skip "
                  "(default: the mission YAML's uav.no_landing_zone, hover)");
}

void add_faults_option(CLI::App* sub, MissionSetupOptions& o) {
  sub->add_option("--faults", o.faults,
                  "A YAML file with a `faults:` list to inject, after the mission YAML's own "
                  "(docs/safety.md; default: none beyond the mission YAML's)");
}

std::string one_of(const std::vector<std::string>& choices) {
  return fmt::format("one of {}", fmt::join(choices, ", "));
}

void check_choice(const std::string& option, const std::string& value,
                  const std::vector<std::string>& choices) {
  for (const auto& c : choices)
    if (c == value) return;
  throw InputError(option, "", one_of(choices), value);
}

}  // namespace ferret::cli
