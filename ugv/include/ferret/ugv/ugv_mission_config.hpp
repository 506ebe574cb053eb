#pragma once
// The miniUGV mission's settings in the mission YAML: the keys of UgvMissionOptions that a
// user sets, beside the base's backend in the `ugv` section, and the search's tuning
// (ExploreTuning) under `ugv.explore` (docs/configuration.md, "The miniUGV's mission").
// Every key is optional; a key the file leaves out keeps the value it had (the default:
// the struct's member initializer is the one home of every default).
//
//   ugv:
//     base: {backend: sim}
//     explore_timeout_s: 300
//     grasp_attempts: 2
//     explore: {max_revisits: 1}
//
// Not keys, since they are filled at run time: bump_time_s (the base's
// ugv.base.stall_time_s), line_catch (from the winch and tether.catch_speed_limit) and,
// of ExploreOptions, method and planner (the command line), sensors and robot (the
// robot's URDF), mission (the common sections), seed, the oracle's object,
// record_decisions and tether_budget_m (the tether's L - l_0).

#include <yaml-cpp/yaml.h>

#include <set>
#include <span>
#include <string>
#include <string_view>

#include "ferret/ugv/explore_options.hpp"
#include "ferret/ugv/mini_ugv_mission_options.hpp"

namespace ferret {

/// The mission's keys in the `ugv` section (the base's backend is not among them;
/// `explore` is, a mapping of explore_tuning_keys()).
[[nodiscard]] std::span<const std::string_view> ugv_mission_keys();
/// Every key the `ugv` section may hold: the backend's (base), then the mission's. The
/// one list both readers of the section check it against.
[[nodiscard]] std::span<const std::string_view> ugv_section_keys();
/// The keys of `ugv.explore`.
[[nodiscard]] std::span<const std::string_view> explore_tuning_keys();

/// Reads the keys of `ugv.explore` (`node`, a mapping; undefined or null: nothing) over
/// `tuning` and checks them. Returns the keys the file set. Throws InputError naming the
/// file and the field (`ugv.explore.KEY`) for an unknown key, a wrong type or a value out
/// of range.
std::set<std::string> read_explore_tuning(const YAML::Node& node, const std::string& source,
                                          ExploreTuning& tuning);
/// Checks the tuning's values (finite, in range); InputError naming `ugv.explore.FIELD`.
void validate_explore_tuning(const ExploreTuning& tuning, const std::string& source);
/// The tuning's keys and values into an open YAML mapping, in explore_tuning_keys()' order.
void emit_explore_tuning(YAML::Emitter& e, const ExploreTuning& tuning);

/// Reads the mission's keys of the section `ugv` (`node`) over `options`, its `explore`
/// mapping over `options.explore`, then validates the result. An undefined or null
/// `node` (no section) changes and checks nothing. The base's key is left to its reader.
/// Returns the keys the file set (`explore.KEY` for the search's). Throws InputError
/// naming the file and the field (`ugv.KEY`) for an unknown key (listing the allowed
/// ones), a wrong type or a value out of range.
std::set<std::string> read_ugv_mission_options(const YAML::Node& node, const std::string& source,
                                               UgvMissionOptions& options);

/// Sets in `to` the members ugv_mission_keys() name (the search's tuning too) to their
/// values in `from`; the rest of `to` (what the run fills) keeps its values.
void assign_ugv_mission_keys(UgvMissionOptions& to, const UgvMissionOptions& from);

/// The mission's keys and values into an open YAML mapping, in the order of
/// ugv_mission_keys(), `explore` last. read_ugv_mission_options reads it back to the same
/// values.
void emit_ugv_mission_options(YAML::Emitter& e, const UgvMissionOptions& options);

}  // namespace ferret
