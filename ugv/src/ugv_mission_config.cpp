#include "ferret/ugv/ugv_mission_config.hpp"

#include <array>
#include <utility>

#include "ferret/core/error.hpp"
#include "ferret/core/number.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/core/yaml_emit.hpp"

namespace ferret {
namespace {

using Options = UgvMissionOptions;

// The keys by type, each once; ugv_mission_keys() is their concatenation in the order
// the dump prints them. Ranges are UgvMissionOptions::validate's (one place).
constexpr std::array<std::pair<std::string_view, double Options::*>, 17> kNumbers{{
    {"explore_timeout_s", &Options::explore_timeout_s},
    {"standoff_m", &Options::standoff_m},
    {"servo_max_speed_mps", &Options::servo_max_speed_mps},
    {"servo_gain_per_s", &Options::servo_gain_per_s},
    {"servo_yaw_gain_per_s", &Options::servo_yaw_gain_per_s},
    {"track_lost_s", &Options::track_lost_s},
    {"track_timeout_s", &Options::track_timeout_s},
    {"turn_timeout_s", &Options::turn_timeout_s},
    {"rear_offset_m", &Options::rear_offset_m},
    {"grasp_speed_mps", &Options::grasp_speed_mps},
    {"grasp_overshoot_m", &Options::grasp_overshoot_m},
    {"grasp_timeout_s", &Options::grasp_timeout_s},
    {"entry_tolerance_m", &Options::entry_tolerance_m},
    {"return_timeout_min_s", &Options::return_timeout_min_s},
    {"retract_timeout_s", &Options::retract_timeout_s},
    {"battery_endurance_s", &Options::battery_endurance_s},
    {"battery_reserve_fraction", &Options::battery_reserve_fraction},
}};
constexpr std::array<std::pair<std::string_view, int Options::*>, 1> kIntegers{{
    {"grasp_attempts", &Options::grasp_attempts},
}};
constexpr std::array<std::pair<std::string_view, bool Options::*>, 1> kFlags{{
    {"tether_aware", &Options::tether_aware},
}};
// The search's tuning: a mapping of its own, as the struct embeds it.
constexpr std::string_view kExplore = "explore";
constexpr std::string_view kBackendKey = "base";

template <std::size_t N>
constexpr auto all_keys(bool with_backend) {
  std::array<std::string_view, N> out{};
  std::size_t i = 0;
  if (with_backend) out[i++] = kBackendKey;
  for (const auto& [k, m] : kNumbers) out[i++] = k;
  for (const auto& [k, m] : kIntegers) out[i++] = k;
  for (const auto& [k, m] : kFlags) out[i++] = k;
  out[i++] = kExplore;
  return out;
}
constexpr std::size_t kMissionKeyCount = 1 + kNumbers.size() + kIntegers.size() + kFlags.size();
constexpr auto kMissionKeys = all_keys<kMissionKeyCount>(false);
constexpr auto kSectionKeys = all_keys<kMissionKeyCount + 1>(true);

using Tuning = ExploreTuning;
constexpr std::array<std::pair<std::string_view, double Tuning::*>, 3> kTuningNumbers{{
    {"decision_period_s", &Tuning::decision_period_s},
    {"tether_margin_m", &Tuning::tether_margin_m},
    {"tether_obstacle_depth_m", &Tuning::tether_obstacle_depth_m},
}};
constexpr std::array<std::pair<std::string_view, int Tuning::*>, 1> kTuningIntegers{{
    {"max_revisits", &Tuning::max_revisits},
}};
constexpr std::array<std::pair<std::string_view, bool Tuning::*>, 2> kTuningFlags{{
    {"cdos_candidates_global", &Tuning::cdos_candidates_global},
    {"cdos_closest_approach", &Tuning::cdos_closest_approach},
}};
constexpr auto kTuningKeys = [] {
  std::array<std::string_view, kTuningNumbers.size() + kTuningIntegers.size() + kTuningFlags.size()>
      out{};
  std::size_t i = 0;
  for (const auto& [k, m] : kTuningNumbers) out[i++] = k;
  for (const auto& [k, m] : kTuningIntegers) out[i++] = k;
  for (const auto& [k, m] : kTuningFlags) out[i++] = k;
  return out;
}();

// Each key of `table` the file gives over its member; get_or refuses `key:` without a
// value and parses numbers finite (NaN, inf refused). The keys set go to `given`, after
// `prefix`.
template <class Table, class Struct>
void read_table(const yaml::MapReader& r, const Table& table, Struct& o, std::string_view prefix,
                std::set<std::string>& given) {
  for (const auto& [key, member] : table) {
    o.*member = r.get_or(key, o.*member);
    if (r.has(key)) given.insert(std::string(prefix) + std::string(key));
  }
}

template <class Table, class Struct>
void emit_table(YAML::Emitter& e, const Table& table, const Struct& o) {
  for (const auto& [key, member] : table) {
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(o.*member)>, double>)
      internal::emit_key_number(e, key.data(), o.*member);
    else
      e << YAML::Key << key.data() << YAML::Value << o.*member;
  }
}

}  // namespace

