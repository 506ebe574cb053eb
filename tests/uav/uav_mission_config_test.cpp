// The UAV mission's keys in the mission YAML's `uav` section (uav/uav_mission_config.hpp).

#include "ferret/uav/uav_mission_config.hpp"

#include <gtest/gtest.h>

#include <string>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/sim/robot_backends.hpp"
#include "ferret/uav/flight_planner.hpp"

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
  EXPECT_EQ(o.release, ReleaseMode::kHover);
  EXPECT_EQ(o.winch_controller, "baseline");
  EXPECT_DOUBLE_EQ(o.flight_endurance_s, 900.0);
  EXPECT_EQ(o.search_area_m, Eigen::Vector4d(-7.0, -6.0, 7.0, 6.0));  // not given: the world's
  EXPECT_DOUBLE_EQ(o.search_speed_mps, UavMissionOptions{}.search_speed_mps);
  EXPECT_EQ(given, (std::set<std::string>{"search_altitude_m", "passes", "release",
                                          "winch_controller", "flight_endurance_s"}));
  // No section, or an empty one: nothing changes.
  const UavMissionOptions before = o;
  EXPECT_TRUE(
      read_uav_mission_options(uav_section("tether: {total_length_m: 15}\n"), "m.yaml", o).empty());
  EXPECT_EQ(dump(o), dump(before));
}

TEST(UavMissionConfig, TheDumpReadsBackToTheSameValues) {
  UavMissionOptions o;
  o.search_area_m = {-20.5, -15.0, 20.0, 15.25};
  o.search_altitude_m = 4.75;
  o.confirm_detections = 3;
  o.survey_frames = 12;
  o.survey_frames_max = 24;
  o.no_landing_zone = NoLandingZone::kSkip;
  o.release = ReleaseMode::kHover;
  o.battery_reserve_fraction = 0.1;  // 0.1 is not exact in binary: the text must round trip
  o.return_timeout_s = 412.5;
  o.marker.dictionary.family = MarkerFamily::kAprilTag;
  o.marker.dictionary.name = "tag25h9";
  o.marker.marker_size_m = 0.175;
  o.marker_from_mission = true;
  o.winch_controllers.mpc.horizon = 24;  // each controller's own options: the MPC's
  o.winch_controllers.mpc.weight_slack = 0.1;
  o.winch_controllers.baseline.use_preview = true;
  const std::string text = dump(o);
  UavMissionOptions again;
  const auto given = read_uav_mission_options(yaml::load_string(text, "dump"), "dump", again);
  EXPECT_EQ(dump(again), text);
  EXPECT_EQ(given.size(), uav_mission_keys().size());  // the dump writes every key
  EXPECT_EQ(again.search_area_m, o.search_area_m);
  EXPECT_EQ(again.no_landing_zone, NoLandingZone::kSkip);
  EXPECT_EQ(again.release, ReleaseMode::kHover);
  EXPECT_NE(text.find("release: hover\n"), std::string::npos);  // the word, not a number
  EXPECT_NE(dump(UavMissionOptions{}).find("release: land\n"), std::string::npos);
  EXPECT_EQ(again.survey_frames, 12);
  EXPECT_EQ(again.survey_frames_max, 24);
  EXPECT_TRUE(again.marker_from_mission);
  EXPECT_EQ(again.marker.dictionary.family, MarkerFamily::kAprilTag);
  EXPECT_EQ(again.marker.dictionary.name, "tag25h9");
  EXPECT_DOUBLE_EQ(again.marker.marker_size_m, 0.175);
  EXPECT_EQ(again.winch_controllers.mpc.horizon, 24);
  EXPECT_DOUBLE_EQ(again.winch_controllers.mpc.weight_slack, 0.1);
  EXPECT_TRUE(again.winch_controllers.baseline.use_preview);
  EXPECT_NE(text.find("winch_control:"), std::string::npos) << text;
  // Without the search area, the dump leaves it to the world; so the marker, unless set.
  EXPECT_EQ(dump(o, false).find("search_area_m"), std::string::npos);
  EXPECT_EQ(dump(UavMissionOptions{}).find("marker:"), std::string::npos);
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
      {"uav:\n  survey_frames_max: 0\n", "uav.survey_frames_max"},
      {"uav:\n  survey_frames_max: 65\n", "uav.survey_frames_max"},
      {"uav:\n  survey_frames_max: .inf\n", "uav.survey_frames_max"},
      {"uav:\n  search_altitude_m: .nan\n", "uav.search_altitude_m"},
      {"uav:\n  cruise_speed_mps: -1\n", "uav.cruise_speed_mps"},
      {"uav:\n  flight_endurance_s:\n", "uav.flight_endurance_s"},
      {"uav:\n  release: crash\n", "uav.release"},
      {"uav:\n  no_landing_zone: crash\n", "uav.no_landing_zone"},
      {"uav:\n  no_landing_zone:\n", "uav.no_landing_zone"},
      {"uav:\n  winch_controller: pid\n", "uav.winch_controller"},
      {"uav:\n  search_area_m: [1, 2, 3]\n", "uav.search_area_m"},
      {"uav:\n  search_area_m: [5, 0, 1, 8]\n", "uav.search_area_m"},
      {"uav:\n  search_area_m:\n", "uav.search_area_m"},
      {"uav:\n  hover_standoff_m: 1.5\n", "uav.hover_standoff_m"},  // not below l_0 = 1 m
      {"uav:\n  passes: 1\n  passes: 2\n", "uav.passes"},
      {"uav: [1, 2]\n", "uav"},
      {"uav:\n  marker: {family: ar, size_m: 0.2}\n", "uav.marker.family"},
      {"uav:\n  marker: {family: aruco, dictionary: tag25h9, size_m: 0.2}\n",
       "uav.marker.dictionary"},
      {"uav:\n  marker: {family: apriltag, dictionary: DICT_4X4_50, size_m: 0.2}\n",
       "uav.marker.dictionary"},
      {"uav:\n  marker: {family: aruco}\n", "uav.marker.size_m"},
      {"uav:\n  marker: {family: aruco, size_m: .inf}\n", "uav.marker.size_m"},
      {"uav:\n  marker: {family: aruco, size_m: 0}\n", "uav.marker.size_m"},
      {"uav:\n  marker: {family: aruco, size_m: 1e9}\n", "uav.marker.size_m"},
      {"uav:\n  marker: {family: aruco, size_m: 0.2, id: 3}\n", "uav.marker.id"},
      {"uav:\n  marker: {size_m: 0.2}\n", "uav.marker.family"},
      {"uav:\n  marker:\n", "uav.marker"},
      {"uav:\n  marker: DICT_4X4_50\n", "uav.marker"},
      {"uav:\n  winch_control: {mpc: {horizon: 1}}\n", "uav.winch_control.mpc.horizon"},
      {"uav:\n  winch_control: {mpc: {weight_slack: -2}}\n", "uav.winch_control.mpc.weight_slack"},
      {"uav:\n  winch_control: {baseline: {kd: .nan}}\n", "uav.winch_control.baseline.kd"},
      {"uav:\n  winch_control: {pid: {}}\n", "uav.winch_control.pid"},
      {"uav:\n  winch_control:\n", "uav.winch_control"},
  };
  for (const Case& c : cases) {
    const std::string e = error_of(c.yaml);
    EXPECT_NE(e.find("m.yaml"), std::string::npos) << c.yaml << " -> " << e;
    EXPECT_NE(e.find(c.field), std::string::npos) << c.yaml << " -> " << e;
  }
  EXPECT_EQ(error_of("uav:\n  release: land\n  winch: {backend: sim}\n"), "");
}

