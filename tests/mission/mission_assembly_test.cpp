// MissionAssembly (mission/mission_assembly.hpp): the UAV's options filled from the world
// and checked once, for every backend set; bad input named by its file and field.

#include "ferret/mission/mission_assembly.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/mission/mission_settings.hpp"
#include "ferret/mission/mission_setup.hpp"
#include "ferret/mission/ugv_mission_run.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/sim/mission_run.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "support/cli_runner.hpp"
#include "support/test_maps.hpp"
#include "two_sites_mission.hpp"

namespace ferret {
namespace {

using Loaded = test::TwoSitesMission;

TEST(MissionAssembly, FillsTheUavOptionsFromTheWorld) {
  const Loaded l;
  ASSERT_TRUE(l.settings.uav.openings.empty());  // the world's, not the mission YAML's
  const MissionAssembly assembly(l.world, l.uav, l.settings, 1, "m.yaml");
  const auto& openings = assembly.uav_options().openings;
  ASSERT_EQ(openings.size(), world_openings(*l.world.spec).size());
  EXPECT_EQ(openings.size(), l.world.spec->hidden_spaces.size());
  EXPECT_EQ(assembly.uav_options().tether.total_length_m,
            l.settings.ugv.exploration.mission.tether.total_length_m);
}

TEST(MissionAssembly, BadUavOptionsAreBadInputNamingTheFileAndField) {
  Loaded l;
  l.settings.uav.search_speed_mps = -1.0;
  try {
    const MissionAssembly assembly(l.world, l.uav, l.settings, 1, "m.yaml");
    FAIL() << "a negative search speed was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("m.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("uav.search_speed_mps"), std::string::npos) << e.what();
  }
}

TEST(MissionAssembly, AUavWithoutItsCamerasIsBadInput) {
  const Loaded l;
  // The miniUGV's URDF has no marker camera for the UAV's search.
  EXPECT_THROW((void)MissionAssembly(l.world, l.ugv, l.settings, 1, "m.yaml"), InputError);
}

// The miniUGV mission's keys of the mission YAML reach the controller a mission builds,
// and change what it does; without them, its options are the defaults.
TEST(MissionAssembly, TheMiniUgvKeysOfTheMissionFileReachItsController) {
  test::TempDir dir;
  const std::string path = dir / "mission.yaml";
  std::ofstream(path) << "ugv:\n  explore_timeout_s: 2\n  explore: {max_revisits: 1}\n";
  MissionSetupOptions o;
  o.world = data_path("worlds/two_sites.yaml").string();
  const MissionSetup defaults = load_mission_setup(o);
  o.mission = path;
  const MissionSetup shorter = load_mission_setup(o);
  const GridGeometry map{0.0, 0.0, 0.05, 60, 40};
  const UgvMissionOptions d = ugv_mission_options(defaults.settings.ugv, 1, std::nullopt, map);
  const UgvMissionOptions s = ugv_mission_options(shorter.settings.ugv, 1, std::nullopt, map);
  EXPECT_DOUBLE_EQ(d.explore_timeout_s, UgvMissionOptions{}.explore_timeout_s);
  EXPECT_EQ(d.explore.max_revisits, ExploreTuning{}.max_revisits);
  EXPECT_DOUBLE_EQ(s.explore_timeout_s, 2.0);
  EXPECT_EQ(s.explore.max_revisits, 1);
  // What the robots set stays: the base's stall time, the line's catch, the planner.
  EXPECT_DOUBLE_EQ(s.bump_time_s, d.bump_time_s);
  EXPECT_DOUBLE_EQ(s.line_catch.pull_budget_n, d.line_catch.pull_budget_n);
  EXPECT_EQ(s.explore.robot.max_velocity_mps, d.explore.robot.max_velocity_mps);

  // The search gives up after its 2 s, where the default searches on.
  const OccupancyMap2D truth = test::room_with_partition();
  const Pose2 entry{0.5, 1.0, 0.0};
  const auto result =
      run_ugv_mission(truth, entry, Eigen::Vector2d(3.2, 0.8), shorter.settings.ugv, 1);
  EXPECT_EQ(result.outcome, UgvMissionOutcome::kSearchTimeout);
}

// A miniUGV set down but never told to search (its start request lost on the link, the
// UAV's time for the space running out) is lifted out with a result, not a crash.
TEST(MissionAssembly, AMiniUgvNeverStartedReportsNoSearch) {
  const Loaded l;
  const OccupancyMap2D truth = test::room_with_partition();
  SimClock clock;
  UgvMissionSim sim(truth, Pose2{0.5, 1.0, 0.0}, Eigen::Vector2d(3.2, 0.8), l.settings.ugv, 1,
                    MissionAssembly::ugv_controllers(l.settings.ugv, clock, nullptr));
  sim.step(sim.tick_s());  // ticks an idle controller: nothing happens
  EXPECT_DOUBLE_EQ(sim.controller().tether_length_m(), 0.0);
  const UgvMissionRunResult r = sim.result(TransitionLog{});
  EXPECT_EQ(r.outcome, UgvMissionOutcome::kNone);
  EXPECT_EQ(r.final_state, UgvMissionState::kIdle);
  EXPECT_EQ(r.decisions, 0);
  EXPECT_EQ(r.grid, nullptr);
}

}  // namespace
}  // namespace ferret