std::span<const std::string_view> ugv_mission_keys() { return kMissionKeys; }
std::span<const std::string_view> ugv_section_keys() { return kSectionKeys; }
std::span<const std::string_view> explore_tuning_keys() { return kTuningKeys; }

void validate_explore_tuning(const ExploreTuning& t, const std::string& source) {
  check_number(t.decision_period_s, NumberRange::positive(60.0, "s"), source,
               "ugv.explore.decision_period_s");
  if (t.max_revisits < 0 || t.max_revisits > 100)
    throw InputError(source, "ugv.explore.max_revisits", "an integer in [0, 100]",
                     std::to_string(t.max_revisits));
  check_number(t.tether_margin_m, NumberRange::non_negative(10.0, "m"), source,
               "ugv.explore.tether_margin_m");
  // ExploreController refuses a depth outside [0, 10] m.
  check_number(t.tether_obstacle_depth_m, NumberRange::non_negative(10.0, "m"), source,
               "ugv.explore.tether_obstacle_depth_m");
}

std::set<std::string> read_explore_tuning(const YAML::Node& node, const std::string& source,
                                          ExploreTuning& t) {
  std::set<std::string> given;
  if (!node.IsDefined() || node.IsNull()) return given;
  const yaml::MapReader r(node, source, "ugv.explore");
  r.allow_only(explore_tuning_keys());
  read_table(r, kTuningNumbers, t, "", given);
  read_table(r, kTuningIntegers, t, "", given);
  read_table(r, kTuningFlags, t, "", given);
  validate_explore_tuning(t, source);
  return given;
}

void emit_explore_tuning(YAML::Emitter& e, const ExploreTuning& t) {
  emit_table(e, kTuningNumbers, t);
  emit_table(e, kTuningIntegers, t);
  emit_table(e, kTuningFlags, t);
}

std::set<std::string> read_ugv_mission_options(const YAML::Node& node, const std::string& source,
                                               UgvMissionOptions& o) {
  std::set<std::string> given;
  if (!node.IsDefined() || node.IsNull()) return given;
  const yaml::MapReader r(node, source, "ugv");
  r.allow_only(ugv_section_keys());
  read_table(r, kNumbers, o, "", given);
  read_table(r, kIntegers, o, "", given);
  read_table(r, kFlags, o, "", given);
  if (r.has(kExplore)) {
    for (const auto& key : read_explore_tuning(r.node()[std::string(kExplore)], source, o.explore))
      given.insert(std::string(kExplore) + "." + key);
  } else if (r.given_empty(kExplore)) {
    r.fail(kExplore, "a mapping of the search's tuning", "a key without a value");
  }
  o.validate(source);
  return given;
}

void assign_ugv_mission_keys(UgvMissionOptions& to, const UgvMissionOptions& from) {
  const auto assign = [&](const auto& table) {
    for (const auto& [key, member] : table) to.*member = from.*member;
  };
  assign(kNumbers);
  assign(kIntegers);
  assign(kFlags);
  to.explore.set_tuning(from.explore);
}

void emit_ugv_mission_options(YAML::Emitter& e, const UgvMissionOptions& o) {
  emit_table(e, kNumbers, o);
  emit_table(e, kIntegers, o);
  emit_table(e, kFlags, o);
  e << YAML::Key << kExplore.data() << YAML::Value << YAML::BeginMap;
  emit_explore_tuning(e, o.explore);
  e << YAML::EndMap;
}

}  // namespace ferret
