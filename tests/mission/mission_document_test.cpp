// The mission YAML parsed once (mission/mission_document.hpp): every section from the
// one document, the UAV mission's keys applied over what the world set.

#include "ferret/mission/mission_document.hpp"

#include <gtest/gtest.h>

#include <string>

#include "ferret/core/data_path.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/uav/uav_mission_config.hpp"
#include "ferret/ugv/ugv_mission_config.hpp"

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
      {"ugv:\n  explore_timout_s: 5\n", "ugv.explore_timout_s"},
      {"ugv:\n  grasp_attempts: 0\n", "ugv.grasp_attempts"},
      {"ugv:\n  explore: {max_revisits: .nan}\n", "ugv.explore.max_revisits"},
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

TEST(MissionDocument, TheMiniUgvKeysAreReadOnceAndAppliedOverTheRun) {
  const MissionDocument d = parse(
      "ugv:\n  base: {backend: sim, stall_time_s: 0.5}\n  explore_timeout_s: 120\n"
      "  grasp_attempts: 2\n  explore: {max_revisits: 1, cdos_candidates_global: true}\n");
  EXPECT_DOUBLE_EQ(d.ugv_mission.explore_timeout_s, 120.0);
  EXPECT_EQ(d.ugv_mission.explore.max_revisits, 1);
  EXPECT_DOUBLE_EQ(d.backends.ugv_base.stall_time_s, 0.5);  // the base's reader, the same section
  EXPECT_EQ(d.ugv_mission_given,
            (std::set<std::string>{"explore_timeout_s", "grasp_attempts", "explore.max_revisits",
                                   "explore.cdos_candidates_global"}));
  // Over a deployment's settings: the file's keys win, what the run filled stays, and the
  // search's tuning goes where the controller's search takes it from.
  UgvMissionRunSettings run;
  run.ugv.bump_time_s = 0.4;
  run.ugv.line_catch.pull_budget_n = 20.0;
  run.ugv.explore.planner = FrontierPlanner::kOmpl;
  run.exploration.method = "nearest";
  d.apply_ugv_mission(run);
  EXPECT_DOUBLE_EQ(run.ugv.explore_timeout_s, 120.0);
  EXPECT_EQ(run.ugv.grasp_attempts, 2);
  EXPECT_DOUBLE_EQ(run.ugv.track_timeout_s, UgvMissionOptions{}.track_timeout_s);
  EXPECT_DOUBLE_EQ(run.ugv.bump_time_s, 0.4);
  EXPECT_DOUBLE_EQ(run.ugv.line_catch.pull_budget_n, 20.0);
  EXPECT_EQ(run.ugv.explore.planner, FrontierPlanner::kOmpl);
  EXPECT_EQ(run.exploration.max_revisits, 1);
  EXPECT_TRUE(run.exploration.cdos_candidates_global);
  EXPECT_EQ(run.exploration.method, "nearest");
  // Without keys, the settings are exactly what they were.
  UgvMissionRunSettings untouched;
  parse("ugv: {base: {backend: sim}}\n").apply_ugv_mission(untouched);
  YAML::Emitter a, b;
  a << YAML::BeginMap;
  emit_ugv_mission_options(a, untouched.ugv);
  a << YAML::EndMap;
  b << YAML::BeginMap;
  emit_ugv_mission_options(b, UgvMissionRunSettings{}.ugv);
  b << YAML::EndMap;
  EXPECT_EQ(std::string(a.c_str()), std::string(b.c_str()));
}

// The shipped mission file's mission sections, as `ferret config --dump` writes them
// (uav_mission, ugv_mission), read back as the `uav` and `ugv` sections of a mission YAML
// give the same values.
TEST(MissionDocument, TheDumpOfTheShippedMissionReadsBack) {
  const MissionDocument d = load_mission_document(data_path("config/mission.yaml"));
  const auto sections = [](const MissionDocument& doc) {
    YAML::Emitter e;
    e << YAML::BeginMap << YAML::Key << "uav" << YAML::Value << YAML::BeginMap;
    emit_uav_mission_options(e, doc.uav_mission, true);
    e << YAML::EndMap << YAML::Key << "ugv" << YAML::Value << YAML::BeginMap;
    emit_ugv_mission_options(e, doc.ugv_mission);
    e << YAML::EndMap << YAML::EndMap;
    return std::string(e.c_str());
  };
  const std::string text = sections(d);
  const MissionDocument again = parse(text);
  EXPECT_EQ(sections(again), text);
  EXPECT_EQ(again.ugv_mission_given.size(),
            ugv_mission_keys().size() - 1 + explore_tuning_keys().size());
  EXPECT_NE(text.find("explore_timeout_s:"), std::string::npos) << text;
}

TEST(MissionDocument, AMissingFileIsAnInputError) {
  EXPECT_THROW((void)load_mission_document("/nonexistent/mission.yaml"), InputError);
}

}  // namespace
}  // namespace ferret
