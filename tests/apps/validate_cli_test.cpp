#include <gtest/gtest.h>

#include <fstream>

#include "support/cli_runner.hpp"

namespace ferret::test {
namespace {

const std::string kDetour = "examples/scenarios/tether_detour.yaml";

std::string write(const TempDir& dir, const std::string& name, const std::string& text) {
  const std::string path = dir / name;
  std::ofstream(path) << text;
  return path;
}

// A hand-made miniUGV plan in the detour scenario's cellar (entry at (-0.1, 4)).
std::string ugv_plan(const std::string& states, double total_length_m = 15.0, const std::string& extra = "") {
  return R"({"format": "ferret-plan", "version": 1, "robot": "ugv", "frame": "world",)" + extra +
         R"( "tether": {"entry": [-0.1, 4.0], "total_length_m": )" + std::to_string(total_length_m) +
         R"(, "entry_offset_m": 1.0, "initial_wraps": []}, "states": [)" + states + "]}";
}

std::string state(double t, double x, double y, double yaw) {
  return "{\"t_s\": " + std::to_string(t) + ", \"x_m\": " + std::to_string(x) + ", \"y_m\": " + std::to_string(y) +
         ", \"z_m\": 0, \"yaw_rad\": " + std::to_string(yaw) + "}";
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
  const auto r = validate(write(dir, "wall.json", ugv_plan(state(0, 2, 4, 0) + "," + state(8, 10, 4, 0))));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("invalid: state 1 at t = 0.9"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("collision"), std::string::npos) << r.out;
}

TEST(ValidateCli, ThroughUnknownSpace) {
  // Outside the cellar, beyond the opening, nothing was ever observed: unknown is
  // occupied for the miniUGV.
  TempDir dir;
  const std::string bounds = R"( "bounds": {"min": [-1, 0, 0], "max": [12, 8, 0.12]},)";
  const auto p = write(dir, "out.json", ugv_plan(state(0, 0.5, 2, 3.1416) + "," + state(1, -0.5, 2, 3.1416), 15,
                                                 bounds));
  auto r = validate(p);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("collision"), std::string::npos) << r.out;
}

TEST(ValidateCli, OverTheTetherLimit) {
  TempDir dir;
  const std::string s = state(0, 1, 6.5, 0) + "," + state(5, 10, 6.5, 0) + "," + state(6, 10, 6.5, -1.5708) + "," +
                        state(9, 10, 1.5, -1.5708);
  EXPECT_EQ(validate(write(dir, "fits.json", ugv_plan(s, 15.0))).exit_code, 0);
  const auto r = validate(write(dir, "long.json", ugv_plan(s, 13.5)));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("invalid: state 3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("tether too long: taut length 13.5"), std::string::npos) << r.out;
  // The budget from the command line overrides the plan's.
  EXPECT_EQ(validate(write(dir, "fits2.json", ugv_plan(s, 15.0)), "--tether-max 12").exit_code, 1);
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
  const std::string plan = R"({"format": "ferret-plan", "version": 1, "robot": "uav", "states": [)" +
                           std::string(R"({"t_s": 0, "x_m": -0.9, "y_m": 4, "z_m": 0.3, "yaw_rad": 0},)") +
                           R"({"t_s": 5, "x_m": 12.9, "y_m": 4, "z_m": 0.3, "yaw_rad": 0}]})";
  const auto r = validate(write(dir, "uav.json", plan));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("collision"), std::string::npos) << r.out;
}

// The shipped example plans say what docs/planning.md says they do.
TEST(ValidateCli, ExamplePlans) {
  EXPECT_EQ(run_cli("validate --world " + kDetour + " --plan examples/plans/detour_ugv.json").exit_code, 0);
  EXPECT_EQ(run_cli("validate --world examples/worlds/default.yaml --plan examples/plans/approach_uav.json").exit_code, 0);
  const auto wall = run_cli("validate --world " + kDetour + " --plan examples/plans/through_block_ugv.csv"
                            " --robot urdf/models/miniugv.urdf --entry -0.1,4");
  EXPECT_EQ(wall.exit_code, 1);
  EXPECT_NE(wall.out.find("collision"), std::string::npos) << wall.out;
  const auto fast = run_cli("validate --world examples/worlds/default.yaml --plan examples/plans/too_fast_uav.csv"
                            " --robot urdf/models/m100.urdf");
  EXPECT_EQ(fast.exit_code, 1);
  EXPECT_NE(fast.out.find("too fast"), std::string::npos) << fast.out;
  const auto tether = run_cli("validate --world " + kDetour + " --plan examples/plans/tether_too_long_ugv.json");
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
      {"notether.json", R"({"format": "ferret-plan", "version": 1, "robot": "ugv", "states": [{}]})"},
      {"field.json", ugv_plan("{\"t_s\": 0, \"x_m\": \"one\", \"y_m\": 1, \"z_m\": 0, \"yaw_rad\": 0}")},
      {"short.csv", "0,1,1,0\n"},
  };
  for (const auto& [name, text] : bad) {
    const auto r = validate(write(dir, name, text), "--robot urdf/models/miniugv.urdf --entry 0,4");
    EXPECT_EQ(r.exit_code, 2) << name << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(name), std::string::npos) << r.err;  // the message names the file
  }
  EXPECT_EQ(validate(dir / "missing.json").exit_code, 2);
}

}  // namespace
}  // namespace ferret::test
