// Plan files a hostile or careless user could write (generated here): every one is an
// InputError naming the file, the field and what was expected, never a misread plan,
// an internal error or work proportional to a number in the file.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/planning/plan_file.hpp"
#include "ferret/planning/plan_validation.hpp"

namespace ferret {
namespace {

using ::testing::HasSubstr;

// The InputError of parsing `text` as "p.x" (the source every case uses).
InputError error_of(const std::string& text) {
  try {
    (void)parse_plan(text, "p.x");
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "accepted: " << text.substr(0, 200);
  return InputError("", "", "");
}

void expect_error(const std::string& text, const std::string& field,
                  const std::string& expected_part, const std::string& got_part = "") {
  const InputError e = error_of(text);
  EXPECT_EQ(e.source(), "p.x") << e.what();
  EXPECT_EQ(e.field(), field) << e.what();
  EXPECT_THAT(e.expected(), HasSubstr(expected_part)) << e.what();
  EXPECT_THAT(std::string(e.what()), HasSubstr(got_part)) << e.what();
  EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();  // one line
}

// A complete ferret miniUGV plan; `tweak` replaces one fragment of it.
const std::string kPlan =
    R"({"format": "ferret-plan", "version": 1, "robot": "ugv", "frame": "world",
 "planner": {"name": "TetheredRRT", "seed": 3, "world": "w.yaml"},
 "unknown_policy": "occupied",
 "bounds": {"min": [0, 0, 0], "max": [12, 8, 0.12]},
 "limits": {"max_velocity_mps": 2.0, "max_yaw_rate_radps": 2.0},
 "tether": {"entry": [-0.1, 4.0], "total_length_m": 13.5, "entry_offset_m": 1.0,
            "initial_wraps": [{"p": [3.0, 5.5], "side": -1}]},
 "states": [{"t_s": 0, "x_m": 1, "y_m": 2, "z_m": 0, "yaw_rad": 0},
            {"t_s": 1, "x_m": 2, "y_m": 2, "z_m": 0, "yaw_rad": 0, "tether_length_m": 3}]})";

std::string tweak(const std::string& from, const std::string& to) {
  std::string s = kPlan;
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

TEST(PlanFileBadInput, TheFullPlanParses) {
  const PlanFile p = parse_plan(kPlan, "p.x");  // the base of every case below is valid
  ASSERT_EQ(p.states.size(), 2u);
  EXPECT_EQ(p.states[1].tether_length_m, 3.0);
  EXPECT_EQ(p.seed, 3u);
  EXPECT_EQ(p.tether->initial_wraps.at(0).side, -1);
}

TEST(PlanFileBadInput, CsvColumnsAreReadByName) {
  // The header the campaign found misread by position: time last.
  const PlanFile a = parse_plan("x,y,z,yaw,t\n1,2,3,0.5,7\n4,5,6,-0.5,8\n", "p.csv");
  ASSERT_EQ(a.states.size(), 2u);
  EXPECT_EQ(a.states[0].t_s, 7.0);
  EXPECT_EQ(a.states[0].x_m, 1.0);
  EXPECT_EQ(a.states[0].y_m, 2.0);
  EXPECT_EQ(a.states[0].z_m, 3.0);
  EXPECT_EQ(a.states[0].yaw_rad, 0.5);
  EXPECT_EQ(a.states[1].t_s, 8.0);
  EXPECT_EQ(a.states[1].yaw_rad, -0.5);
  // Unit-suffixed names, mixed with short ones, in another order.
  const PlanFile b = parse_plan("# other tool\nyaw_rad,z,t_s,y_m,x\n0.25,9,1.5,-3,4\n", "p.csv");
  ASSERT_EQ(b.states.size(), 1u);
  EXPECT_EQ(b.states[0].yaw_rad, 0.25);
  EXPECT_EQ(b.states[0].z_m, 9.0);
  EXPECT_EQ(b.states[0].t_s, 1.5);
  EXPECT_EQ(b.states[0].y_m, -3.0);
  EXPECT_EQ(b.states[0].x_m, 4.0);
}

TEST(PlanFileBadInput, CsvHeaderRequiredAndChecked) {
  expect_error("a,b\n1,2\n", "line 1 column 1", "a header naming the columns", "'a'");
  expect_error("0,1,2,3,0\n1,2,2,3,0\n", "line 1 column 1", "a header", "no header line");
  expect_error("t,x,y,z\n0,1,2,3\n", "line 1", "a header", "no column 'yaw'");
  expect_error("t,x,y,z,yaw,x\n0,1,2,3,0,1\n", "line 1 column 6", "each once", "'x' again");
  expect_error("t,x_m,y,z,yaw,x\n0,1,2,3,0,1\n", "line 1 column 6", "each once", "'x' again");
  expect_error("t,x,y,z,yaw,speed\n0,1,2,3,0,1\n", "line 1 column 6", "a header", "'speed'");
  expect_error("# only a comment\n", "", "a header", "no header line");
  expect_error("t,x,y,z,yaw\n", "", "at least one state", "none");
}

TEST(PlanFileBadInput, CsvRowsHaveTheHeadersCells) {
  expect_error("t,x,y,z,yaw\n0,1,2,3,0\n0,1,2,3\n", "line 3", "5 comma-separated", "4 cells");
  expect_error("t,x,y,z,yaw\n0,1,2,3,0,9\n", "line 2", "5 comma-separated", "6 cells");
  expect_error("t,x,y,z,yaw\n0,1,2,3,0,\n", "line 2", "5 comma-separated", "6 cells");
}

TEST(PlanFileBadInput, CsvEveryNonFiniteOrMalformedCell) {
  for (const std::string cell : {"", " ", "nan", "NaN", "-nan", "inf", "-inf", "Infinity", "1e400",
                                 "-1e400", "0x10", "1.5abc", "1 2", "--1", "1e", "one", "1,5"}) {
    SCOPED_TRACE(cell);
    const std::string text = "t,x,y,z,yaw\n0,1,2,3,0\n1," + cell + ",2,3,0\n";
    if (cell == "1,5") {  // a comma is a column more
      expect_error(text, "line 3", "5 comma-separated");
      continue;
    }
    expect_error(text, "line 3 column 2 (x)", "a finite number");
  }
  // Still numbers: a leading plus, exponents, spaces round the cell.
  const PlanFile p = parse_plan("t,x,y,z,yaw\n+1, 2e1 ,-3.5E-1,0,0\n", "p.csv");
  EXPECT_EQ(p.states[0].t_s, 1.0);
  EXPECT_EQ(p.states[0].x_m, 20.0);
  EXPECT_EQ(p.states[0].y_m, -0.35);
}

TEST(PlanFileBadInput, CoordinatesWithinTheStatedBound) {
  // 4e9 m grew to GBs in the collision check; a coordinate is bounded at +-1e5 m.
  expect_error("t,x,y,z,yaw\n0,0,0,0,0\n1,4e9,0,0,0\n", "line 3 column 2 (x)",
               "a coordinate within +-100000 m", "4e9");
  expect_error(tweak(R"("x_m": 2,)", R"("x_m": 4e9,)"), "states[1].x_m",
               "a coordinate within +-100000 m", "(got 4");
  expect_error(tweak(R"("max": [12, 8, 0.12])", R"("max": [12, -1e6, 0.12])"), "bounds.max[1]",
               "a coordinate within");
  expect_error(tweak(R"("entry": [-0.1, 4.0])", R"("entry": [-0.1, 1e300])"), "tether.entry[1]",
               "a coordinate within");
  // Times: far enough apart to overflow a duration (1e308 - -1e308 is inf) are refused.
  expect_error("t,x,y,z,yaw\n-1e308,0,0,0,0\n1e308,1,0,0,0\n", "line 2 column 1 (t)",
               "a time within +-1e12 s");
  expect_error(tweak(R"("t_s": 1,)", R"("t_s": 1e13,)"), "states[1].t_s", "a time within");
  EXPECT_EQ(parse_plan("t,x,y,z,yaw\n1.7e9,0,0,0,0\n", "p.csv").states[0].t_s, 1.7e9);  // Unix time
  // On the bound is still a plan.
  EXPECT_EQ(parse_plan("t,x,y,z,yaw\n0,-100000,100000,0,0\n", "p.csv").states[0].y_m, 1e5);
}

TEST(PlanFileBadInput, JsonUnknownKeysAtEveryLevel) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {tweak(R"("frame": "world",)", R"("frame": "world", "colour": 1,)"), "colour"},
      {tweak(R"("seed": 3,)", R"("seed": 3, "sede": 4,)"), "planner.sede"},
      {tweak(R"("max": [12, 8, 0.12])", R"("max": [12, 8, 0.12], "mid": [1, 1, 1])"), "bounds.mid"},
      {tweak(R"("max_velocity_mps": 2.0,)", R"("max_velocity_mps": 2.0, "max_speed": 1,)"),
       "limits.max_speed"},
      {tweak(R"("entry_offset_m": 1.0,)", R"("entry_offset_m": 1.0, "offset": 1,)"),
       "tether.offset"},
      {tweak(R"("side": -1})", R"("side": -1, "s": 1})"), "tether.initial_wraps[0].s"},
      {tweak(R"("yaw_rad": 0, "tether)", R"("yaw_rad": 0, "yaw": 0, "tether)"), "states[1].yaw"},
  };
  for (const auto& [text, field] : cases) {
    SCOPED_TRACE(field);
    expect_error(text, field, "one of the keys", "an unknown key");
  }
  // The known keys are listed.
  EXPECT_THAT(error_of(cases[1].first).expected(), HasSubstr("name, planning_time_s, seed, world"));
  // A JSON of another tool's states: the same per-state schema, only "states" on top.
  expect_error(R"({"states": [{"t_s": 0, "x_m": 0, "y_m": 0, "z_m": 0, "yaw_rad": 0, "v": 1}]})",
               "states[0].v", "one of the keys t_s, x_m, y_m, z_m, yaw_rad, tether_length_m");
  expect_error(R"({"comment": 1, "states": []})", "comment", "a string");
  expect_error(
      R"({"name": "a", "states": [{"t_s": 0, "x_m": 0, "y_m": 0, "z_m": 0, "yaw_rad": 0}]})",
      "name", "one of the keys comment, states");
}

