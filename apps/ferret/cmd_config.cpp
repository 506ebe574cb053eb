// `ferret config --dump`: the effective configuration, i.e. what the robot's URDF and
// the mission YAML give once defaults are filled in, printed as YAML.

#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>

#include "command.hpp"
#include "ferret/core/atomic_file.hpp"
#include "ferret/core/error.hpp"
#include "ferret/urdf/mission_config.hpp"
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

/// --robot takes a path, or the name of a shipped model ("m100", "miniugv.urdf").
fs::path resolve_robot(const std::string& robot) {
  if (robot.empty()) return find_model("miniugv.urdf");
  const fs::path p(robot);
  if (fs::exists(p) || p.has_parent_path()) return p;
  try {
    return find_model(p.has_extension() ? robot : robot + ".urdf");
  } catch (const InputError&) {
    return p;  // the loader reports the path the user gave
  }
}

struct Options {
  bool dump = false;
  std::string robot;
  std::string config;
  std::string output;
};

void run(const Options& o) {
  if (!o.dump)
    throw InputError("ferret config", "--dump", "the --dump flag (the only action so far)");
  std::string mission_source = "(built-in defaults)";
  MissionConfig mission;
  if (!o.config.empty()) {
    mission = load_mission_config(o.config);
    mission_source = o.config;
  } else if (fs::is_regular_file("config/mission.yaml")) {
    mission = load_mission_config("config/mission.yaml");
    mission_source = "config/mission.yaml";
  }
  const RobotDescription robot = load_robot_description(resolve_robot(o.robot), mission);

  std::string text = "# ferret effective configuration (ferret config --dump)\n";
  text += "robot:\n" + indent(robot_description_to_yaml(robot));
  text += "mission:\n" +
          indent("source: \"" + mission_source + "\"\n" + mission_config_to_yaml(mission));
  if (o.output.empty() || o.output == "-")
    std::cout << text;
  else
    write_text_atomically(o.output, text);
}

const CommandRegistration kConfig{
    "config", [](CLI::App& app) {
      auto options = std::make_shared<Options>();
      auto* sub =
          app.add_subcommand("config", "Show the effective robot and mission configuration");
      sub->add_flag("--dump", options->dump, "Print the effective configuration as YAML");
      sub->add_option("--robot", options->robot,
                      "Robot URDF, or a shipped model name (m100, miniugv); default: miniugv.urdf");
      sub->add_option("--config", options->config,
                      "Mission YAML; default: config/mission.yaml if present");
      sub->add_option("-o,--output", options->output,
                      "Write the YAML to this file instead of stdout");
      sub->callback([options] { run(*options); });
    }};

}  // namespace
}  // namespace ferret::cli
