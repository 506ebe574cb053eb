#include "ferret/mission/mission_setup.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <optional>

#include "ferret/core/data_path.hpp"
#include "ferret/core/error.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "ferret/mission/mission_settings.hpp"
#include "ferret/planning/exploration_policy.hpp"
#include "ferret/uav/uav_mission_options.hpp"

namespace ferret {

const std::vector<std::string>& shipped_model_names() {
  static const std::vector<std::string> names{"m100", "miniugv"};
  return names;
}

std::filesystem::path resolve_robot(const std::string& robot, std::string_view default_model) {
  if (robot.empty()) return find_model(default_model);
  for (const auto& name : shipped_model_names())
    if (robot == name || robot == name + ".urdf") return find_model(name + ".urdf");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(robot, ec))
    throw InputError("--robot", "",
                     "a URDF file, or a shipped model: " +
                         fmt::format("{}", fmt::join(shipped_model_names(), ", ")),
                     robot);
  return robot;
}

MissionDocument load_mission_document_or_defaults(const std::string& path) {
  return path.empty() ? MissionDocument{} : load_mission_document(path);
}

MissionConfig load_mission_or_defaults(const std::string& path) {
  // The whole document, the backend sections and the UAV mission's keys too, although
  // this command may not build a robot or fly: a typo there is reported by the first
  // command that reads the file, not by the robot at start-up.
  return load_mission_document_or_defaults(path).config;
}

void check_openings_admit(const WorldSpec& world, const std::string& source,
                          const RobotDescription& ugv) {
  // The miniUGV drives in along its x axis: its collision box's width (y) and height (z)
  // must pass the opening, or it would be lowered to a space it cannot enter.
  const Eigen::Vector3d size = ugv.bounding_box_B.sizes();
  for (std::size_t i = 0; i < world.hidden_spaces.size(); ++i) {
    const HiddenSpace& h = world.hidden_spaces[i];
    if (h.opening_width_m >= size.y() && h.opening_height_m >= size.z()) continue;
    throw InputError(
        source, "hidden_spaces[" + std::to_string(i) + "].opening (" + h.name + ")",
        fmt::format("an opening the miniUGV passes through: at least {:.3f} m wide and {:.3f} m "
                    "high (the collision box of {})",
                    size.y(), size.z(), ugv.source),
        fmt::format("{:.3f} m wide, {:.3f} m high", h.opening_width_m, h.opening_height_m));
  }
}

MissionSetup load_mission_setup(const MissionSetupOptions& o) {
  std::optional<NoLandingZone> no_landing_zone;
  if (!o.no_landing_zone.empty())
    no_landing_zone = parse_no_landing_zone(o.no_landing_zone, "--no-landing-zone");
  // The method with the frontier planner, or an InputError naming why not (the miniUGV's
  // ExploreController asks the same function).
  const FrontierPlanner planner = parse_frontier_planner(o.planner, "--planner");
  (void)exploration_policy_for(o.method, planner);
  const MissionDocument document = load_mission_document_or_defaults(o.mission);
  MissionSetup s{
      o.world.empty() ? data_path("worlds/default.yaml") : std::filesystem::path(o.world),
      document.config,
      document.backends,
      {},
      {},
      {},
      {}};
  s.uav = load_robot_description(resolve_robot(o.robot_uav, "m100.urdf"), s.mission);
  s.ugv = load_robot_description(resolve_robot(o.robot_ugv, "miniugv.urdf"), s.mission);
  s.world = load_planning_world(s.world_path);
  if (!s.world.spec)
    throw InputError(s.world_path.string(), "",
                     "a world YAML (an OctoMap file names no hidden spaces or markers)");
  if (s.world.spec->hidden_spaces.empty())
    throw InputError(s.world_path.string(), "hidden_spaces",
                     "at least one hidden space with a marker");
  check_openings_admit(*s.world.spec, s.world_path.string(), s.ugv);

  MissionRunSettings& settings = s.settings;
  settings = mission_settings_for(s.uav, s.ugv, s.mission, *s.world.spec);
  settings.ugv.exploration.method = o.method;
  // The UAV mission's keys of the mission YAML over what the world set (the search area
  // from its bounds); the command line's choice over both.
  document.apply_uav_mission(settings.uav);
  if (no_landing_zone) settings.uav.no_landing_zone = *no_landing_zone;
  // Checked here too, so that a value the miniUGV's commands accept but the UAV's mission
  // does not (l_0 = 0: no hover release) is named in the mission file.
  settings.uav.validate(o.mission.empty() ? "(built-in defaults)" : o.mission);
  // The miniUGV mission's keys of the mission YAML (timeouts, grasp, the search's tuning)
  // over the defaults; what the robot and the winch set stays.
  document.apply_ugv_mission(settings.ugv);
  settings.ugv.ugv.explore.planner = planner;
  // How long the base may stand still when told to drive is the base's (ugv.base).
  settings.ugv.ugv.bump_time_s = s.backends.ugv_base.stall_time_s;
  settings.faults = document.faults;
  if (!o.faults.empty()) {
    const FaultPlan extra = load_fault_plan(o.faults);
    settings.faults.faults.insert(settings.faults.faults.end(), extra.faults.begin(),
                                  extra.faults.end());
  }
  return s;
}

}  // namespace ferret
