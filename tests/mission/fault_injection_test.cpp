// Faults injected into the whole simulated mission (sim/fault_plan.hpp, docs/safety.md):
// each fault the simulation injects, on, and the documented response and end state,
// with every safety invariant held at every step (sim/invariant_monitor.hpp).

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <string>

#include "ferret/core/data_path.hpp"
#include "ferret/core/error.hpp"
#include "ferret/mission/mission_document.hpp"
#include "ferret/mission/mission_run.hpp"
#include "ferret/mission/mission_settings.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/sim/fault_schedule.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

FaultPlan plan(const std::string& yaml) {
  return fault_plan_from_yaml(YAML::Load(yaml), "test", mission_fault_states());
}

// two_sites, seed 1: the miniUGV searches kiln_void (no object), then shed_void (the object).
MissionRunResult run(const FaultPlan& faults) {
  const MissionConfig mission;
  const RobotDescription uav = load_robot_description(data_path("models/m100.urdf"), mission);
  const RobotDescription ugv = load_robot_description(data_path("models/miniugv.urdf"), mission);
  const PlanningWorld world = load_planning_world(data_path("worlds/two_sites.yaml"));
  MissionRunSettings s = mission_settings_for(uav, ugv, mission, *world.spec);
  s.faults = faults;
  return run_mission(world, uav, s, 1);
}

const MissionRunResult& clean() {
  static const MissionRunResult r = run({});
  return r;
}

// What every faulted run keeps: safe at every step (the monitor's verdict), a named end.
void expect_safe(const MissionRunResult& r) {
  EXPECT_TRUE(r.safe()) << r.invariant_violations.size() << " violations, first "
                        << (r.safe() ? "" : to_string(r.invariant_violations[0].kind));
  EXPECT_NE(r.outcome, UavMissionOutcome::kNone);
  EXPECT_NE(r.outcome, UavMissionOutcome::kAborted);
  for (const auto& d : r.deployments)
    EXPECT_NE(d.result.outcome, UgvMissionOutcome::kNone) << d.hidden_space;
}

TEST(FaultInjection, ACleanRunIsSafeAndRetrievesTheObject) {
  expect_safe(clean());
  ASSERT_EQ(clean().deployments.size(), 2u);
  EXPECT_EQ(clean().deployments[1].result.outcome, UgvMissionOutcome::kObjectRetrieved);
  EXPECT_EQ(clean().backends.at("link"), "in-process");
}

// The miniUGV's watchdog holds it while the UAV is silent; the winch holds with it. The
// search resumes when the link comes back, a minute later, and ends as it would have.
TEST(FaultInjection, ALinkOutageWhileTheMiniUgvExploresHoldsItAMinute) {
  const MissionRunResult r =
      run(plan("[{kind: link_outage, on: ugv.explore, at_s: 10, duration_s: 60}]"));
  expect_safe(r);
  EXPECT_EQ(r.backends.at("link"), "messages");  // link faults run the link's messages
  ASSERT_EQ(r.deployments.size(), 2u);
  EXPECT_EQ(r.deployments[0].result.outcome, clean().deployments[0].result.outcome);
  EXPECT_GE(r.deployments[0].result.time_s, clean().deployments[0].result.time_s + 55.0);
  EXPECT_EQ(r.deployments[1].result.outcome, UgvMissionOutcome::kObjectRetrieved);
}

// The flight budget learns the drain, calls the UAV home before the pattern is done, and
// lands it with its reserve kept (at the nominal drain's budget it landed with 6.7 %).
TEST(FaultInjection, AUavBatteryDrainingFourTimesAsFastEndsTheSearchEarly) {
  const MissionRunResult r =
      run(plan("[{kind: battery_drain, target: uav, at_s: 0, permanent: true, strength: 4}]"));
  expect_safe(r);
  EXPECT_EQ(r.outcome, UavMissionOutcome::kFlightBudget);
  EXPECT_LT(r.time_s, clean().time_s);
  EXPECT_GE(r.battery_left, UavMissionOptions{}.battery_reserve_fraction);
}

// The miniUGV's battery check sends it back to the entry; the UAV lifts it out.
TEST(FaultInjection, AMiniUgvBatterySagSendsItBackToTheEntry) {
  const MissionRunResult r =
      run(plan("[{kind: battery_sag, target: ugv, on: ugv.explore, at_s: 5, strength: 0.9}]"));
  expect_safe(r);
  ASSERT_GE(r.deployments.size(), 1u);
  EXPECT_EQ(r.deployments[0].result.outcome, UgvMissionOutcome::kBatteryLow);
  EXPECT_LT(r.deployments[0].result.battery_left, 0.1);
  EXPECT_GT(r.deployments[0].result.battery_left, 0.0);
}