TEST(PlanFileBadInput, JsonDuplicateKeysAtEveryLevel) {
  expect_error(tweak(R"("robot": "ugv",)", R"("robot": "ugv", "robot": "uav",)"), "robot",
               "each key once", "duplicate");
  expect_error(tweak(R"("x_m": 2,)", R"("x_m": 2, "x_m": 3,)"), "states[1].x_m", "each key once");
  expect_error(tweak(R"("side": -1})", R"("side": -1, "side": 1})"), "tether.initial_wraps[0].side",
               "each key once");
  expect_error(tweak(R"("min": [0, 0, 0],)", R"("min": [0, 0, 0], "min": [1, 1, 1],)"),
               "bounds.min", "each key once");
}

TEST(PlanFileBadInput, JsonWrongTypesNameTheField) {
  expect_error(tweak(R"("version": 1)", R"("version": "1")"), "version", "a finite number");
  expect_error(tweak(R"("robot": "ugv")", R"("robot": 1)"), "robot", "a string");
  expect_error(tweak(R"("frame": "world")", R"("frame": ["world"])"), "frame", "a string");
  expect_error(tweak(R"("name": "TetheredRRT")", R"("name": 7)"), "planner.name", "a string");
  expect_error(tweak(R"("seed": 3)", R"("seed": -3)"), "planner.seed", "an unsigned integer");
  expect_error(tweak(R"("seed": 3)", R"("seed": 3.5)"), "planner.seed", "an unsigned integer");
  expect_error(tweak(R"({"name": "TetheredRRT", "seed": 3, "world": "w.yaml"})", "5"), "planner",
               "an object");
  expect_error(tweak(R"("max_velocity_mps": 2.0)", R"("max_velocity_mps": "fast")"),
               "limits.max_velocity_mps", "a finite number");
  expect_error(tweak(R"("max_velocity_mps": 2.0)", R"("max_velocity_mps": 0)"),
               "limits.max_velocity_mps", "a number > 0");
  expect_error(tweak(R"("min": [0, 0, 0])", R"("min": [0, "0", 0])"), "bounds.min[1]",
               "a finite number");
  expect_error(tweak(R"("bounds": {"min": [0, 0, 0], "max": [12, 8, 0.12]})", R"("bounds": [0])"),
               "bounds", "an object");
  expect_error(tweak(R"([{"p": [3.0, 5.5], "side": -1}])", "1"), "tether.initial_wraps", "a list");
  expect_error(tweak(R"("t_s": 1,)", R"("t_s": true,)"), "states[1].t_s", "a finite number");
  expect_error(tweak(R"({"t_s": 0, "x_m": 1, "y_m": 2, "z_m": 0, "yaw_rad": 0},)", "7,"),
               "states[0]", "an object");
  expect_error(R"({"format": "ferret-plan", "version": 1, "robot": "uav", "states": {}})", "states",
               "a non-empty list");
}

