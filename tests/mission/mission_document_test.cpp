// The mission YAML parsed once (mission/mission_document.hpp): every section from the
// one document, the UAV mission's keys applied over what the world set.

#include "ferret/mission/mission_document.hpp"

#include <gtest/gtest.h>

#include <string>

#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"

namespace ferret {
namespace {

MissionDocument parse(const std::string& text) {
  return mission_document_from_yaml(yaml::load_string(text, "m.yaml"), "m.yaml");
}

TEST(MissionDocument, AnEmptyDocumentIsTheDefaults) {
  const MissionDocument d = parse("");
  EXPECT_DOUBLE_EQ(d.config.tether.total_length_m, TetherParams{}.total_length_m);
  EXPECT_TRUE(d.backends.all_sim());
  EXPECT_TRUE(d.uav_mission_given.empty());
  UavMissionOptions world;
  world.search_altitude_m = 7.0;
  d.apply_uav_mission(world);  // nothing to apply
  EXPECT_DOUBLE_EQ(world.search_altitude_m, 7.0);
}

TEST(MissionDocument, EverySectionComesFromTheOneDocument) {
  const MissionDocument d = parse(
      "tether: {total_length_m: 9}\n"
      "ugv_limits: {max_velocity_mps: 0.5}\n"
      "ugv: {base: {backend: sim}}\n"
      "uav:\n  winch: {backend: sim}\n  search_altitude_m: 6\n  release: hover\n");
  EXPECT_DOUBLE_EQ(d.config.tether.total_length_m, 9.0);
  EXPECT_EQ(d.config.provenance("tether.total_length_m"), "mission:m.yaml");
  EXPECT_EQ(d.config.provenance("tether.entry_offset_m"), "default");
  EXPECT_DOUBLE_EQ(d.config.ugv_limits.max_velocity_mps, 0.5);
  EXPECT_TRUE(d.backends.all_sim());
  // The UAV mission's keys over the defaults, with the mission's tether.
  EXPECT_DOUBLE_EQ(d.uav_mission.search_altitude_m, 6.0);
  EXPECT_EQ(d.uav_mission.release, ReleaseMode::kHover);
  EXPECT_DOUBLE_EQ(d.uav_mission.tether.total_length_m, 9.0);
  EXPECT_EQ(d.uav_mission_given.count("search_altitude_m"), 1u);
  EXPECT_EQ(d.uav_mission_given.count("winch"), 0u);  // a backend, not the mission's

  // Applied over what the world set: the file's keys win, the others keep the world's.
  UavMissionOptions world;
  world.search_area_m = {-3.0, -4.0, 3.0, 4.0};
  world.search_altitude_m = 2.0;
  d.apply_uav_mission(world);
  EXPECT_DOUBLE_EQ(world.search_altitude_m, 6.0);
  EXPECT_DOUBLE_EQ(world.search_area_m[1], -4.0);
}

TEST(MissionDocument, BadInputInAnySectionNamesTheFileAndTheField) {
  const struct {
    const char* yaml;
    const char* field;
  } cases[] = {
      {"tether: {total_length_m: -1}\n", "tether.total_length_m"},
      {"object_search: {lambda2: 2}\n", "object_search.lambda2"},
      {"ugv: {base: {backend: lego}}\n", "ugv.base.backend"},
      {"uav:\n  serach_altitude_m: 5\n", "uav.serach_altitude_m"},
      {"uav:\n  release: crash\n", "uav.release"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.yaml);
    try {
      (void)parse(c.yaml);
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), "m.yaml");
      EXPECT_EQ(e.field(), c.field);
    }
  }
}

TEST(MissionDocument, AMissingFileIsAnInputError) {
  EXPECT_THROW((void)load_mission_document("/nonexistent/mission.yaml"), InputError);
}

}  // namespace
}  // namespace ferret
