#include "ferret/uav/uav_mission_config.hpp"

#include <fmt/format.h>

#include <array>
#include <utility>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/core/yaml_emit.hpp"
#include "ferret/perception/marker_family.hpp"

namespace ferret {
namespace {

using Options = UavMissionOptions;

// The keys by type, each once; uav_mission_keys() is their concatenation in the order
// the dump prints them. Ranges are UavMissionOptions::validate's (one place).
constexpr std::array<std::pair<std::string_view, double Options::*>, 26> kNumbers{{
    {"search_altitude_m", &Options::search_altitude_m},
    {"search_speed_mps", &Options::search_speed_mps},
    {"cruise_speed_mps", &Options::cruise_speed_mps},
    {"leg_spacing_m", &Options::leg_spacing_m},
    {"frame_period_s", &Options::frame_period_s},
    {"waypoint_tolerance_m", &Options::waypoint_tolerance_m},
    {"braking_accel_mps2", &Options::braking_accel_mps2},
    {"survey_height_m", &Options::survey_height_m},
    {"survey_standoff_m", &Options::survey_standoff_m},
    {"hover_standoff_m", &Options::hover_standoff_m},
    {"touchdown_height_m", &Options::touchdown_height_m},
    {"retract_speed_mps", &Options::retract_speed_mps},
    {"ugv_return_speed_mps", &Options::ugv_return_speed_mps},
    {"drop_altitude_m", &Options::drop_altitude_m},
    {"drop_time_s", &Options::drop_time_s},
    {"flight_endurance_s", &Options::flight_endurance_s},
    {"battery_reserve_fraction", &Options::battery_reserve_fraction},
    {"takeoff_timeout_s", &Options::takeoff_timeout_s},
    {"approach_timeout_s", &Options::approach_timeout_s},
    {"survey_timeout_s", &Options::survey_timeout_s},
    {"land_timeout_s", &Options::land_timeout_s},
    {"lower_timeout_s", &Options::lower_timeout_s},
    {"ugv_ops_timeout_s", &Options::ugv_ops_timeout_s},
    {"retract_timeout_s", &Options::retract_timeout_s},
    {"deliver_timeout_s", &Options::deliver_timeout_s},
    {"return_timeout_s", &Options::return_timeout_s},
}};
constexpr std::array<std::pair<std::string_view, int Options::*>, 5> kIntegers{{
    {"passes", &Options::passes},
    {"confirm_detections", &Options::confirm_detections},
    {"survey_views", &Options::survey_views},
    {"survey_frames", &Options::survey_frames},
    {"survey_frames_max", &Options::survey_frames_max},
}};
// How the miniUGV goes down: an enum, read and written as its word, before the choices.
constexpr std::string_view kRelease = "release";
constexpr std::string_view kNoLandingZone = "no_landing_zone";
constexpr std::array<std::pair<std::string_view, std::string Options::*>, 1> kChoices{{
    {"winch_controller", &Options::winch_controller},
}};
constexpr std::string_view kSearchArea = "search_area_m";
// The markers the UAV looks for, over the world's: {family, dictionary, size_m}.
constexpr std::string_view kMarker = "marker";
// Each winch controller's own options: {mpc: {...}, baseline: {...}} (winch_controllers.hpp).
constexpr std::string_view kWinchControl = "winch_control";
constexpr std::array<std::string_view, 2> kBackendKeys{"winch", "flight_controller"};

template <std::size_t N>
constexpr auto all_keys(bool with_backends) {
  std::array<std::string_view, N> out{};
  std::size_t i = 0;
  if (with_backends)
    for (const auto k : kBackendKeys) out[i++] = k;
  out[i++] = kSearchArea;
  out[i++] = kMarker;
  out[i++] = kWinchControl;
  for (const auto& [k, m] : kNumbers) out[i++] = k;
  for (const auto& [k, m] : kIntegers) out[i++] = k;
  out[i++] = kRelease;
  out[i++] = kNoLandingZone;
  for (const auto& [k, m] : kChoices) out[i++] = k;
  return out;
}
// search_area_m, marker, winch_control, release and no_landing_zone, then the tables.
constexpr std::size_t kMissionKeyCount = 5 + kNumbers.size() + kIntegers.size() + kChoices.size();
constexpr auto kMissionKeys = all_keys<kMissionKeyCount>(false);
constexpr auto kSectionKeys = all_keys<kMissionKeyCount + kBackendKeys.size()>(true);

ReleaseMode read_release_mode(const std::string& word, const std::string& source) {
  for (const ReleaseMode m : {ReleaseMode::kLand, ReleaseMode::kHover})
    if (word == to_string(m)) return m;
  throw InputError(source, "uav.release", "land or hover", word);
}

}  // namespace

std::span<const std::string_view> uav_mission_keys() { return kMissionKeys; }
std::span<const std::string_view> uav_section_keys() { return kSectionKeys; }

std::set<std::string> read_uav_mission_options(const YAML::Node& node, const std::string& source,
                                               UavMissionOptions& o) {
  std::set<std::string> given;
  if (!node.IsDefined() || node.IsNull()) return given;
  const yaml::MapReader r(node, source, "uav");
  r.allow_only(uav_section_keys());
  const auto note = [&](std::string_view key) {
    if (r.has(key)) given.insert(std::string(key));
  };
  if (r.has(kSearchArea)) {
    const std::vector<double> a = r.get_list<double>(kSearchArea, 4);
    o.search_area_m = {a[0], a[1], a[2], a[3]};
    note(kSearchArea);
  } else if (r.given_empty(kSearchArea)) {
    r.fail(kSearchArea, "a list of 4 values", "a key without a value");
  }
  if (r.has(kMarker)) {
    const yaml::MapReader m = r.child(kMarker);
    m.allow_only({"family", "dictionary", "size_m"});
    MarkerDictionary& d = o.marker.dictionary;
    d.family = parse_marker_family(m.get<std::string>("family"), source, m.field_path("family"));
    d.name = m.get_or<std::string>("dictionary", default_marker_dictionary(d.family));
    check_marker_dictionary(d, source, m.field_path("dictionary"));
    o.marker.marker_size_m = m.get<double>("size_m");
    if (!(o.marker.marker_size_m > 0.0 && o.marker.marker_size_m <= 100.0))
      m.fail("size_m", "the black square's side in metres, in (0, 100]",
             fmt::format("{}", o.marker.marker_size_m));
    o.marker_from_mission = true;
    note(kMarker);
  } else if (r.given_empty(kMarker)) {
    r.fail(kMarker, "a mapping {family, dictionary, size_m}", "a key without a value");
  }
  if (r.has(kWinchControl)) {
    tether::read_winch_controller_options(r.child(kWinchControl), o.winch_controllers);
    note(kWinchControl);
  } else if (r.given_empty(kWinchControl)) {
    r.fail(kWinchControl, "a mapping {mpc: {...}, baseline: {...}}", "a key without a value");
  }
  // get_or refuses `key:` without a value, and parses numbers finite (NaN, inf refused).
  const auto read = [&](const auto& table) {
    for (const auto& [key, member] : table) {
      o.*member = r.get_or(key, o.*member);
      note(key);
    }
  };
  read(kNumbers);
  read(kIntegers);
  o.release = read_release_mode(r.get_or(kRelease, std::string(to_string(o.release))), source);
  note(kRelease);
  o.no_landing_zone =
      parse_no_landing_zone(r.get_or(kNoLandingZone, std::string(to_string(o.no_landing_zone))),
                            source, "uav.no_landing_zone");
  note(kNoLandingZone);
  read(kChoices);
  o.validate(source);
  return given;
}

void emit_uav_mission_options(YAML::Emitter& e, const UavMissionOptions& o, bool with_search_area) {
  if (with_search_area)
    internal::emit_key_numbers(
        e, kSearchArea.data(),
        std::array{o.search_area_m[0], o.search_area_m[1], o.search_area_m[2], o.search_area_m[3]});
  if (o.marker_from_mission) {
    e << YAML::Key << kMarker.data() << YAML::Value << YAML::Flow << YAML::BeginMap;
    e << YAML::Key << "family" << YAML::Value << to_string(o.marker.dictionary.family);
    e << YAML::Key << "dictionary" << YAML::Value << o.marker.dictionary.name;
    internal::emit_key_number(e, "size_m", o.marker.marker_size_m);
    e << YAML::EndMap;
  }
  for (const auto& [key, member] : kNumbers) internal::emit_key_number(e, key.data(), o.*member);
  for (const auto& [key, member] : kIntegers)
    e << YAML::Key << key.data() << YAML::Value << o.*member;
  e << YAML::Key << kRelease.data() << YAML::Value << std::string(to_string(o.release));
  e << YAML::Key << kNoLandingZone.data() << YAML::Value
    << std::string(to_string(o.no_landing_zone));
  for (const auto& [key, member] : kChoices)
    e << YAML::Key << key.data() << YAML::Value << o.*member;
  e << YAML::Key << kWinchControl.data() << YAML::Value;
  tether::emit_winch_controller_options(e, o.winch_controllers);
}

}  // namespace ferret