// No marker frames: nothing found, the pattern flown, home.
TEST(FaultInjection, AMarkerCameraBlackoutFindsNothingAndFliesHome) {
  const MissionRunResult r =
      run(plan("[{kind: camera_blackout, target: marker_camera, at_s: 0, permanent: true}]"));
  expect_safe(r);
  EXPECT_TRUE(r.visits.empty());
  EXPECT_TRUE(r.deployments.empty());
  EXPECT_EQ(r.outcome, UavMissionOutcome::kSearchComplete);
}

// No depth frames: no landing zone can be judged, the survey times out and the UAV
// lowers the miniUGV from a hover instead (the mission's no_landing_zone: hover).
TEST(FaultInjection, ADepthCameraBlackoutHoversInsteadOfLanding) {
  const MissionRunResult r =
      run(plan("[{kind: camera_blackout, target: depth_camera, at_s: 0, permanent: true}]"));
  expect_safe(r);
  ASSERT_EQ(r.visits.size(), 2u);
  for (const auto& v : r.visits) EXPECT_FALSE(v.landed) << v.marker_id;
  EXPECT_EQ(r.deployments[1].result.outcome, UgvMissionOutcome::kObjectRetrieved);
}

TEST(FaultInjection, AMissionYamlsFaultsAreReadOnceWithTheirStates) {
  const MissionDocument d = mission_document_from_yaml(
      YAML::Load("faults:\n  - {kind: link_outage, on: ugv.link_hold, at_s: 2, duration_s: 5}\n"
                 "  - {kind: battery_sag, target: uav, on: uav.ugv_ops, at_s: 1, strength: 0.3}\n"),
      "m.yaml");
  ASSERT_EQ(d.faults.faults.size(), 2u);
  EXPECT_EQ(d.faults.faults[0].start.state, "link_hold");
  EXPECT_EQ(d.faults.faults[1].start.robot, FaultRobot::kUav);
  EXPECT_DOUBLE_EQ(d.faults.faults[1].strength, 0.3);
}

TEST(FaultInjection, AFaultTheSimulationDoesNotInjectIsRefusedByName) {
  try {
    (void)mission_document_from_yaml(
        YAML::Load("faults:\n  - {kind: link_loss, at_s: 0, duration_s: 5, strength: 0.2}\n"
                   "  - {kind: winch_stall, at_s: 10, duration_s: 5}\n"),
        "m.yaml");
    FAIL() << "accepted a fault nothing injects";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("m.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("faults[1]"), std::string::npos) << what;
    EXPECT_NE(what.find("winch_stall"), std::string::npos) << what;
    EXPECT_NE(what.find("camera_blackout (marker_camera, depth_camera)"), std::string::npos)
        << what;
  }
  EXPECT_THROW(
      (void)mission_document_from_yaml(
          YAML::Load("faults:\n  - {kind: link_outage, on: ugv.nap, at_s: 0}\n"), "m.yaml"),
      InputError);
}

TEST(FaultInjection, TheInjectedKindsAreTheOnesTheSimulationApplies) {
  Fault f;
  f.kind = FaultKind::kCameraBlackout;
  f.target = FaultTarget::kObjectCamera;
  EXPECT_FALSE(simulation_injects(f));  // the miniUGV's camera: not yet
  f.target = FaultTarget::kMarkerCamera;
  EXPECT_TRUE(simulation_injects(f));
  EXPECT_TRUE(breaks_link(plan("[{kind: link_duplicate, at_s: 0, strength: 0.1}]")));
  EXPECT_FALSE(breaks_link(plan("[{kind: battery_sag, target: uav, at_s: 0, strength: 0.1}]")));
}

// The invariant's bound for each state is the controller's own timeout for it.
TEST(FaultInjection, EachStatesTimeoutIsTheOneItsControllerActsOn) {
  UavMissionOptions uav;
  uav.survey_timeout_s = 42.0;
  EXPECT_EQ(uav.state_timeout_s(UavMissionState::kSurvey), 42.0);
  EXPECT_EQ(uav.state_timeout_s(UavMissionState::kLiftoff), uav.takeoff_timeout_s);
  EXPECT_EQ(uav.state_timeout_s(UavMissionState::kLandHome), uav.land_timeout_s);
  EXPECT_EQ(uav.state_timeout_s(UavMissionState::kDrop), uav.drop_time_s);
  EXPECT_FALSE(uav.state_timeout_s(UavMissionState::kSearch));  // the flight budget's
  UgvMissionOptions ugv;
  ugv.grasp_timeout_s = 7.0;
  EXPECT_EQ(ugv.state_timeout_s(UgvMissionState::kGrasp), 7.0);
  EXPECT_EQ(ugv.state_timeout_s(UgvMissionState::kAwaitRetract), ugv.retract_timeout_s);
  EXPECT_FALSE(ugv.state_timeout_s(UgvMissionState::kReturn));  // set from its path
}

}  // namespace
}  // namespace ferret
