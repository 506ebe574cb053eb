#include "ferret/planning/plan_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "ferret/core/error.hpp"
#include "support/json_schema.hpp"

namespace ferret {
namespace {

PlanFile sample() {
  PlanFile p;
  p.robot = PlanRobot::kUgv;
  p.unknown_policy = UnknownPolicy::kOccupied;
  p.bounds = Aabb3{{0, 0, 0}, {12, 8, 0.12}};
  p.max_velocity_mps = 2.0;
  p.max_yaw_rate_radps = 2.0;
  p.tether = PlanTether{{-0.1, 4.0}, {{{3.0, 5.5}, -1}, {{9.0, 5.5}, -1}}, 13.5, 1.0};
  for (int k = 0; k < 3; ++k) {
    Waypoint w;
    w.t_s = 0.1 * k + 1.0 / 3.0;
    w.x_m = 10.0 + k / 7.0;
    w.y_m = 4.5;
    w.yaw_rad = -1.57;
    w.tether_length_m = 10.0 + k;
    p.states.push_back(w);
  }
  p.planner = "TetheredRRT";
  p.seed = 42;
  return p;
}

TEST(PlanFile, JsonRoundTripsExactly) {
  const PlanFile p = sample();
  const PlanFile q = parse_plan(plan_to_json(p), "mem");
  EXPECT_EQ(q.robot, PlanRobot::kUgv);
  ASSERT_EQ(q.states.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(q.states[k].t_s, p.states[k].t_s);  // bit-exact: validation re-checks the same poses
    EXPECT_EQ(q.states[k].x_m, p.states[k].x_m);
    EXPECT_EQ(q.states[k].tether_length_m, p.states[k].tether_length_m);
  }
  ASSERT_TRUE(q.tether);
  EXPECT_EQ(q.tether->initial_wraps, p.tether->initial_wraps);
  EXPECT_EQ(q.tether->total_length_m, 13.5);
  EXPECT_EQ(*q.unknown_policy, UnknownPolicy::kOccupied);
  EXPECT_EQ(q.bounds->hi.x(), 12.0);
  EXPECT_EQ(q.seed, 42u);
}

TEST(PlanFile, CsvHeaderShortOrUnitNames) {
  const PlanFile a = parse_plan("t,x,y,z,yaw\n0,1,2,3,0.5\n1.5, 2, 2, 3, 0.5\n", "a.csv");
  EXPECT_FALSE(a.robot_known);
  ASSERT_EQ(a.states.size(), 2u);
  EXPECT_EQ(a.states[1].t_s, 1.5);
  EXPECT_EQ(a.states[1].x_m, 2.0);
  const PlanFile b =
      parse_plan("# comment\n\n t_s , x_m,y_m,z_m,yaw_rad\r\n0,1,2,3,0.5\r\n", "b.csv");
  ASSERT_EQ(b.states.size(), 1u);
  EXPECT_EQ(b.states[0].z_m, 3.0);
  EXPECT_EQ(b.states[0].yaw_rad, 0.5);
}

void expect_error(const std::string& text, const std::string& field,
                  const std::string& expected_part) {
  try {
    (void)parse_plan(text, "plan.json");
    FAIL() << "accepted: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "plan.json");
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.what()).find(expected_part), std::string::npos) << e.what();
  }
}

TEST(PlanFile, BadFilesNameTheFieldAndTheExpectation) {
  std::string good = plan_to_json(sample());
  expect_error("", "", "a plan");
  expect_error("{\"format\": \"ferret-plan\", ", "line 1 column 27", "valid JSON");  // at the end
  expect_error("{\"format\": \"other\"}", "format", "ferret-plan");
  expect_error("{\"format\": \"ferret-plan\", \"version\": 2}", "version", "1");
  auto replace = [&](const std::string& from, const std::string& to) {
    std::string s = good;
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  expect_error(replace("\"robot\": \"ugv\"", "\"robot\": \"tank\""), "robot", "\"uav\"");
  expect_error(replace("\"x_m\": 10.0", "\"x_m\": \"ten\""), "states[0].x_m", "a finite number");
  expect_error(replace("\"side\": -1", "\"side\": 0"), "tether.initial_wraps[0].side", "1 or -1");
  expect_error(replace("\"entry\": [", "\"entry\": [1, "), "tether.entry", "a list of 2 numbers");
  expect_error(replace("\"unknown_policy\": \"occupied\"", "\"unknown_policy\": \"maybe\""),
               "unknown_policy", "\"free\" or");
  expect_error("t,x,y,z,yaw\n0,1,2,3\n", "line 2", "5 comma-separated numbers");
  expect_error("0,1,2,3,0\nt,x,y,z,yaw\n", "line 1 column 1", "a header");  // header first
  expect_error("t,x,y,z,yaw\n0,1,2,3,abc\n", "line 2 column 5 (yaw)", "a finite number");
  EXPECT_THROW((void)load_plan("/nonexistent/plan.json"), InputError);
}

test::JsonSchema plan_schema() {
  std::ifstream in(std::string(FERRET_SOURCE_DIR) + "/docs/plan.schema.json");
  return test::JsonSchema(nlohmann::json::parse(in));
}

// docs/plan.schema.json and the reader agree: what ferret writes and every shipped JSON
// plan conform and parse; documents the schema refuses, the reader refuses too.
TEST(PlanFile, ShippedAndWrittenPlansMatchTheSchema) {
  const test::JsonSchema schema = plan_schema();
  const auto written = nlohmann::json::parse(plan_to_json(sample()));
  const auto errors = schema.errors(written);
  EXPECT_TRUE(errors.empty()) << errors.front();
  int shipped = 0;
  for (const auto& f :
       std::filesystem::directory_iterator(std::string(FERRET_SOURCE_DIR) + "/examples/plans")) {
    if (f.path().extension() != ".json") continue;
    ++shipped;
    std::ifstream in(f.path());
    const auto doc = nlohmann::json::parse(in);
    const auto e = schema.errors(doc);
    EXPECT_TRUE(e.empty()) << f.path() << ": " << e.front();
    EXPECT_NO_THROW((void)load_plan(f.path())) << f.path();
  }
  EXPECT_GE(shipped, 4);
  for (
      const std::string bad :
      {R"({"states": [{"t_s": 0, "x_m": 0, "y_m": 0, "z_m": 0, "yaw_rad": 0, "v": 1}]})",
       R"({"format": "ferret-plan", "version": 1, "robot": "uav", "states": [], "x": 1})",
       R"({"format": "ferret-plan", "version": 1, "robot": "uav", "states": [{"t_s": 0, "x_m": 1e6, "y_m": 0, "z_m": 0, "yaw_rad": 0}]})"}) {
    EXPECT_FALSE(schema.errors(nlohmann::json::parse(bad)).empty()) << bad;
    EXPECT_THROW((void)parse_plan(bad, "bad.json"), InputError) << bad;
  }
}

TEST(PlanFile, SaveIsAtomicAndReadable) {
  const auto dir = std::filesystem::temp_directory_path() / "ferret_plan_file_test";
  std::filesystem::remove_all(dir);
  const auto path = dir / "p.json";
  save_plan(sample(), path);
  EXPECT_EQ(load_plan(path).states.size(), 3u);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir),
                          std::filesystem::directory_iterator{}),
            1);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ferret
