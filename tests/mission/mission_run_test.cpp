// The whole mission end to end in simulation (mission/mission_run.hpp): the UAV's and the
// miniUGV's controllers on the rendered world, against the world's truth.

#include "ferret/mission/mission_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "ferret/core/data_path.hpp"
#include "ferret/mission/mission_document.hpp"
#include "ferret/mission/mission_settings.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/tether_model/tension_model.hpp"
#include "ferret/uav/uav_mission_options.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A variant of the shipped second world, written where the test can load it.
fs::path world_variant(const std::string& name, const std::string& from, const std::string& to) {
  std::string text = read_text(data_path("worlds/two_sites.yaml"));
  if (!from.empty()) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  const fs::path p = fs::temp_directory_path() / ("ferret_mission_" + name + ".yaml");
  std::ofstream(p) << text;
  return p;
}

struct MissionRunOut {
  MissionRunResult result;
  PlanningWorld world;
};

MissionRunOut run(const fs::path& world_path, MissionConfig mission = {}, std::uint64_t seed = 1,
                  const std::string& no_landing_zone = "hover", const std::string& planner = "grid",
                  double flight_endurance_s = 0.0,
                  std::optional<link::LossyChannelOptions> link = std::nullopt) {
  const RobotDescription uav = load_robot_description(data_path("models/m100.urdf"), mission);
  const RobotDescription ugv = load_robot_description(data_path("models/miniugv.urdf"), mission);
  MissionRunOut r{{}, load_planning_world(world_path)};
  MissionRunSettings s = mission_settings_for(uav, ugv, mission, *r.world.spec);
  s.uav.no_landing_zone = parse_no_landing_zone(no_landing_zone, "test");
  s.ugv.ugv.explore.planner = parse_frontier_planner(planner, "test");
  if (flight_endurance_s > 0) s.uav.flight_endurance_s = flight_endurance_s;
  s.link_channel = link;
  r.result = run_mission(r.world, uav, s, seed);
  return r;
}

const HiddenSpaceVisit* visit_of(const MissionRunResult& r, int marker_id) {
  for (const auto& v : r.visits)
    if (v.marker_id == marker_id) return &v;
  return nullptr;
}

// What every run must keep, whatever happens: a named end, no collision, the tether
// never paid out beyond L, never needing more than L, never pulled over its tension
// limit (the simulation's true taut tether against the winch, every millisecond).
void expect_safe(const MissionRunResult& r, const MissionConfig& mission) {
  EXPECT_NE(r.outcome, UavMissionOutcome::kNone);
  EXPECT_NE(r.outcome, UavMissionOutcome::kAborted);
  EXPECT_EQ(r.uav_collisions, 0);
  EXPECT_LE(r.max_released_m, mission.tether.total_length_m + 1e-3);
  EXPECT_EQ(r.required_over_length, 0);
  EXPECT_EQ(r.over_tension_events, 0) << "peak " << r.max_tension_n << " N";
  for (const auto& d : r.deployments)
    EXPECT_NE(d.result.outcome, UgvMissionOutcome::kNone) << d.hidden_space;
}

// The miniUGV kept its body off the walls: at most `allowed` contacts with the truth,
// none deeper than the truth raster's half cell beyond its own (docs/mission.md, "Body
// contacts"; 97 in the shipped worlds' 20 runs before the controllers kept the body's
// disc off G's occupied cells, up to 4.6 cm deep).
void expect_body_kept_off_walls(const MissionRunResult& r, int allowed) {
  int contacts = 0;
  for (const auto& d : r.deployments) {
    contacts += d.result.body_contacts;
    EXPECT_LT(d.result.deepest_contact_m, 0.0125) << d.hidden_space;
  }
  EXPECT_LE(contacts, allowed);
}

