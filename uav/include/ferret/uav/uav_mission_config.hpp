#pragma once
// The UAV mission's settings in the mission YAML: the keys of UavMissionOptions that a
// user sets, beside the UAV's backends in the `uav` section (docs/configuration.md,
// "The UAV's mission"). Every key is optional; a key the file leaves out keeps the value
// it had (the default, or what the world set, as the search area from its bounds).
//
//   uav:
//     flight_controller: {backend: sim}
//     search_altitude_m: 5.0
//     release: hover          # land (the default) or hover over every opening
//     flight_endurance_s: 900

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <set>
#include <span>
#include <string>
#include <string_view>

#include "ferret/uav/uav_mission_options.hpp"

namespace ferret {

/// The mission's keys in the `uav` section (the backends' keys are not among them).
[[nodiscard]] std::span<const std::string_view> uav_mission_keys();
/// Every key the `uav` section may hold: the backends' (winch, flight_controller), then
/// the mission's. The one list both readers of the section check it against.
[[nodiscard]] std::span<const std::string_view> uav_section_keys();

/// Reads the mission's keys of the section `uav` over `options`, then validates the
/// result. An undefined or null `node` (no section) changes and checks nothing. Keys that are not
/// the mission's (the backends: winch, flight_controller) are left to their readers. Returns the
/// keys the file set. Throws InputError naming the file and the field (`uav.KEY`) for a wrong type,
/// a value out of range or an unknown choice.
std::set<std::string> read_uav_mission_options(const YAML::Node& node, const std::string& source,
                                               UavMissionOptions& options);

/// The mission's keys and values into an open YAML mapping, in the order of
/// uav_mission_keys(); the search area only when `with_search_area` (without it, it is
/// the world's). read_uav_mission_options reads it back to the same values.
void emit_uav_mission_options(YAML::Emitter& e, const UavMissionOptions& options,
                              bool with_search_area);

}  // namespace ferret
