#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/cli_runner.hpp"
#include "support/json_schema.hpp"

namespace ferret::test {
namespace {

const std::string kDetour = "examples/scenarios/tether_detour.yaml";

std::string write(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir / name;
  std::ofstream(path) << text;
  return path;
}

// A hand-made miniUGV plan in the detour scenario's cellar (entry at (-0.1, 4)).
std::string ugv_plan(const std::string& states, double total_length_m = 15.0,
                     const std::string& extra = "") {
  return R"({"format": "ferret-plan", "version": 1, "robot": "ugv", "frame": "world",)" + extra +
         R"( "tether": {"entry": [-0.1, 4.0], "total_length_m": )" +
         std::to_string(total_length_m) +
         R"(, "entry_offset_m": 1.0, "initial_wraps": []}, "states": [)" + states + "]}";
}

std::string state(double t, double x, double y, double yaw) {
  return "{\"t_s\": " + std::to_string(t) + ", \"x_m\": " + std::to_string(x) +
         ", \"y_m\": " + std::to_string(y) + ", \"z_m\": 0, \"yaw_rad\": " + std::to_string(yaw) +
         "}";
}

struct Outcome {
  int exit_code;
  std::string out, err;
};

Outcome validate(const std::string& plan_path, const std::string& extra = "") {
  const auto r = run_cli("validate --world " + kDetour + " --plan " + plan_path + " " + extra);
  return {r.exit_code, r.out, r.err};
}

TEST(ValidateCli, HandMadeValidPlan) {
  TempDir dir;
  const auto p = write(dir, "ok.json", ugv_plan(state(0, 1, 1, 0) + "," + state(2, 3, 1, 0)));
  const auto r = validate(p);
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
}

TEST(ValidateCli, ThroughAWall) {
  TempDir dir;
  const auto r =
      validate(write(dir, "wall.json", ugv_plan(state(0, 2, 4, 0) + "," + state(8, 10, 4, 0))));
  EXPECT_EQ(r.exit_code, 1);
  // The segment (both ends), the time and place inside it, the part and what it hits.
  EXPECT_NE(r.out.find("invalid: segment 0-1 at t = 0.9"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("collision of ugv_body with block (voxel at 3.025"), std::string::npos)
      << r.out;
}

TEST(ValidateCli, ThroughUnknownSpace) {
  // Outside the cellar, beyond the opening, nothing was ever observed: unknown is
  // occupied for the miniUGV.
  TempDir dir;
  const std::string bounds = R"( "bounds": {"min": [-1, 0, 0], "max": [12, 8, 0.12]},)";
  const auto p =
      write(dir, "out.json",
            ugv_plan(state(0, 0.5, 2, 3.1416) + "," + state(1, -0.5, 2, 3.1416), 15, bounds));
  auto r = validate(p);
  EXPECT_EQ(r.exit_code, 1);
  // At y = 2 the cellar's wall is in the way (unknown space: PlanValidation.ThroughUnknownSpace).
  EXPECT_NE(r.out.find("collision of ugv_body with cellar"), std::string::npos) << r.out;
}

TEST(ValidateCli, OverTheTetherLimit) {
  TempDir dir;
  const std::string s = state(0, 1, 6.5, 0) + "," + state(5, 10, 6.5, 0) + "," +
                        state(6, 10, 6.5, -1.5708) + "," + state(9, 10, 1.5, -1.5708);
  EXPECT_EQ(validate(write(dir, "fits.json", ugv_plan(s, 15.0))).exit_code, 0);
  const auto r = validate(write(dir, "long.json", ugv_plan(s, 13.5)));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("invalid: state 3 at t = 9.000 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("tether too long: taut length 13.5"), std::string::npos) << r.out;
  // The budget from the command line overrides the plan's (--tether-max: the old spelling).
  EXPECT_EQ(validate(write(dir, "fits2.json", ugv_plan(s, 15.0)), "--tether-budget 12").exit_code,
            1);
  EXPECT_EQ(validate(write(dir, "fits3.json", ugv_plan(s, 15.0)), "--tether-max 12").exit_code, 1);
  EXPECT_EQ(validate(write(dir, "bad.json", ugv_plan(s, 15.0)), "--tether-budget -1").exit_code, 2);
}

TEST(ValidateCli, TooFastCsvFromAnotherTool) {
  TempDir dir;
  const auto ok = write(dir, "ok.csv", "t,x,y,z,yaw\n0,1,1,0,0\n1,2,1,0,0\n");
  const auto fast = write(dir, "fast.csv", "t,x,y,z,yaw\n0,1,1,0,0\n0.25,2,1,0,0\n");
  const std::string robot = "--robot urdf/models/miniugv.urdf --entry -0.1,4";
  EXPECT_EQ(validate(ok, robot).exit_code, 0);
  const auto r = validate(fast, robot);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("too fast: 4 m/s > 2 m/s"), std::string::npos) << r.out;
  // A CSV says nothing about the robot: --robot is required.
  const auto no_robot = validate(ok);
  EXPECT_EQ(no_robot.exit_code, 2);
  EXPECT_NE(no_robot.err.find("--robot"), std::string::npos) << no_robot.err;
}

TEST(ValidateCli, PlanOfAWorldItHasNotSeen) {
  // A UAV plan across an empty yard, checked against the detour world: the cellar's
  // block is not on its way, but its straight line at 0.2 m crosses the cellar roof.
  TempDir dir;
  const std::string plan =
      R"({"format": "ferret-plan", "version": 1, "robot": "uav", "states": [)" +
      std::string(R"({"t_s": 0, "x_m": -0.9, "y_m": 4, "z_m": 0.3, "yaw_rad": 0},)") +
      R"({"t_s": 5, "x_m": 12.9, "y_m": 4, "z_m": 0.3, "yaw_rad": 0}]})";
  const auto r = validate(write(dir, "uav.json", plan));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("collision"), std::string::npos) << r.out;
}

// The shipped example plans say what docs/planning.md says they do.
TEST(ValidateCli, ExamplePlans) {
  EXPECT_EQ(
      run_cli("validate --world " + kDetour + " --plan examples/plans/detour_ugv.json").exit_code,
      0);
  // The planner times every segment rest to rest within the robot's limits, so the
  // plan also holds with the robot's own 2 m/s^2, and its segment-to-segment
  // acceleration stays within half of it (motion_check.hpp's assign_times).
  const auto accel = run_cli("validate --world " + kDetour +
                             " --plan examples/plans/detour_ugv.json --robot miniugv --json");
  EXPECT_EQ(accel.exit_code, 0) << accel.out;
  const auto doc = nlohmann::json::parse(accel.out);
  EXPECT_TRUE(doc["violations"].empty());
  EXPECT_EQ(doc["inputs"]["limits"]["max_acceleration_mps2"], 2.0);
  EXPECT_GT(doc["margins"]["peak_acceleration_mps2"].get<double>(), 0.1);
  EXPECT_LE(doc["margins"]["peak_acceleration_mps2"].get<double>(), 1.0 + 1e-9);
  EXPECT_EQ(run_cli("validate --world " + kDetour +
                    " --plan examples/plans/states_only_ugv.json --robot miniugv")
                .exit_code,
            0);
  const auto degrees = run_cli("validate --world " + kDetour +
                               " --plan examples/plans/degrees_ugv.csv --robot miniugv");
  EXPECT_EQ(degrees.exit_code, 2);
  EXPECT_NE(degrees.err.find("degrees_ugv.csv"), std::string::npos) << degrees.err;
  EXPECT_EQ(
      run_cli(
          "validate --world examples/worlds/default.yaml --plan examples/plans/approach_uav.json")
          .exit_code,
      0);
  const auto wall = run_cli("validate --world " + kDetour +
                            " --plan examples/plans/through_block_ugv.csv"
                            " --robot urdf/models/miniugv.urdf --entry -0.1,4");
  EXPECT_EQ(wall.exit_code, 1);
  EXPECT_NE(wall.out.find("collision"), std::string::npos) << wall.out;
  const auto fast = run_cli(
      "validate --world examples/worlds/default.yaml --plan examples/plans/too_fast_uav.csv"
      " --robot urdf/models/m100.urdf");
  EXPECT_EQ(fast.exit_code, 1);
  EXPECT_NE(fast.out.find("too fast"), std::string::npos) << fast.out;
  const auto tether =
      run_cli("validate --world " + kDetour + " --plan examples/plans/tether_too_long_ugv.json");
  EXPECT_EQ(tether.exit_code, 1);
  EXPECT_NE(tether.out.find("tether too long"), std::string::npos) << tether.out;
}

TEST(ValidateCli, BadPlanFilesExitTwo) {
  TempDir dir;
  const std::vector<std::pair<std::string, std::string>> bad{
      {"empty.json", ""},
      {"syntax.json", "{\"format\": \"ferret-plan\","},
      {"format.json", "{\"format\": \"gpx\"}"},
      {"robot.json", R"({"format": "ferret-plan", "version": 1, "robot": "tank", "states": []})"},
      {"nostates.json", R"({"format": "ferret-plan", "version": 1, "robot": "uav"})"},
      {"notether.json",
       R"({"format": "ferret-plan", "version": 1, "robot": "ugv", "states": [{}]})"},
      {"field.json",
       ugv_plan("{\"t_s\": 0, \"x_m\": \"one\", \"y_m\": 1, \"z_m\": 0, \"yaw_rad\": 0}")},
      {"short.csv", "t,x,y,z,yaw\n0,1,1,0\n"},
      {"noheader.csv", "0,1,1,0,0\n"},
  };
  for (const auto& [name, text] : bad) {
    const auto r = validate(write(dir, name, text), "--robot urdf/models/miniugv.urdf --entry 0,4");
    EXPECT_EQ(r.exit_code, 2) << name << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(name), std::string::npos) << r.err;  // the message names the file
  }
  EXPECT_EQ(validate(dir / "missing.json").exit_code, 2);
}

// What the mutation campaign found, generated here: each exits 2 with one line naming
// the plan file and the field, and prints no report.
void expect_bad_plan(const Outcome& r, const std::string& file_and_field) {
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_EQ(r.err.rfind("ferret: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(file_and_field), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

TEST(ValidateCli, CsvHeaderReadByNameNotPosition) {
  // Time last: read by position this was "a collision at t = -2 s"; by name it is the
  // valid drive of HandMadeValidPlan's CSV twin.
  TempDir dir;
  const auto p = write(dir, "perm.csv", "x,y,z,yaw,t\n1,1,0,0,0\n2,1,0,0,1\n");
  const auto r = validate(p, "--robot miniugv --entry -0.1,4");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  expect_bad_plan(validate(write(dir, "ab.csv", "a,b\n1,2\n"), "--robot miniugv --entry -0.1,4"),
                  "ab.csv: line 1 column 1: expected a header");
}

TEST(ValidateCli, MalformedPlanJsonIsBadInput) {
  TempDir dir;
  const std::string ok = state(0, 1, 1, 0) + "," + state(2, 3, 1, 0);
  expect_bad_plan(
      validate(write(dir, "big.json",
                     ugv_plan(state(0, 1, 1, 0) +
                              R"(,{"t_s": 2, "x_m": 1e400, "y_m": 1, "z_m": 0, "yaw_rad": 0})"))),
      "big.json: states[1].x_m: expected a finite number (got 1e400)");
  expect_bad_plan(validate(write(dir, "dup.json", ugv_plan(ok, 15, R"( "robot": "uav",)"))),
                  "dup.json: robot: expected each key once");
  expect_bad_plan(validate(write(dir, "key.json", ugv_plan(ok, 15, R"( "bound": {},)"))),
                  "key.json: bound: expected one of the keys");
  expect_bad_plan(
      validate(write(dir, "deep.json", std::string(100000, '[') + std::string(100000, ']'))),
      "deep.json: line 1: expected JSON nested at most 64 levels deep");
}

TEST(ValidateCli, FarWaypointIsBadInputWithinSeconds) {
  // 4e9 m grew to GBs, then bad_alloc (exit 3); the coordinate bound refuses it at once.
  TempDir dir;
  expect_bad_plan(validate(write(dir, "far.csv", "t,x,y,z,yaw\n0,1,1,0,0\n1,4e9,1,0,0\n"),
                           "--robot miniugv --entry -0.1,4"),
                  "far.csv: line 3 column 2 (x): expected a coordinate within +-100000 m");
  // Within the bound but too long to check: six legs of 1e5 m at the UAV's 0.05 m step.
  std::string legs = "t,x,y,z,yaw\n";
  for (int k = 0; k <= 6; ++k)
    legs += std::to_string(k * 1000) + "," + (k % 2 ? "100000" : "0") + ",1,1,0\n";
  expect_bad_plan(validate(write(dir, "long.csv", legs), "--robot m100"),
                  "long.csv: states: expected a plan of at most 1000000 collision checks");
}

TEST(ValidateCli, ABoxTooLargeToFillIsBadInputNamingItsOrigin) {
  // 3 x 3 km and 0.2 m high with unknown space occupied: billions of voxels to fill.
  TempDir dir;
  const std::string huge = R"( "bounds": {"min": [-1500, -1500, 0], "max": [1500, 1500, 0.2]},)";
  const auto plan = write(dir, "huge.json",
                          ugv_plan(state(0, 1, 6.5, 0) + "," + state(10, 11, 6.5, 0), 15.0, huge));
  expect_bad_plan(validate(plan),
                  "huge.json: bounds: expected a box whose faces hold at most 10000000 voxels");
  expect_bad_plan(
      validate(write(dir, "ok.json", ugv_plan(state(0, 1, 6.5, 0) + "," + state(10, 11, 6.5, 0))),
               "--bounds -1500,-1500,0,1500,1500,0.2"),
      "--bounds: expected a box whose faces hold at most 10000000 voxels");
}

TEST(ValidateCli, MessagesNameThePlanNotAnOptionNeverGiven) {
  TempDir dir;
  // No robot in the plan: the plan is named; --robot is how to give one.
  const auto states = write(dir, "states.json", "{\"states\": [" + state(0, 1, 1, 0) + "]}");
  expect_bad_plan(validate(states), "states.json: robot: expected a plan that names its robot");
  // A miniUGV CSV far from every hidden space: the plan has no box.
  const auto away = write(dir, "away.csv", "t,x,y,z,yaw\n0,50,50,0,0\n1,51,50,0,0\n");
  expect_bad_plan(validate(away, "--robot miniugv"), "away.csv: bounds: expected");
  // A box, a floor, but no entry: the plan's missing tether section is named.
  expect_bad_plan(validate(away, "--robot miniugv --bounds 49,49,0,53,52,0.2 --floor-z 0"),
                  "away.csv: tether: expected a tether section");
  // The plan's own box beyond the map's key range (unknown occupied turns it into keys).
  const std::string huge = R"({"format": "ferret-plan", "version": 1, "robot": "uav",
      "unknown_policy": "occupied", "bounds": {"min": [-90000, -1, 0], "max": [90000, 9, 3]},
      "states": [)" + state(0, 1, -0.5, 0) +
                           "]}";
  // A box of no voxel: the plan's field is named, not the map.
  const std::string flat =
      ugv_plan(state(0, 1, 1, 0), 15, R"( "bounds": {"min": [1, 1, 0.01], "max": [2, 2, 0.01]},)");
  expect_bad_plan(validate(write(dir, "flat.json", flat)),
                  "flat.json: bounds: expected a box holding a voxel centre on every axis");
  expect_bad_plan(validate(write(dir, "huge.json", huge)),
                  "huge.json: bounds: expected a box within");
}

template <typename Result>
nlohmann::json json_of(const Result& r) {
  try {
    return nlohmann::json::parse(r.out);
  } catch (const nlohmann::json::exception& e) {
    ADD_FAILURE() << "not JSON: " << e.what() << "\n" << r.out << r.err;
    return nullptr;
  }
}

JsonSchema validate_schema() {
  std::ifstream in(std::string(FERRET_SOURCE_DIR) + "/docs/validate.schema.json");
  return JsonSchema(nlohmann::json::parse(in));
}

// Plans from ferret and from other tools, valid and invalid: the report always fits
// docs/validate.schema.json, and its verdict agrees with the exit code.
TEST(ValidateCli, JsonMatchesTheSchema) {
  TempDir dir;
  const JsonSchema schema = validate_schema();
  const std::string csv_robot = "--robot miniugv --entry -0.1,4";
  struct Case {
    std::string name, text, extra;
    int exit_code;
  };
  const std::vector<Case> cases{
      {"ok.json", ugv_plan(state(0, 1, 1, 0) + "," + state(2, 3, 1, 0)), "", 0},
      {"wall.json", ugv_plan(state(0, 2, 4, 0) + "," + state(8, 10, 4, 0)), "", 1},
      {"ok.csv", "t,x,y,z,yaw\n0,1,1,0,0\n1,2,1,0,0\n", csv_robot, 0},
      {"fast.csv", "# another tool\nt,x,y,z,yaw\n0,1,1,0,0\n0.25,2,1,0,0\n0.5,2,1,0,1.5707963\n",
       csv_robot, 1},
      {"states.json", "{\"states\": [" + state(0, 1, 1, 0) + "," + state(2, 3, 1, 0) + "]}",
       csv_robot, 0},
      {"states_wall.json", "{\"states\": [" + state(0, 2, 4, 0) + "," + state(8, 10, 4, 0) + "]}",
       csv_robot, 1},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const auto r = validate(write(dir, c.name, c.text), c.extra + " --json");
    EXPECT_EQ(r.exit_code, c.exit_code) << r.out << r.err;
    const auto doc = json_of(r);
    const auto errors = schema.errors(doc);
    EXPECT_TRUE(errors.empty()) << errors.front() << "\n" << r.out;
    if (!errors.empty()) continue;
    EXPECT_EQ(doc["verdict"], c.exit_code == 0 ? "valid" : "invalid");
    EXPECT_EQ(doc["violation_count"], doc["violations"].size());
    EXPECT_EQ(doc["violations"].empty(), c.exit_code == 0);
    EXPECT_EQ(doc["inputs"]["robot"], "ugv");
    EXPECT_EQ(doc["inputs"]["plan"], dir / c.name);
  }
  // The schema check itself can fail: a report without margins, a kind not listed.
  auto broken = json_of(validate(write(dir, "w2.json", cases[1].text), "--json"));
  broken.erase("margins");
  broken["violations"][0]["kind"] = "bump";
  EXPECT_EQ(schema.errors(broken).size(), 2u);
}

TEST(ValidateCli, JsonNamesWhatAndWhere) {
  TempDir dir;
  const auto r =
      validate(write(dir, "wall.json", ugv_plan(state(0, 2, 4, 0) + "," + state(8, 10, 4, 0))),
               "--robot miniugv --json");
  ASSERT_EQ(r.exit_code, 1) << r.out << r.err;
  const auto doc = json_of(r);
  ASSERT_EQ(doc["violations"].size(), 1u);
  const auto& v = doc["violations"][0];
  EXPECT_EQ(v["kind"], "collision");
  EXPECT_EQ(v["segment"]["from"], 0);
  EXPECT_EQ(v["segment"]["to"], 1);
  EXPECT_EQ(v["part"], "chassis_link");       // a link of the URDF
  EXPECT_EQ(v["obstacle"]["name"], "block");  // the world YAML's name of the box
  EXPECT_NEAR(v["obstacle"]["position_m"][0].get<double>(), 3.025, 1e-9);
  EXPECT_TRUE(v["value"].is_null());
  const auto& in = doc["inputs"];
  EXPECT_EQ(in["geofence_source"], "hidden space cellar");
  EXPECT_EQ(in["floor_source"], "hidden space cellar");
  EXPECT_EQ(in["unknown_policy"], "occupied");
  EXPECT_EQ(in["limits"]["max_velocity_mps"], 2.0);  // the miniUGV's wheels and mission
  EXPECT_EQ(doc["margins"]["min_clearance_m"], 0.0);
  EXPECT_EQ(doc["margins"]["peak_speed_mps"], 1.0);
}

TEST(ValidateCli, AllListsEveryViolation) {
  TempDir dir;
  // 1-2 through the block, 3-4 at 5 m/s, and at state 3 from 2 to 5 m/s in 0.3 s.
  const auto p =
      write(dir, "many.json",
            ugv_plan(state(0, 1, 1, 0) + "," + state(2, 2, 4, 0) + "," + state(10, 10, 4, 0) + "," +
                     state(10.5, 11, 4, 0) + "," + state(10.6, 11.5, 4, 0)));
  const auto first = validate(p);
  EXPECT_EQ(first.exit_code, 1);
  EXPECT_NE(first.out.find("invalid: segment 1-2 at t = "), std::string::npos) << first.out;
  EXPECT_NE(first.out.find("(2 more violations: --all lists them)"), std::string::npos)
      << first.out;
  const auto all = validate(p, "--all");
  EXPECT_EQ(all.exit_code, 1);
  std::vector<std::string> lines;
  std::istringstream in(all.out);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 3u) << all.out;
  EXPECT_EQ(lines[0].rfind("invalid: segment 1-2 at t = ", 0), 0u) << lines[0];
  EXPECT_NE(lines[0].find("collision of ugv_body with block"), std::string::npos) << lines[0];
  EXPECT_EQ(lines[1].rfind("invalid: segment 2-4 at t = 10.500 s", 0), 0u) << lines[1];
  EXPECT_NE(lines[1].find("acceleration too high: 10 m/s^2 > 2 m/s^2"), std::string::npos)
      << lines[1];
  EXPECT_EQ(lines[2].rfind("invalid: segment 3-4 at t = 10.500 s", 0), 0u) << lines[2];
  EXPECT_NE(lines[2].find("too fast: 5 m/s > 2 m/s"), std::string::npos) << lines[2];
}

TEST(ValidateCli, CsvFarOutsideTheWorldBreaksItsBounds) {
  // A UAV flying 15 m beyond the detour world's bounds (x <= 13): no --bounds, no
  // bounds in the plan, so the world's own bounds are the geofence.
  TempDir dir;
  const auto p = write(dir, "away.csv", "t,x,y,z,yaw\n0,1,-0.5,0.9,0\n10,28,-0.5,0.9,0\n");
  const auto r = validate(p, "--robot m100");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("invalid: state 1 at t = 10.000 s, position (28.000, -0.500, 0.900): "
                       "outside the geofence"),
            std::string::npos)
      << r.out;
  const auto doc = json_of(validate(p, "--robot m100 --json"));
  const auto errors = validate_schema().errors(doc);
  EXPECT_TRUE(errors.empty()) << errors.front();
  EXPECT_TRUE(doc["inputs"]["floor_z_m"].is_null());  // a UAV: no floor, no entry
  EXPECT_TRUE(doc["margins"]["peak_tether_m"].is_null());
  EXPECT_EQ(doc["inputs"]["geofence_source"], "world bounds");
  EXPECT_EQ(doc["inputs"]["geofence"]["max"][0], 13.0);
  // Inside the world, the same flight is valid.
  EXPECT_EQ(validate(write(dir, "near.csv", "t,x,y,z,yaw\n0,1,-0.5,0.9,0\n10,12,-0.5,0.9,0\n"),
                     "--robot m100")
                .exit_code,
            0);
}

TEST(ValidateCli, YawInDegreesIsBadInput) {
  TempDir dir;
  const auto p = write(dir, "degrees.csv", "t,x,y,z,yaw\n0,1,1,0,0\n1,1,1,0,90\n");
  const auto r = validate(p, "--robot miniugv --entry -0.1,4");
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("degrees.csv"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("states[1]"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("degrees?"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1);  // one line
}

TEST(ValidateCli, RoverIsSlowerThanTheMiniUgv) {
  // 1 m/s: within the miniUGV's 2 m/s, twice the rover's 0.5 m/s (its wheel joints).
  TempDir dir;
  const auto p = write(dir, "walk.csv", "t,x,y,z,yaw\n0,1,1,0,0\n1,2,1,0,0\n");
  EXPECT_EQ(validate(p, "--robot miniugv --entry -0.1,4").exit_code, 0);
  const auto r = validate(p, "--robot tests/data/robots/rover.urdf --entry -0.1,4 --json");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const auto doc = json_of(r);
  bool speed = false;
  for (const auto& v : doc["violations"])
    if (v["kind"] == "speed") {
      speed = true;
      EXPECT_DOUBLE_EQ(v["value"].get<double>(), 1.0);
      EXPECT_DOUBLE_EQ(v["limit"].get<double>(), 0.5);
    }
  EXPECT_TRUE(speed) << r.out;
  EXPECT_EQ(doc["inputs"]["limits"]["max_velocity_mps"], 0.5);
}

TEST(ValidateCli, StatesOnlyJsonNeedsARobot) {
  TempDir dir;
  const auto r = validate(write(dir, "states.json", "{\"states\": [" + state(0, 1, 1, 0) + "]}"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--robot"), std::string::npos) << r.err;
  const auto bad =
      validate(write(dir, "bad.json", "{\"states\": [{\"t_s\": 0}]}"), "--robot miniugv");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("states[0].x_m"), std::string::npos) << bad.err;
}

// An OctoMap of a 0.4 m pillar on a floor slab (z from -0.2 to 0). The tether, entering
// at (0, 2), wraps the pillar to 5.95 m at the plan's end (straight: at most 5.10 m).
// Bounds whose z0 lies in or under the slab must not move the floor the tether's
// obstacles are read at: the floor is found in the map.
TEST(ValidateCli, TetherFloorOfAnOctoMapWhateverTheBounds) {
  TempDir dir;
  const auto yaml = write(dir, "pillar.yaml", R"(name: pillar
resolution_m: 0.05
bounds_m: {min: [-1, -1, -0.2], max: [7, 5, 1.0]}
ground: {height_m: 0.0}
boxes:
  - {name: pillar, center_m: [3, 2], size_m: [0.4, 0.4, 0.3]}
)");
  const std::string bt = dir / "pillar.bt";
  ASSERT_EQ(run_cli("world build " + yaml + " -o " + bt).exit_code, 0);
  const auto plan =
      write(dir, "wrap.json", R"({"format": "ferret-plan", "version": 1, "robot": "ugv",
    "tether": {"entry": [0, 2], "total_length_m": 6.5, "entry_offset_m": 1.0}, "states": [
    {"t_s": 0, "x_m": 1, "y_m": 2.6, "z_m": 0, "yaw_rad": 0},
    {"t_s": 4, "x_m": 5, "y_m": 2.6, "z_m": 0, "yaw_rad": 0},
    {"t_s": 6, "x_m": 5, "y_m": 1.0, "z_m": 0, "yaw_rad": 0},
    {"t_s": 10, "x_m": 1, "y_m": 1.0, "z_m": 0, "yaw_rad": 0}]})");
  for (const std::string z0 : {"-0.2", "-0.05", "0"}) {
    SCOPED_TRACE("z0 = " + z0);
    const std::string args =
        "validate --world " + bt + " --plan " + plan + " --bounds 0,0," + z0 + ",6,4,0.12";
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
    EXPECT_NE(
        r.out.find(
            "invalid: state 3 at t = 10.000 s, position (1.000, 1.000, 0.000): tether too long: "
            "taut length 5.948 m > 5.5 m"),
        std::string::npos)
        << r.out;
    const auto doc = json_of(run_cli(args + " --json"));
    EXPECT_EQ(doc["inputs"]["floor_z_m"], 0.0);
    EXPECT_EQ(doc["inputs"]["floor_source"], "map");
    EXPECT_EQ(run_cli(args + " --tether-budget 6").exit_code, 0);
  }
  // Without bounds a UAV's geofence is the map's extent (here z <= 1 m).
  const auto uav = write(dir, "high.csv", "t,x,y,z,yaw\n0,1,1,0.5,0\n10,5,1,2,0\n");
  const auto r = run_cli("validate --world " + bt + " --plan " + uav + " --robot m100 --json");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const auto doc = json_of(r);
  EXPECT_EQ(doc["inputs"]["geofence_source"], "map extent");
  const auto errors = validate_schema().errors(doc);
  EXPECT_TRUE(errors.empty()) << errors.front();
  ASSERT_EQ(doc["violations"].size(), 1u) << r.out;
  EXPECT_EQ(doc["violations"][0]["kind"], "geofence");
  EXPECT_EQ(doc["violations"][0]["segment"]["from"], 1);
}

}  // namespace
}  // namespace ferret::test

namespace ferret::test {
namespace {

// A ground robot's own box sets the hidden space's unknown-is-occupied band (and the
// tether's obstacle band): a CSV plan with no bounds gets a geofence as tall as the
// robot, the rover's 0.12 m against the miniUGV's 0.055 m.
TEST(ValidateCli, TheGroundRobotsBoxSetsTheHiddenSpaceBand) {
  TempDir dir;
  const std::string plan =
      write(dir, "slow.csv", "t,x,y,z,yaw\n0,10,4.5,0,-1.57\n10,10,3.5,0,-1.57\n");
  auto top_m = [&](const std::string& robot) {
    const auto r = run_cli("validate --world " + kDetour + " --plan " + plan + " --robot " + robot +
                           " --json");
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    const auto doc = nlohmann::json::parse(r.out);
    EXPECT_EQ(doc["inputs"]["geofence_source"], "hidden space cellar") << r.out;
    return doc["inputs"]["geofence"]["max"][2].get<double>();
  };
  EXPECT_NEAR(top_m("tests/data/robots/rover.urdf") - top_m("miniugv"), 0.12 - 0.055, 1e-9);
}

}  // namespace
}  // namespace ferret::test