TEST(MissionRun, FindsBothSpacesRetrievesTheObjectAndReportsTheEmptyOne) {
  const MissionRunOut run_ = run(data_path("worlds/two_sites.yaml"));
  const MissionRunResult& r = run_.result;
  expect_safe(r, {});
  // Every interface simulated, as announced before the run; the link in the process.
  EXPECT_EQ(r.backends, mission_backends());
  EXPECT_EQ(r.backends.at("uav.flight_controller"), "sim");
  EXPECT_EQ(r.backends.at("link"), "in-process");
  EXPECT_EQ(r.outcome, UavMissionOutcome::kSearchComplete);
  ASSERT_EQ(r.visits.size(), 2u);
  const HiddenSpaceVisit* shed = visit_of(r, 5);
  const HiddenSpaceVisit* kiln = visit_of(r, 9);
  ASSERT_TRUE(shed && kiln);
  // The opening from the marker is where the world has it (to a few centimetres).
  const auto& spec = *run_.world.spec;
  EXPECT_LT(Eigen::Vector2d((shed->opening.p_WE - spec.hidden_spaces[0].p_WE).head(2)).norm(), 0.3);
  EXPECT_LT(Eigen::Vector2d((kiln->opening.p_WE - spec.hidden_spaces[1].p_WE).head(2)).norm(), 0.3);
  EXPECT_EQ(shed->state, VisitState::kServiced);
  EXPECT_TRUE(shed->object_retrieved);
  EXPECT_TRUE(shed->object_dropped);
  // The miniUGV's return can stall on its way back (docs/mission.md, open defects);
  // the winch then drags it out along its tether, the object on the magnet.
  EXPECT_TRUE(shed->ugv_outcome == "object_retrieved" || shed->ugv_outcome == "return_failed")
      << shed->ugv_outcome;
  EXPECT_EQ(kiln->state, VisitState::kServiced);
  EXPECT_FALSE(kiln->object_retrieved);
  EXPECT_TRUE(kiln->ugv_outcome == "no_object" || kiln->ugv_outcome == "return_failed")
      << kiln->ugv_outcome;
  EXPECT_EQ(r.objects_dropped, 1);
  ASSERT_EQ(r.deployments.size(), 2u);
  EXPECT_GT(r.battery_left, 0.0);
  expect_body_kept_off_walls(r, 1);
}

TEST(MissionRun, TheDefaultWorldsSecondSpaceIsFoundOnTheSecondPass) {
  // The garage's opening faces south: the first pass's legs along x pass its marker
  // side-on; the legs along y find it. The house holds the object.
  const MissionRunOut run_ = run(data_path("worlds/default.yaml"));
  const MissionRunResult& r = run_.result;
  expect_safe(r, {});
  const HiddenSpaceVisit* house = visit_of(r, 11);
  const HiddenSpaceVisit* garage = visit_of(r, 23);
  ASSERT_TRUE(house && garage);
  EXPECT_LT(house->pattern_index, r.first_pass_waypoints);
  EXPECT_GE(garage->pattern_index, r.first_pass_waypoints);
  EXPECT_TRUE(house->object_dropped);
  EXPECT_EQ(garage->state, VisitState::kServiced);
  EXPECT_EQ(garage->ugv_outcome, "no_object");
  EXPECT_EQ(r.objects_dropped, 1);
  expect_body_kept_off_walls(r, 1);
}

TEST(MissionRun, TheOmplFrontierPlannerRunsTheMissionToo) {
  const MissionRunResult r = run(data_path("worlds/two_sites.yaml"), {}, 2, "hover", "ompl").result;
  expect_safe(r, {});
  EXPECT_EQ(r.visits.size(), 2u);
  EXPECT_EQ(r.objects_dropped, 1);
  for (const auto& d : r.deployments) EXPECT_GT(d.result.decisions, 0) << d.hidden_space;
}

TEST(MissionRun, NoFlightToTheDropZoneEndsAsDeliveryFailedNotAsTheFlightBudget) {
  // The small world's bounds end 1 m up: the UAV hovers over the cellar's opening and
  // the miniUGV brings the object out, but no flight with it hanging below fits under
  // that ceiling. The UAV lands at home with it, on a nearly full battery.
  const MissionRunOut run_ = run(data_path("worlds/small.yaml"));
  const MissionRunResult& r = run_.result;
  expect_safe(r, {});
  EXPECT_EQ(r.outcome, UavMissionOutcome::kDeliveryFailed) << to_string(r.outcome);
  ASSERT_EQ(r.visits.size(), 1u);
  EXPECT_TRUE(r.visits[0].object_retrieved);
  EXPECT_FALSE(r.visits[0].object_dropped);
  EXPECT_EQ(r.objects_dropped, 0);
  EXPECT_NE(r.visits[0].note.find("no flight to the drop zone"), std::string::npos)
      << r.visits[0].note;
  EXPECT_GT(r.battery_left, 0.5);  // not the budget
}