TEST(PlanFileBadInput, JsonNumbersBeyondDoubleAreNamed) {
  // nlohmann refuses 1e400 (out_of_range): one line naming the field and the number.
  expect_error(tweak(R"("x_m": 2,)", R"("x_m": 1e400,)"), "states[1].x_m", "a finite number",
               "got 1e400");
  expect_error(
      tweak(R"("y_m": 2, "z_m": 0, "yaw_rad": 0},)", R"("y_m": -1e400, "z_m": 0, "yaw_rad": 0},)"),
      "states[0].y_m", "a finite number", "got -1e400");
  expect_error(tweak(R"("max": [12, 8, 0.12])", R"("max": [12, 1e400, 0.12])"), "bounds.max[1]",
               "a finite number", "1e400");
  expect_error(tweak(R"("total_length_m": 13.5)", R"("total_length_m": 1E+999)"),
               "tether.total_length_m", "a finite number", "1E+999");
  // Not JSON at all: NaN and Infinity literals are syntax errors, with line and column.
  const InputError nan = error_of(tweak(R"("x_m": 2,)", R"("x_m": NaN,)"));
  EXPECT_THAT(nan.field(), HasSubstr("line 9 column "));
  EXPECT_EQ(nan.expected(), "valid JSON");
}

TEST(PlanFileBadInput, JsonNestingIsBoundedBeforeParsing) {
  // 100000 levels overflowed nlohmann's recursion; the depth is checked first.
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  expect_error(deep, "line 1", "at most 64 levels", "deeper nesting");
  expect_error(R"({"states": )" + std::string(100000, '[') + "0" + std::string(100000, ']') + "}",
               "line 1", "at most 64 levels");
  expect_error(std::string(100000, '{'), "line 1", "at most 64 levels");
  // Brackets inside strings are not nesting.
  const PlanFile p = parse_plan(
      tweak(R"("world": "w.yaml")", R"("world": ")" + std::string(1000, '[') + R"(")"), "p.x");
  EXPECT_EQ(p.world.size(), 1000u);
}