// The markers the UAV looks for: the family's default dictionary when none is named,
// and what the file sets stays when the world is read afterwards (the mission starts
// from the world's first marker otherwise).
TEST(UavMissionConfig, TheMissionsMarkerIsReadAndTheWorldDoesNotReplaceIt) {
  UavMissionOptions o;
  const auto given = read_uav_mission_options(
      uav_section("uav:\n  marker: {family: apriltag, size_m: 0.3}\n"), "m.yaml", o);
  EXPECT_EQ(given, std::set<std::string>{"marker"});
  EXPECT_TRUE(o.marker_from_mission);
  EXPECT_EQ(o.marker.dictionary.family, MarkerFamily::kAprilTag);
  EXPECT_EQ(o.marker.dictionary.name, "tag36h11");
  EXPECT_DOUBLE_EQ(o.marker.marker_size_m, 0.3);

  const WorldSpec world =
      load_world(std::string(FERRET_SOURCE_DIR) + "/examples/worlds/default.yaml");
  ASSERT_FALSE(world.hidden_spaces.empty());
  ASSERT_EQ(world.hidden_spaces.front().marker.dictionary.name, "DICT_4X4_50");
  fill_uav_mission_from_world(o, world, MissionConfig{});
  EXPECT_EQ(o.marker.dictionary.name, "tag36h11");
  EXPECT_DOUBLE_EQ(o.marker.marker_size_m, 0.3);
  UavMissionOptions from_world;
  fill_uav_mission_from_world(from_world, world, MissionConfig{});
  EXPECT_EQ(from_world.marker.dictionary.name, "DICT_4X4_50");
  EXPECT_DOUBLE_EQ(from_world.marker.marker_size_m, world.hidden_spaces.front().marker.size_m);
}

TEST(UavMissionConfig, TheBackendsReaderTakesTheMissionKeysAndStillRefusesTypos) {
  // One section, two readers: each takes its own keys and the other's, and no other.
  const auto backends = robot_backends_from_yaml(
      yaml::load_string("uav:\n  search_altitude_m: 5\n  winch: {backend: sim}\n", "m.yaml"),
      "m.yaml");
  EXPECT_TRUE(backends.all_sim());
  try {
    (void)robot_backends_from_yaml(yaml::load_string("uav:\n  winch_contoller: mpc\n", "m.yaml"),
                                   "m.yaml");
    ADD_FAILURE() << "a typo in the uav section was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("uav.winch_contoller"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ferret