TEST(MissionRun, TheSameSeedGivesTheSameMission) {
  // OMPL is seeded once per process, so the same mission is flown by two processes.
  const fs::path w = world_variant("seed", "", "");
  const std::string cmd = std::string(FERRET_CLI) + " mission -q --seed 3 --world " + w.string();
  const auto output = [&] {
    std::string out;
    FILE* p = popen(cmd.c_str(), "r");
    char buf[4096];
    while (p && fgets(buf, sizeof buf, p)) out += buf;
    if (p) {
      EXPECT_EQ(pclose(p), 0);
    }
    return out;
  };
  const std::string a = output();
  EXPECT_NE(a.find("outcome: "), std::string::npos) << a;
  EXPECT_EQ(a, output());
}

TEST(MissionRun, NoObjectAnywhereEndsWithEverySpaceEmpty) {
  const fs::path w = world_variant("no_object",
                                   "  - {name: canister, hidden_space: shed_void, position_m: "
                                   "[1.8, 1.0], size_m: [0.08, 0.08, 0.05]}\n",
                                   "");
  const MissionRunResult r = run(w).result;
  expect_safe(r, {});
  EXPECT_EQ(r.outcome, UavMissionOutcome::kSearchComplete);
  ASSERT_EQ(r.visits.size(), 2u);
  for (const auto& v : r.visits) {
    EXPECT_TRUE(v.ugv_outcome == "no_object" || v.ugv_outcome == "return_failed") << v.ugv_outcome;
    EXPECT_FALSE(v.object_retrieved);
  }
  EXPECT_EQ(r.objects_dropped, 0);
}

TEST(MissionRun, UnsafeGroundByAnOpeningHoversOrSkips) {
  // Low debris 0.9 m out from the kiln's opening: no disc within l_0 of it is clear,
  // but a hover over it is.
  const std::string debris =
      "boxes:\n"
      "  - {name: debris_1, center_m: [-11.55, -5.0], size_m: [0.3, 0.3, 0.3]}\n"
      "  - {name: debris_2, center_m: [-11.55, -5.5], size_m: [0.3, 0.3, 0.3]}\n"
      "  - {name: debris_3, center_m: [-11.55, -6.0], size_m: [0.3, 0.3, 0.3]}\n";
  const fs::path w = world_variant("unsafe_landing", "boxes:\n", debris);
  const MissionRunResult hover = run(w).result;
  expect_safe(hover, {});
  const HiddenSpaceVisit* kiln = visit_of(hover, 9);
  ASSERT_TRUE(kiln);
  EXPECT_FALSE(kiln->landed);
  EXPECT_FALSE(kiln->landing_zone.has_value());
  EXPECT_EQ(kiln->state, VisitState::kServiced) << kiln->note;
  EXPECT_GE(kiln->deployed_s, 0.0);
  const HiddenSpaceVisit* shed = visit_of(hover, 5);
  ASSERT_TRUE(shed);
  EXPECT_TRUE(shed->object_dropped);
  // A survey hover that found nothing in 8 frames, then 16, then 32, looked on to
  // uav.survey_frames_max (64) before the next view: the kiln's three views at least.
  const auto said = [&](const std::string& words) {
    return std::count_if(hover.transitions.begin(), hover.transitions.end(),
                         [&](const Transition& t) {
                           return t.component == "uav" && t.from == "survey" &&
                                  t.reason.find(words) != std::string::npos;
                         });
  };
  EXPECT_GE(said("in 64 frames, next view"), 2);  // views 1 and 2 of 3
  EXPECT_EQ(said("(64 frames a view)"), 1);       // and the third
  EXPECT_EQ(said("in 8 frames, next view") + said("in 16 frames, next view") +
                said("in 32 frames, next view"),
            0);

  const MissionRunResult skip = run(w, {}, 1, "skip").result;
  expect_safe(skip, {});
  kiln = visit_of(skip, 9);
  ASSERT_TRUE(kiln);
  EXPECT_EQ(kiln->state, VisitState::kSkipped);
  EXPECT_LT(kiln->deployed_s, 0.0);
}

