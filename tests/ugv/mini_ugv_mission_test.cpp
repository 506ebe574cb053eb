#include "ferret/ugv/mini_ugv_mission.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>

#include "ferret/core/clock.hpp"
#include "ferret/core/error.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/mission/mission_assembly.hpp"
#include "ferret/mission/ugv_mission_run.hpp"
#include "ferret/sim/sim_ugv_base.hpp"
#include "ferret/sim/ugv_mission_run.hpp"
#include "ferret/tether_model/line_catch.hpp"
#include "ferret/tether_model/taut_tether.hpp"
#include "support/test_maps.hpp"

namespace ferret {
namespace {

const Pose2 kEntry{0.5, 1.0, 0.0};
const Eigen::Vector2d kBehindPartition{3.2, 0.8};  // out of sight from the entry

UgvMissionRunSettings settings() {
  UgvMissionRunSettings s;
  s.exploration.method = "cdos";
  s.exploration.record = true;
  s.ugv.explore_timeout_s = 200.0;
  return s;
}

bool visited(const UgvMissionRunResult& r, UgvMissionState state) {
  const std::string name(to_string(state));
  return std::any_of(r.transitions.begin(), r.transitions.end(),
                     [&](const Transition& t) { return t.to == name; });
}

double distance_to_entry(const UgvMissionRunResult& r) {
  return (r.trajectory.back().position() - kEntry.position()).norm();
}

TEST(UgvMission, AMapWindowIsCentredOnTheEntryNotTakenFromTheTruth) {
  const auto map = test::small_hidden_space();
  UgvMissionRunSettings s = settings();
  EXPECT_EQ(ugv_mission_map(map.geometry, kEntry, s).width, map.geometry.width);  // the given map
  s.map_window_m = Eigen::Vector2d(3.0, 2.0);
  const GridGeometry g = ugv_mission_map(map.geometry, kEntry, s);
  EXPECT_DOUBLE_EQ(g.resolution_m, map.geometry.resolution_m);
  EXPECT_NEAR(g.width_m(), 3.0, g.resolution_m);
  EXPECT_NEAR(g.height_m(), 2.0, g.resolution_m);
  const Eigen::Vector2d middle(g.origin_x_m + 0.5 * g.width_m(), g.origin_y_m + 0.5 * g.height_m());
  EXPECT_LT((middle - kEntry.position()).norm(), 1.5 * g.resolution_m);
  // The window does not move with the truth: a map shifted by 1 m gives the same one.
  GridGeometry shifted = map.geometry;
  shifted.origin_x_m += 1.0;
  EXPECT_DOUBLE_EQ(ugv_mission_map(shifted, kEntry, s).origin_x_m, g.origin_x_m);
  // And the mission runs in it: the object found and brought back.
  const auto r = run_ugv_mission(map, kEntry, Eigen::Vector2d(1.6, 1.0), s, 2);
  EXPECT_EQ(r.outcome, UgvMissionOutcome::kObjectRetrieved) << to_string(r.outcome);
}

TEST(UgvMission, FindsGraspsAndBringsTheObjectBackToTheEntry) {
  const auto map = test::small_hidden_space();
  const auto r = run_ugv_mission(map, kEntry, kBehindPartition, settings(), 5);
  EXPECT_EQ(r.outcome, UgvMissionOutcome::kObjectRetrieved) << to_string(r.outcome);
  EXPECT_EQ(r.final_state, UgvMissionState::kDone);
  EXPECT_TRUE(r.object_held);  // the simulator's truth agrees with the magnet's sensor
  EXPECT_TRUE(r.found_right);
  ASSERT_FALSE(r.trajectory.empty());
  EXPECT_LE(distance_to_entry(r), 0.2 + 1e-9);
  for (const auto s : {UgvMissionState::kExplore, UgvMissionState::kTrack, UgvMissionState::kTurn,
                       UgvMissionState::kGrasp, UgvMissionState::kReturn,
                       UgvMissionState::kAwaitRetract, UgvMissionState::kDone})
    EXPECT_TRUE(visited(r, s)) << to_string(s);
  // The transitions are in time order and each names its reason.
  for (std::size_t i = 1; i < r.transitions.size(); ++i) {
    EXPECT_LE(r.transitions[i - 1].t_s, r.transitions[i].t_s);
    EXPECT_EQ(r.transitions[i - 1].to, r.transitions[i].from);
    EXPECT_FALSE(r.transitions[i].reason.empty());
  }
  EXPECT_LT(r.battery_left, 1.0);
  EXPECT_GT(r.path_m, 4.0);  // round the partition and back
}

TEST(UgvMission, ServoStopsAtTheStandoffAndTheMagnetFacesTheObject) {
  const auto map = test::small_hidden_space();
  const Eigen::Vector2d object{1.8, 2.3};  // in view of the entry
  const auto r = run_ugv_mission(map, kEntry, object, settings(), 2);
  ASSERT_EQ(r.outcome, UgvMissionOutcome::kObjectRetrieved) << to_string(r.outcome);
  // The pose at the start of the grasp: d_min from the object, its back to it.
  const auto grasp = std::find_if(r.transitions.begin(), r.transitions.end(),
                                  [](const Transition& t) { return t.to == "grasp"; });
  ASSERT_NE(grasp, r.transitions.end());
  const auto k = static_cast<std::size_t>(std::lround(grasp->t_s / 0.05));
  ASSERT_LT(k, r.trajectory.size());
  const Pose2 p = r.trajectory[k];
  EXPECT_NEAR((p.position() - object).norm(), 0.3, 0.06);
  const Eigen::Vector2d to_object = object - p.position();
  const double rear_bearing =
      wrap_angle_rad(std::atan2(to_object.y(), to_object.x()) - (p.yaw_rad + std::numbers::pi));
  EXPECT_LT(std::abs(rear_bearing), 0.2);
  EXPECT_EQ(r.grasp_attempts, 1);
}

TEST(UgvMission, AnEmptyHiddenSpaceIsReportedAsSuchAndTheRobotComesBack) {
  const auto map = test::small_hidden_space();
  const auto r = run_ugv_mission(map, kEntry, std::nullopt, settings(), 3);
  EXPECT_EQ(r.outcome, UgvMissionOutcome::kNoObject) << to_string(r.outcome);
  EXPECT_FALSE(r.found_W.has_value());
  EXPECT_FALSE(visited(r, UgvMissionState::kTrack));
  EXPECT_LE(distance_to_entry(r), 0.2 + 1e-9);
}

TEST(UgvMission, AnObjectTheMagnetCannotHoldEndsAsGraspFailedAfterEveryAttempt) {
  const auto map = test::small_hidden_space();
  auto s = settings();
  s.base.object_graspable = false;
  s.ugv.grasp_attempts = 2;
  const auto r = run_ugv_mission(map, kEntry, Eigen::Vector2d{1.8, 2.3}, s, 2);
  EXPECT_EQ(r.outcome, UgvMissionOutcome::kGraspFailed) << to_string(r.outcome);
  EXPECT_EQ(r.grasp_attempts, 2);
  EXPECT_FALSE(r.object_held);
  EXPECT_LE(distance_to_entry(r), 0.2 + 1e-9);
}

TEST(UgvMission, ALowBatteryEndsTheSearchWithTheWayBackStillCovered) {
  const auto map = test::small_hidden_space();
  auto s = settings();
  // 20 s at full speed in all: less than exploring the whole space takes.
  s.base.battery_endurance_s = 20.0;
  s.ugv.battery_endurance_s = 20.0;
  s.ugv.battery_reserve_fraction = 0.25;
  const auto r = run_ugv_mission(map, kEntry, std::nullopt, s, 4);
  EXPECT_EQ(r.outcome, UgvMissionOutcome::kBatteryLow) << to_string(r.outcome);
  // It drove home on what was left (waiting there to be lifted may drain the rest: the
  // EPM holds without power).
  EXPECT_TRUE(std::any_of(r.transitions.begin(), r.transitions.end(), [](const Transition& t) {
    return t.from == "return" && t.to == "await_retract";
  }));
  EXPECT_LE(distance_to_entry(r), 0.2 + 1e-9);
}

TEST(UgvMission, NobodyLiftingItOutEndsInRetractTimeout) {
  const auto map = test::small_hidden_space();
  auto s = settings();
  s.retract_time_s = 1e9;
  s.ugv.retract_timeout_s = 5.0;
  const auto r = run_ugv_mission(map, kEntry, std::nullopt, s, 3);
  EXPECT_EQ(r.outcome, UgvMissionOutcome::kRetractTimeout) << to_string(r.outcome);
  const Transition& last = r.transitions.back();
  EXPECT_EQ(last.from, "await_retract");
  const auto await = std::find_if(r.transitions.begin(), r.transitions.end(),
                                  [](const Transition& t) { return t.to == "await_retract"; });
  ASSERT_NE(await, r.transitions.end());
  EXPECT_NEAR(last.t_s - await->t_s, 5.0, 0.1);
}

TEST(UgvMission, AReturnThatStallsAtAWallPlansAgainAndGetsHome) {
  // Found by scripts/ugv-mission-campaign: the search of the empty dense space ends
  // against the bottom wall, and the first way home starts inside the wall's clearance
  // band; without re-planning the return timed out (return_failed).
  const auto map = load_map_server(std::string(FERRET_SOURCE_DIR) + "/examples/maps/dense.yaml");
  const Pose2 entry{1.0, 4.0, 0.0};
  auto s = settings();
  s.ugv.explore_timeout_s = 600.0;
  const auto r = run_ugv_mission(map, entry, std::nullopt, s, 1);
  EXPECT_EQ(r.outcome, UgvMissionOutcome::kNoObject) << to_string(r.outcome);
  EXPECT_LE((r.trajectory.back().position() - entry.position()).norm(), 0.2 + 1e-9);
}

// The taut tether over the driven path, wrapped round the corners of the truth's walls.
double longest_true_tether(const OccupancyMap2D& truth, const UgvMissionRunResult& r,
                           const Pose2& entry) {
  TautTether t(TetherCorners::from_map(truth), entry.position());
  double longest = 0.0;
  for (const Pose2& p : r.trajectory) {
    t.move_to(p.position());
    longest = std::max(longest, t.length_m());
  }
  return longest;
}

TEST(UgvMission, AnObjectBeyondTheTethersReachIsNeverDrivenTo) {
  const auto map = test::small_hidden_space();
  auto s = settings();
  // L - l_0 = 2 m: the way round the partition to the object needs about 3.5 m.
  s.exploration.mission.tether.total_length_m = 3.0;
  s.exploration.mission.tether.entry_offset_m = 1.0;
  const auto r = run_ugv_mission(map, kEntry, kBehindPartition, s, 5);
  EXPECT_EQ(r.outcome, UgvMissionOutcome::kNoObject) << to_string(r.outcome);
  const auto explored = std::find_if(r.transitions.begin(), r.transitions.end(),
                                     [](const Transition& t) { return t.to == "return"; });
  ASSERT_NE(explored, r.transitions.end());
  EXPECT_NE(explored->reason.find("tether's reach"), std::string::npos) << explored->reason;
  EXPECT_LE(r.max_tether_m, 2.0);
  EXPECT_LE(longest_true_tether(map, r, kEntry), 2.0 + 0.1);  // G's corners vs the truth's
  EXPECT_LE(distance_to_entry(r), 0.2 + 1e-9);
  // The same object with the mission's 15 m tether is retrieved, the tether model tracking it.
  const auto free = run_ugv_mission(map, kEntry, kBehindPartition, settings(), 5);
  EXPECT_EQ(free.outcome, UgvMissionOutcome::kObjectRetrieved) << to_string(free.outcome);
  EXPECT_GT(free.max_tether_m, 2.5);
  EXPECT_NEAR(free.max_tether_m, longest_true_tether(map, free, kEntry), 0.3);
}

TEST(UgvMission, ARecallEndsTheSearchWithTheWayHomeAndIsLiftedOutAsRecalled) {
  const auto map = test::small_hidden_space();
  SimClock clock;
  TransitionLog log;
  UgvMissionSim sim(map, kEntry, kBehindPartition, settings(), 5,
                    MissionAssembly::ugv_controllers(settings(), clock, &log));
  sim.start();
  double t = 0.0;
  const auto run_until = [&](const std::function<bool()>& done, double limit_s) {
    for (; t < limit_s && !done(); t += sim.tick_s()) {
      clock.set(t);
      sim.step(sim.tick_s());
    }
  };
  run_until([] { return false; }, 3.0);  // 3 s into the search
  ASSERT_EQ(ugv_mission_of(sim).state(), UgvMissionState::kExplore);
  ugv_mission_of(sim).recall("the UAV's flight budget");
  EXPECT_EQ(ugv_mission_of(sim).state(), UgvMissionState::kReturn);
  EXPECT_EQ(ugv_mission_of(sim).return_outcome(), UgvMissionOutcome::kRecalled);
  EXPECT_NE(log.all().back().reason.find("recalled: the UAV's flight budget"), std::string::npos);
  run_until([&] { return ugv_mission_of(sim).wants_retraction(); }, 60.0);
  ASSERT_TRUE(ugv_mission_of(sim).wants_retraction());
  EXPECT_LE((sim.base().true_pose().position() - kEntry.position()).norm(), 0.2 + 1e-9);
  ugv_mission_of(sim).recall("again");  // waiting at the entry: nothing changes
  EXPECT_TRUE(ugv_mission_of(sim).wants_retraction());
  ugv_mission_of(sim).retracted();
  EXPECT_EQ(ugv_mission_of(sim).outcome(), UgvMissionOutcome::kRecalled);
}

// Each tick of a mission on its line: the base's speed, and the limit a catch puts on it
// where the line may be longer than its estimate by more than the limit's stretch.
struct LineTick {
  double speed_mps = 0.0, applied_mps = 0.0, due_mps = 0.0;
};
std::vector<LineTick> line_ticks(UgvMissionRunSettings s, const tether::LineCatchLimit& line,
                                 UgvMissionRunResult& result) {
  std::vector<LineTick> ticks;
  const double l0_m = s.exploration.mission.tether.entry_offset_m;
  const auto on_tick = [&](double, const MiniUgvMission& m, const SimUgvBase& base) {
    const ExploreController& e = m.explore_controller();
    const double line_m = l0_m + e.tether_length_m();
    const bool doubt = e.reach_length_m() - e.tether_length_m() > line.stretch_m(line_m);
    ticks.push_back({std::abs(base.speed_mps()), m.line_speed_limit_mps(),
                     doubt ? line.speed_mps(line_m) : std::numeric_limits<double>::infinity()});
  };
  result =
      run_ugv_mission(test::small_hidden_space(), kEntry, kBehindPartition, s, 5, nullptr, on_tick);
  return ticks;
}

TEST(UgvMission, OnItsLineTheRobotDrivesNoFasterThanTheWinchCanFollowACatch) {
  // The mission's limit (mission/mission_settings.cpp): 8 N of pull on a 1 mm nylon line.
  const tether::LineCatchLimit line{8.0, 1500.0, 0.065, 1.8};
  UgvMissionRunResult free_run, held_run;
  const auto free_ticks = line_ticks(settings(), line, free_run);
  ASSERT_EQ(free_run.outcome, UgvMissionOutcome::kObjectRetrieved) << to_string(free_run.outcome);
  // Without the limit the robot drives faster than a catch allows where its line may
  // be longer than its estimate.
  int over = 0;
  for (const LineTick& t : free_ticks) over += t.speed_mps > t.due_mps + 0.01;
  EXPECT_GT(over, 20);
  UgvMissionRunSettings s = settings();
  s.ugv.line_catch = line;
  const auto ticks = line_ticks(s, line, held_run);
  ASSERT_EQ(held_run.outcome, UgvMissionOutcome::kObjectRetrieved) << to_string(held_run.outcome);
  int held = 0;
  for (std::size_t k = 1; k < ticks.size(); ++k) {
    // A tick's limit is the one due on the line and doubt the tick began with (the
    // search updates its tether model after), and the base keeps to it.
    const double applied = ticks[k].applied_mps;
    EXPECT_TRUE(applied == ticks[k - 1].due_mps || applied == ticks[k].due_mps) << k;
    EXPECT_LE(ticks[k].speed_mps, applied + 1e-9) << k;
    held += std::isfinite(applied);
  }
  EXPECT_GT(held, 20);
  EXPECT_LT(held, static_cast<int>(ticks.size()));  // not where the estimate is sure
  EXPECT_GT(held_run.time_s, free_run.time_s);
}

TEST(UgvMission, SameSeedSameMission) {
  const auto map = test::small_hidden_space();
  const auto a = run_ugv_mission(map, kEntry, kBehindPartition, settings(), 9);
  const auto b = run_ugv_mission(map, kEntry, kBehindPartition, settings(), 9);
  EXPECT_EQ(a.time_s, b.time_s);
  EXPECT_EQ(a.path_m, b.path_m);
  ASSERT_EQ(a.transitions.size(), b.transitions.size());
  for (std::size_t i = 0; i < a.transitions.size(); ++i)
    EXPECT_EQ(a.transitions[i].t_s, b.transitions[i].t_s);
}

// A base that does nothing it is told: the state machine must still end every state.
class DeadBase final : public UgvBase {
 public:
  explicit DeadBase(bool sees_object) : sees_(sees_object) {}
  [[nodiscard]] std::string backend() const override { return "test"; }
  [[nodiscard]] Pose2 odometry() const override { return {1.0, 1.0, 0.0}; }
  [[nodiscard]] double speed_mps() const override { return 0.0; }
  [[nodiscard]] RangeScan ir_scan() override {
    RangeScan s;
    s.X_WS = odometry();
    s.max_range_m = 4.0;
    for (int k = -5; k <= 5; ++k) s.beams.push_back({0.05 * k, 0.5});
    return s;
  }
  [[nodiscard]] CameraFrame camera_frame(double time_s) override {
    CameraFrame f;
    f.time_s = time_s;
    f.view = ir_scan();
    if (sees_) f.detections.push_back({0.0, 0.35, 0.95});  // 0.35 m ahead: strong evidence
    return f;
  }
  void command_velocity(double, double) override {}
  void set_epm(bool on) override { epm_ = on; }
  [[nodiscard]] UgvStatus status() const override { return {0.9, epm_, false}; }

