// The miniUGV mission's keys in the mission YAML's `ugv` section and its search's tuning
// under `ugv.explore` (ugv/ugv_mission_config.hpp).

#include "ferret/ugv/ugv_mission_config.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"

namespace ferret {
namespace {

YAML::Node ugv_section(const std::string& text) { return yaml::load_string(text, "m.yaml")["ugv"]; }

std::string dump(const UgvMissionOptions& o) {
  YAML::Emitter e;
  e << YAML::BeginMap;
  emit_ugv_mission_options(e, o);
  e << YAML::EndMap;
  return e.c_str();
}

// The field a bad section's InputError names (with the file checked), or "" when read.
std::string field_of_error(const std::string& text, std::string* message = nullptr) {
  try {
    UgvMissionOptions o;
    (void)read_ugv_mission_options(ugv_section(text), "m.yaml", o);
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "m.yaml");
    if (message) *message = e.what();
    return e.field();
  }
  return "";
}

TEST(UgvMissionConfig, TheKeysTheFileSetsLandInTheirFields) {
  UgvMissionOptions o;
  const auto given = read_ugv_mission_options(ugv_section("ugv:\n"
                                                          "  base: {backend: sim}\n"
                                                          "  explore_timeout_s: 250\n"
                                                          "  grasp_attempts: 5\n"
                                                          "  grasp_speed_mps: 0.05\n"
                                                          "  tether_aware: false\n"
                                                          "  battery_reserve_fraction: 0.2\n"
                                                          "  explore:\n"
                                                          "    max_revisits: 1\n"
                                                          "    decision_period_s: 0.2\n"
                                                          "    cdos_closest_approach: true\n"
                                                          "    tether_margin_m: 0.5\n"),
                                              "m.yaml", o);
  EXPECT_DOUBLE_EQ(o.explore_timeout_s, 250.0);
  EXPECT_EQ(o.grasp_attempts, 5);
  EXPECT_DOUBLE_EQ(o.grasp_speed_mps, 0.05);
  EXPECT_FALSE(o.tether_aware);
  EXPECT_DOUBLE_EQ(o.battery_reserve_fraction, 0.2);
  EXPECT_EQ(o.explore.max_revisits, 1);
  EXPECT_DOUBLE_EQ(o.explore.decision_period_s, 0.2);
  EXPECT_TRUE(o.explore.cdos_closest_approach);
  EXPECT_DOUBLE_EQ(o.explore.tether_margin_m, 0.5);
  // Not given: the struct's defaults.
  const UgvMissionOptions defaults;
  EXPECT_DOUBLE_EQ(o.track_timeout_s, defaults.track_timeout_s);
  EXPECT_DOUBLE_EQ(o.explore.tether_obstacle_depth_m, defaults.explore.tether_obstacle_depth_m);
  EXPECT_FALSE(o.explore.cdos_candidates_global);
  EXPECT_EQ(given,
            (std::set<std::string>{"explore_timeout_s", "grasp_attempts", "grasp_speed_mps",
                                   "tether_aware", "battery_reserve_fraction",
                                   "explore.max_revisits", "explore.decision_period_s",
                                   "explore.cdos_closest_approach", "explore.tether_margin_m"}));
}

TEST(UgvMissionConfig, NoSectionOrOnlyTheBaseChangesNothing) {
  UgvMissionOptions o;
  const std::string before = dump(o);
  EXPECT_TRUE(
      read_ugv_mission_options(ugv_section("tether: {total_length_m: 15}\n"), "m.yaml", o).empty());
  EXPECT_TRUE(
      read_ugv_mission_options(ugv_section("ugv:\n  base: {backend: sim}\n"), "m.yaml", o).empty());
  EXPECT_EQ(dump(o), before);
}

TEST(UgvMissionConfig, TheDumpReadsBackToTheSameValues) {
  UgvMissionOptions o;
  o.explore_timeout_s = 412.5;
  o.battery_reserve_fraction = 0.1;  // 0.1 is not exact in binary: the text must round trip
  o.grasp_attempts = 7;
  o.tether_aware = false;
  o.explore.max_revisits = 0;
  o.explore.cdos_candidates_global = true;
  o.explore.tether_obstacle_depth_m = 0.35;
  const std::string text = dump(o);
  UgvMissionOptions again;
  const auto given = read_ugv_mission_options(yaml::load_string(text, "dump"), "dump", again);
  EXPECT_EQ(dump(again), text);
  // The dump writes every key: the mission's (explore as its keys) and the search's.
  EXPECT_EQ(given.size(), ugv_mission_keys().size() - 1 + explore_tuning_keys().size());
  EXPECT_DOUBLE_EQ(again.explore_timeout_s, 412.5);
  EXPECT_DOUBLE_EQ(again.battery_reserve_fraction, 0.1);
  EXPECT_EQ(again.grasp_attempts, 7);
  EXPECT_FALSE(again.tether_aware);
  EXPECT_EQ(again.explore.max_revisits, 0);
  EXPECT_TRUE(again.explore.cdos_candidates_global);
  EXPECT_DOUBLE_EQ(again.explore.tether_obstacle_depth_m, 0.35);
  EXPECT_NE(text.find("explore_timeout_s: 412.5\n"), std::string::npos) << text;
  EXPECT_NE(text.find("tether_aware: false\n"), std::string::npos) << text;
}

TEST(UgvMissionConfig, AssigningTheKeysLeavesWhatTheRunFilled) {
  UgvMissionOptions file;
  file.explore_timeout_s = 90.0;
  file.explore.max_revisits = 1;
  UgvMissionOptions run;
  run.bump_time_s = 0.7;                // the base's stall time
  run.line_catch.pull_budget_n = 12.0;  // from the winch
  run.explore.planner = FrontierPlanner::kOmpl;
  run.explore.method = "nearest";
  assign_ugv_mission_keys(run, file);
  EXPECT_DOUBLE_EQ(run.explore_timeout_s, 90.0);
  EXPECT_EQ(run.explore.max_revisits, 1);
  EXPECT_DOUBLE_EQ(run.bump_time_s, 0.7);
  EXPECT_DOUBLE_EQ(run.line_catch.pull_budget_n, 12.0);
  EXPECT_EQ(run.explore.planner, FrontierPlanner::kOmpl);
  EXPECT_EQ(run.explore.method, "nearest");
}

TEST(UgvMissionConfig, AnUnknownKeyIsNamedWithTheKeysAllowed) {
  std::string message;
  EXPECT_EQ(field_of_error("ugv:\n  explor_timeout_s: 5\n", &message), "ugv.explor_timeout_s");
  // The list names the base and the mission's keys alike.
  EXPECT_NE(message.find("base"), std::string::npos) << message;
  EXPECT_NE(message.find("grasp_attempts"), std::string::npos) << message;
  EXPECT_NE(message.find("explore"), std::string::npos) << message;
  EXPECT_EQ(field_of_error("ugv:\n  explore: {max_revisit: 1}\n", &message),
            "ugv.explore.max_revisit");
  EXPECT_NE(message.find("max_revisits"), std::string::npos) << message;
  // Keys the run fills are not the file's.
  EXPECT_EQ(field_of_error("ugv:\n  bump_time_s: 0.5\n"), "ugv.bump_time_s");
  EXPECT_EQ(field_of_error("ugv:\n  explore: {method: nearest}\n"), "ugv.explore.method");
}

TEST(UgvMissionConfig, BadValuesNameTheFieldAndTheExpectation) {
  struct Case {
    const char* yaml;
    const char* field;
    const char* expected;  ///< a part of the message
  };
  const Case cases[] = {
      // wrong type
      {"ugv:\n  explore_timeout_s: long\n", "ugv.explore_timeout_s", "number"},
      {"ugv:\n  grasp_attempts: 2.5\n", "ugv.grasp_attempts", "integer"},
      {"ugv:\n  tether_aware: maybe\n", "ugv.tether_aware", "true or false"},
      {"ugv:\n  explore: 3\n", "ugv.explore", "mapping"},
      {"ugv:\n  explore:\n", "ugv.explore", "mapping"},
      {"ugv:\n  grasp_timeout_s:\n", "ugv.grasp_timeout_s", "number"},
      // not finite
      {"ugv:\n  explore_timeout_s: .nan\n", "ugv.explore_timeout_s", "finite"},
      {"ugv:\n  track_timeout_s: .inf\n", "ugv.track_timeout_s", "finite"},
      {"ugv:\n  explore: {tether_margin_m: .nan}\n", "ugv.explore.tether_margin_m", "finite"},
      // negative or zero
      {"ugv:\n  explore_timeout_s: -1\n", "ugv.explore_timeout_s", "(0, "},
      {"ugv:\n  grasp_overshoot_m: -0.1\n", "ugv.grasp_overshoot_m", "[0, "},
      {"ugv:\n  explore: {decision_period_s: 0}\n", "ugv.explore.decision_period_s", "(0, "},
      {"ugv:\n  explore: {max_revisits: -1}\n", "ugv.explore.max_revisits", "[0, 100]"},
      // absurd
      {"ugv:\n  retract_timeout_s: 1e9\n", "ugv.retract_timeout_s", "(0, "},
      {"ugv:\n  grasp_attempts: 1000\n", "ugv.grasp_attempts", "[1, 100]"},
      {"ugv:\n  battery_reserve_fraction: 0.95\n", "ugv.battery_reserve_fraction", "[0, 0.9]"},
      {"ugv:\n  explore: {tether_obstacle_depth_m: 20}\n", "ugv.explore.tether_obstacle_depth_m",
       "[0, 10]"},
      // values that contradict each other
      {"ugv:\n  standoff_m: 0.1\n", "ugv.standoff_m", "rear_offset_m"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.yaml);
    std::string message;
    EXPECT_EQ(field_of_error(c.yaml, &message), c.field);
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace ferret
