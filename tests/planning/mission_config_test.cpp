#include "ferret/planning/mission_config.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>
#include <vector>

#include "ferret/core/error.hpp"

namespace ferret {
namespace {

MissionConfig parse(const std::string& text) {
  return mission_config_from_yaml(YAML::Load(text), "mission.yaml");
}

InputError parse_error(const std::string& text) {
  try {
    (void)parse(text);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "no InputError for:\n" << text;
  return InputError("", "", "");
}

TEST(MissionConfig, DefaultsAreThePapersValues) {
  const MissionConfig c = parse("");
  EXPECT_EQ(c.curiosity.a, -0.5);
  EXPECT_EQ(c.curiosity.b, 0.1);
  EXPECT_EQ(c.curiosity.K, 0.62);
  EXPECT_EQ(c.object_search.lambda1, 0.10);
  EXPECT_EQ(c.object_search.lambda2, 0.95);
  EXPECT_EQ(c.ugv_limits.max_velocity_mps, 2.0);  // the paper's max velocity
  // c(p) = -(p + a)^2 / (4b) + K peaks at p = 0.5 with 0.62 and is about 0 at p = 0 and 1.
  auto curiosity = [&](double p) {
    return -std::pow(p + c.curiosity.a, 2) / (4 * c.curiosity.b) + c.curiosity.K;
  };
  EXPECT_NEAR(curiosity(0.5), 0.62, 1e-12);
  EXPECT_NEAR(curiosity(0.0), -0.005, 1e-12);
  EXPECT_NEAR(curiosity(1.0), -0.005, 1e-12);
}

TEST(MissionConfig, ShippedFileHoldsTheDefaults) {
  const MissionConfig file =
      load_mission_config(std::string(FERRET_SOURCE_DIR) + "/config/mission.yaml");
  EXPECT_EQ(mission_config_to_yaml(file), mission_config_to_yaml(MissionConfig{}));
}

TEST(MissionConfig, PartialFileOverridesOnlyItsKeys) {
  const MissionConfig c = parse("tether: {total_length_m: 8}\nuav_limits: {max_velocity_mps: 3}\n");
  EXPECT_EQ(c.tether.total_length_m, 8.0);
  EXPECT_EQ(c.tether.entry_offset_m, 1.0);
  EXPECT_TRUE(c.tether.catch_speed_limit);
  EXPECT_FALSE(parse("tether: {catch_speed_limit: false}\n").tether.catch_speed_limit);
  EXPECT_EQ(c.uav_limits.max_velocity_mps, 3.0);
  EXPECT_EQ(c.uav_limits.max_yaw_rate_radps, 1.0);
}

TEST(MissionConfig, DumpReadsBackAndIsShortest) {
  MissionConfig c;
  c.curiosity.K = 0.7;
  c.object_search.eta_m = 1.25;
  c.ugv_limits.max_velocity_mps = 0.3;
  const std::string text = mission_config_to_yaml(c);
  EXPECT_NE(text.find("lambda1: 0.1\n"), std::string::npos) << text;  // not 0.10000000000000001
  EXPECT_EQ(mission_config_to_yaml(parse(text)), text);
  EXPECT_EQ(parse(text).ugv_limits.max_velocity_mps, 0.3);
}

TEST(MissionConfig, WrongType) {
  const auto e = parse_error("object_search:\n  lambda1: high\n");
  EXPECT_EQ(e.source(), "mission.yaml");
  EXPECT_EQ(e.field(), "object_search.lambda1");
  EXPECT_EQ(e.expected(), "a number in [0, 0.5]");  // the range, even when the type is wrong
  EXPECT_EQ(parse_error("curiosity: 3\n").field(), "curiosity");
  EXPECT_EQ(parse_error("tether:\n  total_length_m: [1, 2]\n").field(), "tether.total_length_m");
}

TEST(MissionConfig, UnknownKeys) {
  auto e = parse_error("curiosty:\n  a: 1\n");
  EXPECT_EQ(e.field(), "curiosty");
  EXPECT_NE(e.expected().find("curiosity"), std::string::npos);  // lists the keys it knows
  e = parse_error("ugv_limits:\n  max_speed_mps: 1\n");
  EXPECT_EQ(e.field(), "ugv_limits.max_speed_mps");
}

TEST(MissionConfig, TheBackendSectionsAreAllowedButATypoOfThemIsNot) {
  // `ugv` and `uav` belong to the backends' reader (sim/robot_backends.hpp); this layer
  // lets them through and still refuses a misspelt section.
  EXPECT_EQ(parse("ugv: {base: {backend: hw}}\nuav: {winch: {}}\ntether: {total_length_m: 9}\n")
                .tether.total_length_m,
            9.0);
  const auto e = parse_error("ugvs:\n  base: {backend: hw}\n");
  EXPECT_EQ(e.field(), "ugvs");
  EXPECT_NE(e.expected().find("ugv, uav"), std::string::npos) << e.expected();
}

TEST(MissionConfig, OutOfRangeValues) {
  EXPECT_EQ(parse_error("object_search: {lambda2: 1.5}\n").field(), "object_search.lambda2");
  EXPECT_EQ(parse_error("object_search: {lambda1: -0.1}\n").field(), "object_search.lambda1");
  EXPECT_EQ(parse_error("curiosity: {b: 0}\n").field(), "curiosity.b");
  EXPECT_EQ(parse_error("ugv_limits: {max_velocity_mps: 0}\n").field(),
            "ugv_limits.max_velocity_mps");
  EXPECT_EQ(parse_error("tether: {total_length_m: -1}\n").field(), "tether.total_length_m");
  EXPECT_EQ(parse_error("tether: {catch_speed_limit: 2}\n").field(), "tether.catch_speed_limit");
  EXPECT_EQ(parse_error("object_search: {eta_m: .nan}\n").field(), "object_search.eta_m");
  // Inconsistent pairs name the field that breaks the relation.
  EXPECT_EQ(parse_error("object_search: {conf_floor: 0.9, conf_cap: 0.8}\n").field(),
            "object_search.conf_floor");
  EXPECT_EQ(parse_error("tether: {total_length_m: 2, entry_offset_m: 2}\n").field(),
            "tether.entry_offset_m");
}

TEST(MissionConfig, MissingFile) {
  try {
    (void)load_mission_config("/nonexistent/mission.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "/nonexistent/mission.yaml");
  }
}

TEST(MissionConfig, RolesAndProvenanceReadBack) {
  const MissionConfig c = mission_config_from_yaml(
      YAML::Load("roles: {rover: {object_camera: cam_main, ir: [range_l, range_r]}}\n"
                 "ugv_limits: {max_velocity_mps: 0.4}\n"),
      "m.yaml");
  ASSERT_EQ(c.roles.count("rover"), 1u);
  EXPECT_EQ(c.roles.at("rover").at("object_camera"), std::vector<std::string>{"cam_main"});
  EXPECT_EQ(c.roles.at("rover").at("ir"), (std::vector<std::string>{"range_l", "range_r"}));
  EXPECT_EQ(c.provenance("ugv_limits.max_velocity_mps"), "mission:m.yaml");
  EXPECT_EQ(c.provenance("ugv_limits.max_yaw_rate_radps"), "default");
  // The dump reads back to the same roles.
  const MissionConfig again =
      mission_config_from_yaml(YAML::Load(mission_config_to_yaml(c)), "dump.yaml");
  EXPECT_EQ(again.roles, c.roles);
  EXPECT_EQ(MissionConfig{}.provenance("curiosity.K"), "default");
}

}  // namespace
}  // namespace ferret
