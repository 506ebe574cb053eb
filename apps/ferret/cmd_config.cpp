// `ferret config --dump`: the effective configuration, i.e. what the robot's URDF and
// the mission YAML give once defaults are filled in (its cameras' models included, and
// the backend each hardware interface runs on), printed as YAML. `ferret config
// --camera-info SENSOR -o FILE`: a URDF camera as a ROS camera_info file, to start a
// calibration from.

#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/mission/mission_document.hpp"
#include "ferret/perception/camera_info.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/perception/camera_summary.hpp"
#include "ferret/uav/uav_mission_config.hpp"
#include "ferret/ugv/ugv_mission_config.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::cli {
namespace {

namespace fs = std::filesystem;

/// Indents every line of a YAML block by two spaces, to nest it under a key.
std::string indent(const std::string& text) {
  std::istringstream in(text);
  std::string line, out;
  while (std::getline(in, line))
    if (!line.empty()) out += "  " + line + "\n";
  return out;
}

struct Options {
  bool dump = false;
  std::string camera_info;  ///< the sensor whose camera_info to write
  std::string robot;
  std::string mission;
  std::string out;
};

void run(const Options& o) {
  if (o.dump == !o.camera_info.empty())
    throw InputError("--dump", "", "exactly one of --dump or --camera-info SENSOR",
                     o.dump ? "both" : "neither");
  const bool to_stdout = o.camera_info.empty() && (o.out.empty() || o.out == "-");
  fs::path out_file;
  if (!o.camera_info.empty())
    out_file = checked_out_file(o.out, "the camera_info YAML to write");
  else if (!to_stdout)
    out_file = check_output_target(o.out, OutputKind::kFile, "--out");
  std::string mission_source = "(built-in defaults)";
  if (!o.mission.empty())
    mission_source = o.mission;
  else if (fs::is_regular_file("config/mission.yaml"))
    mission_source = "config/mission.yaml";
  const MissionDocument document = mission_source == "(built-in defaults)"
                                       ? MissionDocument{}
                                       : load_mission_document(mission_source);
  const MissionConfig& mission = document.config;
  const RobotDescription robot =
      load_robot_description(resolve_robot(o.robot, "miniugv.urdf"), mission);

  if (!o.camera_info.empty()) {
    const CameraSensor* sensor = robot.find_camera(o.camera_info);
    if (sensor == nullptr) {
      std::string names;
      for (const auto& c : robot.cameras) names += (names.empty() ? "" : ", ") + c.name;
      throw InputError("--camera-info", "",
                       "a camera of " + robot.source + " (" +
                           (names.empty() ? std::string("it has none") : "one of " + names) + ")",
                       o.camera_info);
    }
    OutputSet outputs(out_file, OutputKind::kFile);
    outputs.write_text({}, "# camera_info of " + printable(robot.source) + " sensor " +
                               printable(sensor->name) +
                               " (ferret config --camera-info): the URDF's camera, to be\n"
                               "# replaced by a calibration (ROS camera_calibration)\n" +
                               camera_info_yaml(camera_model(*sensor, robot.source)));
    outputs.commit();
    return;
  }

  std::string text = "# ferret effective configuration (ferret config --dump)\n";
  text += "# provenance: where each value came from (urdf:FILE:LINE, mission:FILE, default)\n";
  text += "robot:\n" + indent(robot_description_to_yaml(robot) + camera_models_yaml(robot));
  text += "mission:\n" +
          indent("source: \"" + mission_source + "\"\n" + mission_config_to_yaml(mission) +
                 "provenance:\n" + indent(mission_provenance_to_yaml(mission)));
  text += "# backends: which implementation each hardware interface runs on (sim or hw)\n";
  text += "backends:\n" + indent(robot_backends_to_yaml(document.backends));
  const bool search_area_given = document.uav_mission_given.count("search_area_m") > 0;
  text += std::string(
              "# the UAV mission's settings (the mission YAML's uav section takes these keys)") +
          (search_area_given ? "" : "; the search area is the world's bounds less 1 m") + "\n";
  YAML::Emitter uav_yaml;
  uav_yaml << YAML::BeginMap;
  emit_uav_mission_options(uav_yaml, document.uav_mission, search_area_given);
  uav_yaml << YAML::EndMap;
  text += "uav_mission:\n" + indent(std::string(uav_yaml.c_str()) + "\n");
  // The miniUGV's: every key with its value; which of them the file set (the rest are
  // the defaults), as a comment so that the section reads back as a `ugv` section.
  std::string given;
  for (const auto& key : document.ugv_mission_given) given += (given.empty() ? "" : ", ") + key;
  text +=
      "# the miniUGV mission's settings (the mission YAML's ugv section takes these keys, "
      "the search's under explore); from " +
      (given.empty() ? std::string("the defaults")
                     : "mission:" + mission_source + ": " + given + "; the rest the defaults") +
      "\n";
  YAML::Emitter ugv_yaml;
  ugv_yaml << YAML::BeginMap;
  emit_ugv_mission_options(ugv_yaml, document.ugv_mission);
  ugv_yaml << YAML::EndMap;
  text += "ugv_mission:\n" + indent(std::string(ugv_yaml.c_str()) + "\n");
  if (to_stdout) {
    std::cout << text;
  } else {
    OutputSet outputs(out_file, OutputKind::kFile);
    outputs.write_text({}, text);
    outputs.commit();
  }
}

const CommandRegistration kConfig{
    "config", [](CLI::App& app) {
      auto options = std::make_shared<Options>();
      auto* sub =
          app.add_subcommand("config", "Show the effective robot and mission configuration");
      sub->add_flag("--dump", options->dump, "Print the effective configuration as YAML");
      sub->add_option(
          "--camera-info", options->camera_info,
          "Write the camera_info YAML of this URDF camera (a sensor name) to -o, instead of "
          "--dump (default: none)");
      add_robot_option(sub, options->robot, "miniugv");
      auto* mission = add_mission_option(sub, options->mission);
      mission->description(
          "mission YAML: motion limits, tether L and l_0, object search, roles (default: "
          "config/mission.yaml if present, else the built-in values)");
      sub->add_option("-o,--out", options->out,
                      "Write the YAML to this file (default for --dump: stdout; required for "
                      "--camera-info)");
      add_hidden_alias(sub, "--output", options->out);
      sub->callback([options, sub] {
        refuse_empty_out(sub, options->out);
        run(*options);
      });
    }};

}  // namespace
}  // namespace ferret::cli