 private:
  bool sees_;
  bool epm_ = false;
};

UgvMissionOptions dead_options() {
  UgvMissionOptions o;
  o.explore_timeout_s = 3.0;
  o.track_timeout_s = 2.0;
  o.turn_timeout_s = 1.5;
  o.return_timeout_min_s = 2.5;
  return o;
}

UgvMissionRunResult drive_dead(DeadBase& base, const UgvMissionOptions& options,
                               TransitionLog& log) {
  SimClock clock;
  const GridGeometry geo{0.0, 0.0, 0.05, 60, 40};
  MiniUgvMission mission(base, clock, geo, options, &log);
  mission.start();
  for (int k = 1; k < 4000 && !mission.done(); ++k) {
    mission.tick();
    clock.set(k * mission.tick_s());
  }
  UgvMissionRunResult r;
  r.outcome = mission.outcome();
  r.final_state = mission.state();
  r.time_s = clock.now_s();
  r.transitions = log.all();
  return r;
}

TEST(UgvMissionStates, ARobotThatCannotMoveTimesOutOfTheSearchAndTheReturn) {
  DeadBase base(false);
  TransitionLog log;
  const auto r = drive_dead(base, dead_options(), log);
  EXPECT_EQ(r.final_state, UgvMissionState::kDone);
  // It is at the entry already (it never moved): explore times out or ends explored,
  // then the return finds it home.
  ASSERT_GE(r.transitions.size(), 3u);
  EXPECT_EQ(r.transitions[1].from, "explore");
  EXPECT_EQ(r.transitions[1].to, "return");
  EXPECT_EQ(r.transitions[2].to, "await_retract");
  EXPECT_EQ(r.outcome, UgvMissionOutcome::kRetractTimeout);
}

TEST(UgvMissionStates, AServoThatNeverClosesInTimesOutOfTrackAndTheTurnTimesOut) {
  DeadBase base(true);  // sees the object 0.35 m ahead forever, never gets nearer
  TransitionLog log;
  auto o = dead_options();
  o.standoff_m = 0.2;
  const auto r = drive_dead(base, o, log);
  std::vector<std::string> path;
  for (const auto& t : r.transitions) path.push_back(t.to);
  ASSERT_GE(path.size(), 3u);
  EXPECT_EQ(path[0], "explore");
  EXPECT_EQ(path[1], "track");
  EXPECT_EQ(path[2], "return");
  EXPECT_NE(r.transitions[2].reason.find("in time"), std::string::npos) << r.transitions[2].reason;
  EXPECT_NEAR(r.transitions[2].t_s - r.transitions[1].t_s, 2.0, 0.11);
  EXPECT_EQ(r.final_state, UgvMissionState::kDone);
}

// A room 3 x 2 m whose IR sees its walls but not a low kerb across it at x = 2 m (below
// the beams): the base stops the 12 cm body at the kerb, as SimUgvBase stops it at a wall.
// A sluggish base (start_delay_s) stands still for that long when told to drive from rest.
class KerbBase final : public UgvBase {
 public:
  static constexpr double kKerb_m = 2.0, kRadius_m = 0.06, kTick_s = 0.05;
  explicit KerbBase(double kerb_m = kKerb_m, double start_delay_s = 0.0)
      : kerb_m_(kerb_m), start_delay_s_(start_delay_s) {}
  [[nodiscard]] std::string backend() const override { return "test"; }
  [[nodiscard]] Pose2 odometry() const override { return pose_; }
  [[nodiscard]] double speed_mps() const override { return v_mps_; }
  [[nodiscard]] RangeScan ir_scan() override {
    RangeScan s;
    s.X_WS = pose_;
    s.max_range_m = 4.0;
    for (int k = -8; k <= 8; ++k) {  // to the room's walls, through the kerb
      const double a = pose_.yaw_rad + 0.1 * k, c = std::cos(a), sn = std::sin(a);
      double d = 4.0;
      if (c > 1e-9) d = std::min(d, (3.0 - pose_.x_m) / c);
      if (c < -1e-9) d = std::min(d, -pose_.x_m / c);
      if (sn > 1e-9) d = std::min(d, (2.0 - pose_.y_m) / sn);
      if (sn < -1e-9) d = std::min(d, -pose_.y_m / sn);
      s.beams.push_back({0.1 * k, d});
    }
    return s;
  }
  [[nodiscard]] CameraFrame camera_frame(double time_s) override {
    CameraFrame f;
    f.time_s = time_s;
    f.view = ir_scan();
    return f;
  }
  void command_velocity(double v, double w) override {
    if (v > 0.0 && v_mps_ <= 0.0 && waited_s_ < start_delay_s_ - 1e-9) {
      waited_s_ += kTick_s;  // from rest, nothing moves yet
      return;
    }
    waited_s_ = 0.0;
    const Pose2 next = integrate_unicycle(pose_, {v, w}, kTick_s);
    const bool blocked = next.x_m + kRadius_m > kerb_m_ && next.x_m > pose_.x_m;
    pose_ = blocked ? Pose2{pose_.x_m, pose_.y_m, next.yaw_rad} : next;
    v_mps_ = blocked ? 0.0 : v;
    stalled_ticks_ = blocked && v > 0.0 ? stalled_ticks_ + 1 : 0;
    longest_stall_ = std::max(longest_stall_, stalled_ticks_);
  }
  void set_epm(bool) override {}
  [[nodiscard]] UgvStatus status() const override { return {0.9, false, false}; }
  [[nodiscard]] int longest_stall_ticks() const { return longest_stall_; }