TEST(MissionRun, AHoverReleaseFromTheMissionYamlNeverLands) {
  // uav.release: hover, as a team sets it for ground it knows is unsafe: no survey, no
  // landing zone, the miniUGV lowered from a hover at both openings, the object still
  // brought out and dropped.
  const fs::path mission_yaml = fs::temp_directory_path() / "ferret_mission_hover_release.yaml";
  std::ofstream(mission_yaml) << "uav:\n  release: hover\n";
  const MissionDocument document = load_mission_document(mission_yaml);
  const MissionConfig& mission = document.config;
  const RobotDescription uav = load_robot_description(data_path("models/m100.urdf"), mission);
  const RobotDescription ugv = load_robot_description(data_path("models/miniugv.urdf"), mission);
  const PlanningWorld world = load_planning_world(data_path("worlds/two_sites.yaml"));
  MissionRunSettings s = mission_settings_for(uav, ugv, mission, *world.spec);
  document.apply_uav_mission(s.uav);
  ASSERT_EQ(s.uav.release, ReleaseMode::kHover);
  const MissionRunResult r = run_mission(world, uav, s, 1);
  expect_safe(r, mission);
  ASSERT_EQ(r.visits.size(), 2u);
  for (const HiddenSpaceVisit& v : r.visits) {
    EXPECT_EQ(v.state, VisitState::kServiced) << v.marker_id << ": " << v.note;
    EXPECT_FALSE(v.landed) << v.marker_id;
    EXPECT_FALSE(v.landing_zone.has_value()) << v.marker_id;
  }
  EXPECT_EQ(r.objects_dropped, 1);
  EXPECT_FALSE(std::any_of(r.transitions.begin(), r.transitions.end(), [](const Transition& t) {
    return t.to == "survey" && t.component == "uav";
  }));
}

TEST(MissionRun, HoveringOnALowBatteryRecallsTheMiniUgvInTime) {
  // A 220 s battery and a hover release (uav.release: hover; whether the survey finds a
  // landing zone by the kiln's opening depends on where the marker put it): the kiln
  // comes up when hovering through the miniUGV's whole search would eat the reserve.
  // The UAV calls it back while the battery covers its return, the lift and the way home.
  const RobotDescription uav = load_robot_description(data_path("models/m100.urdf"), {});
  const PlanningWorld world = load_planning_world(data_path("worlds/two_sites.yaml"));
  const RobotDescription ugv = load_robot_description(data_path("models/miniugv.urdf"), {});
  MissionRunSettings s = mission_settings_for(uav, ugv, {}, *world.spec);
  s.uav.release = ReleaseMode::kHover;
  s.uav.flight_endurance_s = 220.0;
  const MissionRunResult r = run_mission(world, uav, s, 1);
  expect_safe(r, {});
  EXPECT_EQ(r.outcome, UavMissionOutcome::kFlightBudget);
  const HiddenSpaceVisit* kiln = visit_of(r, 9);
  ASSERT_TRUE(kiln);
  EXPECT_FALSE(kiln->landed);
  EXPECT_EQ(kiln->ugv_outcome, "recalled");
  EXPECT_EQ(kiln->state, VisitState::kServiced);
  EXPECT_GE(r.battery_left, 0.10);  // home with the reserve
}