TEST(PlanFileBadInput, MessagesAreOnePrintableLine) {
  // A newline, a NUL and a non-ASCII byte in a header name, a key with an escaped
  // newline, a cell of 10000 characters: escaped and cut, never a second line.
  expect_error(std::string("t,x,y,z,ya\nw\n0,0,0,0,0\n"), "line 1 column 5", "a header", "'ya'");
  expect_error(std::string("t,x,y,z,y") + '\0' + "\xc3\xa9\n0,0,0,0,0\n", "line 1 column 5",
               "a header", "'y\\x00\\xc3\\xa9'");
  expect_error(tweak(R"("frame": "world",)", R"("frame": "world", "a\nb": 1,)"), "a\\x0ab",
               "one of the keys");
  const InputError e = error_of("t,x,y,z,yaw\n0," + std::string(10000, '7') + "x,0,0,0\n");
  EXPECT_EQ(e.field(), "line 2 column 2 (x)");
  EXPECT_LT(std::string(e.what()).size(), 300u) << e.what();
}

TEST(PlanFileBadInput, StatesAtMostAMillion) {
  std::string text = "t,x,y,z,yaw\n";
  for (int k = 0; k <= 1'000'000; ++k) text += "0,0,0,0,0\n";
  expect_error(text, "states", "at most 1000000 states");
}

TEST(PlanFileBadInput, CollisionChecksCountedBeforeChecking) {
  // By hand: 1 m at 0.25 m steps is 4 steps, 5 poses; 0.5 rad at 0.125 rad the same; the
  // pose the segments share is counted with each.
  const CheckResolution coarse{0.25, 0.125};
  std::vector<Waypoint> states(3);
  states[1].x_m = 1.0;
  states[2].x_m = 1.0;
  states[2].yaw_rad = 0.5;
  EXPECT_EQ(plan_check_count(states, coarse), 1u + 5u + 5u);
  // 1e4 m legs at 1/64 m: 6.4e5 steps a leg; one leg fits in 1e6 checks, two do not.
  const CheckResolution fine{1.0 / 64, 0.125};
  PlanFile far;
  far.states.resize(3);
  far.states[1].x_m = 1e4;
  try {
    check_plan_work(far, fine, "far.csv");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "far.csv");
    EXPECT_EQ(e.field(), "states");
    EXPECT_THAT(e.expected(), HasSubstr("at most 1000000 collision checks"));
    EXPECT_THAT(std::string(e.what()), HasSubstr("plan too long to check"));
  }
  far.states.pop_back();
  EXPECT_EQ(plan_check_count(far.states, fine), 1u + 640'001u);
  EXPECT_NO_THROW(check_plan_work(far, fine, "far.csv"));
}

}  // namespace
}  // namespace ferret