 private:
  double kerb_m_, start_delay_s_, waited_s_ = 0.0;
  Pose2 pose_{1.0, 1.0, 0.0};
  double v_mps_ = 0.0;
  int stalled_ticks_ = 0, longest_stall_ = 0;
};

TEST(UgvMissionStates, ABaseThatStandsStillWhenToldToDriveIsABumpAndTheRobotStopsPressing) {
  KerbBase base;
  SimClock clock;
  TransitionLog log;
  UgvMissionOptions o;
  o.explore.robot.body_radius_m = KerbBase::kRadius_m;
  o.explore.robot.max_velocity_mps = 0.3;
  o.explore_timeout_s = 60.0;
  const GridGeometry geo{0.0, 0.0, 0.025, 120, 80};
  MiniUgvMission mission(base, clock, geo, o, &log);
  mission.start();
  for (int k = 1; k < 3000 && !mission.done() && !mission.wants_retraction(); ++k) {
    mission.tick();
    clock.set(k * mission.tick_s());
  }
  // The room beyond the kerb is a frontier the search drives for: it meets the kerb,
  // the IR says nothing is there, and only the bump tells G.
  EXPECT_GE(mission.bumps(), 1);
  // Each stretch against the kerb ends within a few ticks of the bump (without it the
  // follower, trusting G, pressed on until the search's stuck detection: 4 s, 80 ticks).
  EXPECT_LE(base.longest_stall_ticks(), 12);
  EXPECT_LT(base.odometry().x_m + KerbBase::kRadius_m, KerbBase::kKerb_m + 1e-9);
}

TEST(UgvMissionStates, ABaseSlowerToStartThanItsStallTimeIsNotABump) {
  // The room without its kerb, and a base that starts 0.5 s after a command from rest:
  // held to the default 0.3 s every start is a bump; given 0.8 s (the mission YAML's
  // ugv.base.stall_time_s) none is. The kerb is still met with the longer time.
  struct Run {
    int bumps;
    double x_m;
  };
  const auto run = [](double kerb_m, double bump_time_s) {
    KerbBase base(kerb_m, 0.5);
    SimClock clock;
    UgvMissionOptions o;
    o.explore.robot.body_radius_m = KerbBase::kRadius_m;
    o.explore.robot.max_velocity_mps = 0.3;
    o.explore_timeout_s = 60.0;
    o.bump_time_s = bump_time_s;
    MiniUgvMission mission(base, clock, {0.0, 0.0, 0.025, 120, 80}, o, nullptr);
    mission.start();
    for (int k = 1; k < 1200 && !mission.done() && !mission.wants_retraction(); ++k) {
      mission.tick();
      clock.set(k * mission.tick_s());
    }
    return Run{mission.bumps(), base.odometry().x_m};
  };
  EXPECT_GE(run(9.0, 0.3).bumps, 1);
  EXPECT_EQ(run(9.0, 0.8).bumps, 0);
  const Run kerb = run(KerbBase::kKerb_m, 0.8);
  EXPECT_GE(kerb.bumps, 1);
  EXPECT_LT(kerb.x_m + KerbBase::kRadius_m, KerbBase::kKerb_m + 1e-9);
  UgvMissionOptions bad;
  for (const double t : {0.0, 0.01, 11.0, std::nan("")}) {
    bad.bump_time_s = t;
    try {
      bad.validate("mission.yaml");
      ADD_FAILURE() << t;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "ugv.base.stall_time_s") << t;
    }
  }
}

TEST(UgvMissionStates, StopAbortsFromAnyStateAndTicksAfterDoneDoNothing) {
  DeadBase base(false);
  SimClock clock;
  TransitionLog log;
  MiniUgvMission mission(base, clock, {0.0, 0.0, 0.05, 60, 40}, dead_options(), &log);
  mission.start();
  mission.tick();
  mission.stop("operator");
  EXPECT_EQ(mission.outcome(), UgvMissionOutcome::kAborted);
  const auto n = log.all().size();
  mission.tick();
  mission.stop("again");
  EXPECT_EQ(log.all().size(), n);
  EXPECT_NE(log.all().back().reason.find("operator"), std::string::npos);
}

TEST(UgvMissionStates, BadOptionsNameTheField) {
  UgvMissionOptions o;
  o.standoff_m = 0.1;  // no room to turn next to the object
  try {
    o.validate("mission.yaml");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "ugv.standoff_m");
  }
  o = {};
  o.track_timeout_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(o.validate("m"), InputError);
  o = {};
  o.grasp_attempts = 0;
  EXPECT_THROW(o.validate("m"), InputError);
}

}  // namespace
}  // namespace ferret