TEST(MissionRun, AnObjectBeyondTheTethersReachIsNeverReached) {
  MissionConfig short_tether;
  short_tether.tether.total_length_m = 3.0;  // 2 m on the floor; the object is 3.3 m in
  const MissionRunResult r = run(data_path("worlds/two_sites.yaml"), short_tether).result;
  expect_safe(r, short_tether);
  const HiddenSpaceVisit* shed = visit_of(r, 5);
  ASSERT_TRUE(shed);
  EXPECT_FALSE(shed->object_retrieved);
  EXPECT_TRUE(shed->ugv_outcome == "no_object" || shed->ugv_outcome == "return_failed")
      << shed->ugv_outcome;
  for (const auto& d : r.deployments) EXPECT_FALSE(d.result.object_held) << d.hidden_space;
}

// The controllers talk in the robot link's messages (wire format, sessions, watchdogs)
// through a network that loses and reorders a tenth of the datagrams each way: the
// mission ends as it does with the two in one process, and as safely.
TEST(MissionRun, OverTheLinkWithATenthLostAndReorderedTheOutcomeIsTheSame) {
  const MissionConfig mission;
  const auto direct = run(data_path("worlds/two_sites.yaml"));
  link::LossyChannelOptions lossy;
  lossy.drop_fraction = 0.1;
  lossy.reorder_fraction = 0.1;
  const auto linked =
      run(data_path("worlds/two_sites.yaml"), mission, 1, "hover", "grid", 0.0, lossy);
  const MissionRunResult& a = direct.result;
  const MissionRunResult& b = linked.result;
  expect_safe(b, mission);
  EXPECT_EQ(b.outcome, a.outcome) << to_string(b.outcome);
  EXPECT_EQ(b.objects_dropped, a.objects_dropped);
  ASSERT_EQ(b.visits.size(), a.visits.size());
  for (std::size_t k = 0; k < a.visits.size(); ++k) {
    EXPECT_EQ(b.visits[k].marker_id, a.visits[k].marker_id);
    EXPECT_EQ(b.visits[k].state, a.visits[k].state);
    EXPECT_EQ(b.visits[k].object_retrieved, a.visits[k].object_retrieved);
    EXPECT_EQ(b.visits[k].ugv_outcome, a.visits[k].ugv_outcome);
  }
  ASSERT_EQ(b.deployments.size(), a.deployments.size());
  for (std::size_t k = 0; k < a.deployments.size(); ++k)
    EXPECT_EQ(b.deployments[k].result.outcome, a.deployments[k].result.outcome)
        << a.deployments[k].hidden_space;
  EXPECT_EQ(b.backends.at("link"), "messages");
  EXPECT_EQ(a.backends.at("link"), "in-process");
  // The network did lose and reorder: the UAV's end dropped late telemetry as stale.
  const std::string uav_end = b.link_counters.substr(0, b.link_counters.find("; miniUGV end"));
  EXPECT_NE(uav_end.find("stale "), std::string::npos) << b.link_counters;
  EXPECT_EQ(uav_end.find("stale 0 "), std::string::npos) << b.link_counters;
  EXPECT_EQ(b.link_counters.find("given_up 1"), std::string::npos) << b.link_counters;
}

// Seven datagrams in ten lost each way and a fifth of the rest reordered (the worst case
// of docs/link.md's sweep, 50 over-tension events up to 48.6 N before the miniUGV kept
// its line within what the winch had heard): the tether never pulls over its limit, and
// the object still comes out.
TEST(MissionRun, OverALinkLosingSevenInTenTheTetherNeverPullsOverItsLimit) {
  const MissionConfig mission;
  link::LossyChannelOptions lossy;
  lossy.drop_fraction = 0.7;
  lossy.reorder_fraction = 0.2;
  const auto linked =
      run(data_path("worlds/two_sites.yaml"), mission, 3, "hover", "grid", 0.0, lossy);
  const MissionRunResult& r = linked.result;
  expect_safe(r, mission);
  EXPECT_LT(r.max_tension_n, tether::TensionModel{}.max_tension_n);
  EXPECT_EQ(r.outcome, UavMissionOutcome::kSearchComplete) << to_string(r.outcome);
  EXPECT_EQ(r.objects_dropped, 1);
  EXPECT_EQ(r.backends.at("link"), "messages");
}

}  // namespace
}  // namespace ferret
