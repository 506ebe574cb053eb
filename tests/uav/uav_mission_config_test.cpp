// The UAV mission's keys in the mission YAML's `uav` section (uav/uav_mission_config.hpp).

#include "ferret/uav/uav_mission_config.hpp"

#include <gtest/gtest.h>

#include <string>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/sim/robot_backends.hpp"

namespace ferret {
namespace {

YAML::Node uav_section(const std::string& text) { return yaml::load_string(text, "m.yaml")["uav"]; }

std::string dump(const UavMissionOptions& o, bool with_area = true) {
  YAML::Emitter e;
  e << YAML::BeginMap;
  emit_uav_mission_options(e, o, with_area);
  e << YAML::EndMap;
  return e.c_str();
}

// The message a bad section gives, or "" when it is read.
std::string error_of(const std::string& text) {
  try {
    UavMissionOptions o;
    (void)read_uav_mission_options(uav_section(text), "m.yaml", o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(UavMissionConfig, TheKeysTheFileSetsAreReadAndTheRestKeepTheirValues) {
  UavMissionOptions o;
  o.search_area_m = {-7.0, -6.0, 7.0, 6.0};  // as the world's bounds would set it
  const auto given = read_uav_mission_options(uav_section("uav:\n"
                                                          "  flight_controller: {backend: sim}\n"
                                                          "  search_altitude_m: 5.5\n"
                                                          "  passes: 1\n"
                                                          "  release: hover\n"
                                                          "  winch_controller: baseline\n"
                                                          "  flight_endurance_s: 900\n"),
                                              "m.yaml", o);
  EXPECT_DOUBLE_EQ(o.search_altitude_m, 5.5);
  EXPECT_EQ(o.passes, 1);
  EXPECT_EQ(o.release, "hover");
  EXPECT_EQ(o.winch_controller, "baseline");
  EXPECT_DOUBLE_EQ(o.flight_endurance_s, 900.0);
  EXPECT_EQ(o.search_area_m, Eigen::Vector4d(-7.0, -6.0, 7.0, 6.0));  // not given: the world's
  EXPECT_DOUBLE_EQ(o.search_speed_mps, UavMissionOptions{}.search_speed_mps);
  EXPECT_EQ(given, (std::set<std::string>{"search_altitude_m", "passes", "release", "winch_controller",
                                          "flight_endurance_s"}));
  // No section, or an empty one: nothing changes.
  const UavMissionOptions before = o;
  EXPECT_TRUE(read_uav_mission_options(uav_section("tether: {total_length_m: 15}\n"), "m.yaml", o).empty());
  EXPECT_EQ(dump(o), dump(before));
}

TEST(UavMissionConfig, TheDumpReadsBackToTheSameValues) {
  UavMissionOptions o;
  o.search_area_m = {-20.5, -15.0, 20.0, 15.25};
  o.search_altitude_m = 4.75;
  o.confirm_detections = 3;
  o.survey_frames = 12;
  o.no_landing_zone = "skip";
  o.battery_reserve_fraction = 0.1;  // 0.1 is not exact in binary: the text must round trip
  o.return_timeout_s = 412.5;
  const std::string text = dump(o);
  UavMissionOptions again;
  const auto given = read_uav_mission_options(yaml::load_string(text, "dump"), "dump", again);
  EXPECT_EQ(dump(again), text);
  EXPECT_EQ(given.size(), uav_mission_keys().size());  // the dump writes every key
  EXPECT_EQ(again.search_area_m, o.search_area_m);
  EXPECT_EQ(again.no_landing_zone, "skip");
  EXPECT_EQ(again.survey_frames, 12);
  // Without the search area, the dump leaves it to the world.
  EXPECT_EQ(dump(o, false).find("search_area_m"), std::string::npos);
}

TEST(UavMissionConfig, BadValuesNameTheFileAndTheField) {
  struct Case {
    const char* yaml;
    const char* field;
  };
  const Case cases[] = {
      {"uav:\n  serach_altitude_m: 5\n", "uav.serach_altitude_m"},
      {"uav:\n  passes: two\n", "uav.passes"},
      {"uav:\n  passes: 3\n", "uav.passes"},
      {"uav:\n  survey_frames: 0\n", "uav.survey_frames"},
      {"uav:\n  survey_frames: 65\n", "uav.survey_frames"},
      {"uav:\n  survey_frames: 2.5\n", "uav.survey_frames"},
      {"uav:\n  survey_frames: 1e9\n", "uav.survey_frames"},
      {"uav:\n  search_altitude_m: .nan\n", "uav.search_altitude_m"},
      {"uav:\n  cruise_speed_mps: -1\n", "uav.cruise_speed_mps"},
      {"uav:\n  flight_endurance_s:\n", "uav.flight_endurance_s"},
      {"uav:\n  release: crash\n", "uav.release"},
      {"uav:\n  winch_controller: pid\n", "uav.winch_controller"},
      {"uav:\n  search_area_m: [1, 2, 3]\n", "uav.search_area_m"},
      {"uav:\n  search_area_m: [5, 0, 1, 8]\n", "uav.search_area_m"},
      {"uav:\n  search_area_m:\n", "uav.search_area_m"},
      {"uav:\n  hover_standoff_m: 1.5\n", "uav.hover_standoff_m"},  // not below l_0 = 1 m
      {"uav:\n  passes: 1\n  passes: 2\n", "uav.passes"},
      {"uav: [1, 2]\n", "uav"},
  };
  for (const Case& c : cases) {
    const std::string e = error_of(c.yaml);
    EXPECT_NE(e.find("m.yaml"), std::string::npos) << c.yaml << " -> " << e;
    EXPECT_NE(e.find(c.field), std::string::npos) << c.yaml << " -> " << e;
  }
  EXPECT_EQ(error_of("uav:\n  release: land\n  winch: {backend: sim}\n"), "");
}

TEST(UavMissionConfig, TheBackendsReaderTakesTheMissionKeysAndStillRefusesTypos) {
  // One section, two readers: each takes its own keys and the other's, and no other.
  const auto backends = robot_backends_from_yaml(
      yaml::load_string("uav:\n  search_altitude_m: 5\n  winch: {backend: sim}\n", "m.yaml"), "m.yaml");
  EXPECT_TRUE(backends.all_sim());
  try {
    (void)robot_backends_from_yaml(yaml::load_string("uav:\n  winch_contoller: mpc\n", "m.yaml"), "m.yaml");
    ADD_FAILURE() << "a typo in the uav section was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("uav.winch_contoller"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ferret
