#include "ferret/mission/mission_document.hpp"

#include <array>

#include "ferret/core/yaml_config.hpp"
#include "ferret/sim/fault_schedule.hpp"
#include "ferret/uav/uav_mission_config.hpp"
#include "ferret/ugv/mini_ugv_mission_options.hpp"
#include "ferret/ugv/ugv_mission_config.hpp"

namespace ferret {

MissionDocument mission_document_from_yaml(const YAML::Node& root, const std::string& source) {
  MissionDocument d;
  d.source = source;
  d.config = mission_config_from_yaml(root, source);
  d.backends = robot_backends_from_yaml(root, source);
  // The document's shape is mission_config_from_yaml's to check; a section is a mapping.
  // Only a key that is there is kept: yaml-cpp refuses to assign a missing key's node.
  if (root.IsMap() && root["uav"]) d.uav_section = root["uav"];
  d.uav_mission.tether = d.config.tether;
  d.uav_mission_given = read_uav_mission_options(d.uav_section, source, d.uav_mission);
  if (root.IsMap() && root["ugv"]) d.ugv_section = root["ugv"];
  d.ugv_mission_given = read_ugv_mission_options(d.ugv_section, source, d.ugv_mission);
  if (root.IsMap() && root["faults"])
    d.faults = fault_plan_from_yaml(root["faults"], source, mission_fault_states());
  check_injectable(d.faults, source);
  return d;
}

const FaultStates& mission_fault_states() {
  static const auto uav = [] {
    std::array<std::string_view, static_cast<std::size_t>(UavMissionState::kDone) + 1> n{};
    for (std::size_t k = 0; k < n.size(); ++k) n[k] = to_string(static_cast<UavMissionState>(k));
    return n;
  }();
  static const auto ugv = [] {
    std::array<std::string_view, static_cast<std::size_t>(UgvMissionState::kDone) + 2> n{};
    for (std::size_t k = 0; k + 1 < n.size(); ++k)
      n[k] = to_string(static_cast<UgvMissionState>(k));
    n.back() = "link_hold";
    return n;
  }();
  static const FaultStates states{uav, ugv};
  return states;
}

FaultPlan load_fault_plan(const std::filesystem::path& path) {
  const YAML::Node root = yaml::load_file(path);
  if (root.IsNull()) return {};
  const yaml::MapReader doc(root, path.string());
  doc.allow_only({"faults"});
  FaultPlan plan = fault_plan_from_yaml(root["faults"], path.string(), mission_fault_states());
  check_injectable(plan, path.string());
  return plan;
}

MissionDocument load_mission_document(const std::filesystem::path& path) {
  return mission_document_from_yaml(yaml::load_file(path), path.string());
}

void MissionDocument::apply_uav_mission(UavMissionOptions& options) const {
  (void)read_uav_mission_options(uav_section, source, options);
}

void MissionDocument::apply_ugv_mission(UgvMissionRunSettings& settings) const {
  // The file's keys as read once above; what the run filled (the line's catch, the stall
  // time, the planner) stays.
  assign_ugv_mission_keys(settings.ugv, ugv_mission);
  settings.exploration.set_tuning(ugv_mission.explore);
}

}  // namespace ferret
