// The miniUGV's end of the robot link against the UAV's (LinkedUgv), the datagrams
// carried between their sessions: the UAV's calls reach the mission in order, the
// telemetry answers them, a frame from before a search is not that search's answer, and
// the watchdog stops a robot whose UAV went silent.
#include "ferret/ugv/ugv_link_endpoint.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ferret/core/clock.hpp"
#include "ferret/core/transition_log.hpp"
#include "ferret/link/codec.hpp"
#include "ferret/mission/mission_assembly.hpp"
#include "ferret/sim/ugv_mission_run.hpp"
#include "ferret/tether_model/taut_control_options.hpp"
#include "ferret/uav/linked_ugv.hpp"
#include "ferret/ugv/mini_ugv_mission.hpp"
#include "support/test_maps.hpp"

namespace ferret {
namespace {

const Pose2 kEntry{0.5, 1.0, 0.0};

UgvMissionRunSettings settings() {
  UgvMissionRunSettings s;
  s.exploration.method = "cdos";
  s.ugv.explore_timeout_s = 200.0;
  return s;
}

// Both ends and a perfect network between them, stepped at the control rate.
struct Linked {
  SimClock clock;
  TransitionLog log;
  OccupancyMap2D map = test::small_hidden_space();
  UgvMissionSim sim{map,        kEntry, Eigen::Vector2d(3.2, 0.8),
                    settings(), 5,      MissionAssembly::ugv_controllers(settings(), clock, &log)};
  int searches_asked = 0;
  UgvLinkEndpoint ugv{clock, [this](const link::UavRequest& r) {
                        ++searches_asked;
                        last_entry = {r.entry_x_m, r.entry_y_m};
                        return UgvLinkEndpoint::Deployment{&ugv_mission_of(sim), &sim.base()};
                      }};
  LinkedUgv uav{clock};
  Eigen::Vector2d last_entry = Eigen::Vector2d::Zero();
  int steps = 0;

  // One control period: the UAV's datagrams to the miniUGV, its step, its answer back.
  void step(bool uav_speaks = true, bool uav_hears = true) {
    clock.set(0.05 * ++steps);
    if (uav_speaks)
      for (const auto& d : uav.session().take_outgoing()) ugv.session().receive(d);
    const bool hold = ugv.handle_requests();
    sim.step(0.05, hold);
    ugv.report();
    for (const auto& d : ugv.session().take_outgoing())
      if (uav_hears) uav.session().receive(d);
  }
};

TEST(UgvLinkEndpoint, TheUavsCallsReachTheMissionAndTheTelemetryAnswersThem) {
  Linked k;
  k.step();
  // Heard, idle: the UAV knows nothing is under way.
  UgvReport r = k.uav.report();
  EXPECT_TRUE(r.link_ok);
  EXPECT_FALSE(r.running);
  EXPECT_FALSE(r.done);
  k.uav.deploy({0.5, 1.0, 0.0}, 0.0);
  // The request is on its way: not running yet, at the entry the UAV gave.
  r = k.uav.report();
  EXPECT_FALSE(r.running);
  EXPECT_EQ(r.p_WG, Eigen::Vector2d(0.5, 1.0));
  k.step();
  EXPECT_EQ(k.searches_asked, 1);
  EXPECT_EQ(k.last_entry, Eigen::Vector2d(0.5, 1.0));
  EXPECT_EQ(ugv_mission_of(k.sim).state(), UgvMissionState::kExplore);
  EXPECT_EQ(k.ugv.last_request_id(), 1u);
  for (int i = 0; i < 40; ++i) k.step();
  r = k.uav.report();
  EXPECT_TRUE(r.running);
  // The pose the UAV reads is the robot's own estimate, to float32 where the wire has it.
  const Pose2 p = k.sim.base().odometry();
  EXPECT_NEAR(r.p_WG.x(), p.x_m, 1e-9);
  EXPECT_NEAR(r.p_WG.y(), p.y_m, 1e-9);
  EXPECT_NEAR(r.v_WG.norm(), std::abs(k.sim.base().speed_mps()), 1e-6);
  EXPECT_NEAR(r.battery_fraction, k.sim.base().status().battery_fraction, 1e-6);
  // Recalled: it turns for home and says why once it is there.
  k.uav.recall("the UAV's flight budget");
  k.step();
  EXPECT_EQ(ugv_mission_of(k.sim).return_outcome(), UgvMissionOutcome::kRecalled);
  // Aborted: the mission ends, and the UAV reads the outcome's name.
  k.uav.abort("test");
  k.step();
  EXPECT_TRUE(ugv_mission_of(k.sim).done());
  k.step();
  r = k.uav.report();
  EXPECT_TRUE(r.done);
  EXPECT_EQ(r.outcome, "aborted");
  // Lifted out: no mission any more; the magnet is still the robot's.
  k.sim.base().set_epm(true);
  k.uav.retracted();
  k.step();
  EXPECT_EQ(k.ugv.mission(), nullptr);
  k.uav.release_object();
  k.step();
  EXPECT_FALSE(k.sim.base().status().epm_on);
  EXPECT_EQ(k.ugv.requests_without_mission(), 0u);
  EXPECT_EQ(k.ugv.last_request_id(), 5u);
}

TEST(UgvLinkEndpoint, ADoneFromTheLastSearchIsNotTheNextSearchsEnd) {
  SimClock clock;
  LinkedUgv uav(clock);
  // The miniUGV's last word from the previous hidden space, still on its way: done,
  // object retrieved, acting on request 1.
  link::UgvTelemetry old;
  old.mode = link::UgvMode::kDone;
  old.outcome = link::UgvOutcome::kObjectRetrieved;
  old.last_request_id = 1;
  uav.deploy({1.0, 2.0, 0.0}, 0.0);  // request 1
  uav.deploy({5.0, 6.0, 0.0}, 0.0);  // request 2: the next hidden space
  uav.session().receive(link::encode(7, old));
  UgvReport r = uav.report();
  EXPECT_FALSE(r.done) << "a frame about request 1 ended the search of request 2";
  EXPECT_FALSE(r.running);
  EXPECT_EQ(r.p_WG, Eigen::Vector2d(5.0, 6.0));
  // Its answer to request 2: searching.
  link::UgvTelemetry now = old;
  now.mode = link::UgvMode::kExplore;
  now.outcome = link::UgvOutcome::kNone;
  now.last_request_id = 2;
  now.x_m = 5.5;
  uav.session().receive(link::encode(8, now));
  r = uav.report();
  EXPECT_TRUE(r.running);
  EXPECT_FALSE(r.done);
  EXPECT_EQ(r.p_WG.x(), 5.5);
  EXPECT_EQ(uav.awaited_request(), 2u);
}

TEST(UgvLinkEndpoint, ASilentUavStopsTheRobotWithinTwoControlPeriods) {
  Linked k;
  k.uav.deploy({0.5, 1.0, 0.0}, 0.0);
  for (int i = 0; i < 60; ++i) k.step();  // 3 s of search, the UAV heard all along
  ASSERT_FALSE(k.ugv.holding());
  ASSERT_EQ(ugv_mission_of(k.sim).state(), UgvMissionState::kExplore);
  // The UAV goes silent: within two control periods of the link's timeout (0.5 s after
  // the last frame heard) the robot holds, its wheels commanded to 0.
  const double last_heard = k.clock.now_s() - k.ugv.session().watchdog().since_heard_s();
  double held_at = -1.0;
  for (int i = 0; i < 40 && held_at < 0; ++i) {
    k.step(/*uav_speaks=*/false);
    if (k.ugv.holding()) held_at = k.clock.now_s();
  }
  ASSERT_GE(held_at, 0.0);
  EXPECT_LE(held_at - last_heard, 0.5 + 2 * 0.05 + 1e-9);
  EXPECT_GE(held_at - last_heard, 0.5 - 1e-9);  // not before the timeout
  for (int i = 0; i < 10; ++i) k.step(false);
  EXPECT_NEAR(k.sim.base().speed_mps(), 0.0, 1e-9);
  const Pose2 stood = k.sim.base().true_pose();
  k.step(false);
  EXPECT_EQ(k.sim.base().true_pose().position(), stood.position());
  EXPECT_EQ(k.ugv.holds(), 1u);
  // Heard again: it goes on.
  for (int i = 0; i < 20; ++i) k.step();
  EXPECT_FALSE(k.ugv.holding());
  EXPECT_EQ(ugv_mission_of(k.sim).state(), UgvMissionState::kExplore);
}

TEST(UgvLinkEndpoint, TheLinesSpeedFollowsWhatTheWinchHeardAndHowLongAgo) {
  UgvLinkEndpointOptions o;
  // The winch follows for the UAV's telemetry timeout, 0.3 s; the robot brakes at
  // 2 m/s^2; the line catch is 0.05 m/s here.
  ASSERT_EQ(o.winch_follow_s, link::UavLinkOptions{}.telemetry_timeout_s);
  ASSERT_EQ(o.winch_follow_s, 0.3);
  const double catch_mps = 0.05;
  const auto limit = [&](double age_s, double known_mps) {
    return winch_view_line_speed_mps(o, age_s, known_mps, catch_mps);
  };
  // Fresh: the known 0.25 m/s (braking could still allow 2 * 0.25 = 0.5) and the catch.
  EXPECT_NEAR(limit(0.05, 0.25), 0.30, 1e-12);
  EXPECT_NEAR(limit(0.0, 0.25), 0.30, 1e-12);
  // Older: braking to be within the catch by 0.3 s: 2 * (0.3 - 0.2) = 0.2 < 0.25.
  EXPECT_NEAR(limit(0.2, 0.25), 0.25, 1e-12);
  EXPECT_NEAR(limit(0.29, 0.25), 0.07, 1e-12);
  // Stale (the winch may hold), never heard, or shortening the line: the catch alone.
  EXPECT_NEAR(limit(0.3, 0.25), catch_mps, 1e-12);
  EXPECT_NEAR(limit(5.0, 0.25), catch_mps, 1e-12);
  EXPECT_NEAR(limit(std::numeric_limits<double>::infinity(), 0.25), catch_mps, 1e-12);
  EXPECT_NEAR(limit(0.05, -0.2), catch_mps, 1e-12);
  o.winch_view_limit = false;
  EXPECT_EQ(limit(5.0, 0.0), std::numeric_limits<double>::infinity());
}

TEST(UgvLinkEndpoint, ARobotTheWinchNoLongerHearsGrowsTheLineNoFasterThanTheCatch) {
  Linked k;
  EXPECT_EQ(k.ugv.winch_view_age_s(), std::numeric_limits<double>::infinity());
  EXPECT_EQ(k.ugv.winch_known_line_speed_mps(), 0.0);
  k.uav.deploy({0.5, 1.0, 0.0}, 0.0);
  for (int i = 0; i < 60; ++i) k.step();  // 3 s of search over a perfect link
  const MiniUgvMission& m = ugv_mission_of(k.sim);
  ASSERT_EQ(m.state(), UgvMissionState::kExplore);
  // The echo comes back a control period after the telemetry went out.
  EXPECT_LE(k.ugv.winch_view_age_s(), 0.05 + 1e-9);
  tether::LineCatchLimit line_catch = tether::LineCatchLimit::for_winch({});
  line_catch.pull_budget_n *= 0.5;  // the half the link leaves to the catch
  // The UAV stops hearing the robot, and keeps telling it so: once 0.3 s have passed
  // since the telemetry it heard last, the line grows no faster than the catch.
  Eigen::Vector2d anchor = m.entry_W();
  double line_m = (k.sim.base().odometry().position() - anchor).norm();
  int driving = 0;
  for (int i = 0; i < 60; ++i) {
    k.step(/*uav_speaks=*/true, /*uav_hears=*/false);
    if (const auto a = m.explore_controller().tether_anchor()) anchor = a->first;
    const double now_m = (k.sim.base().odometry().position() - anchor).norm();
    if (k.ugv.winch_view_age_s() > 0.3 + 0.05 + 1e-9) {
      const double catch_mps = line_catch.speed_mps(m.line_length_m());
      EXPECT_NEAR(k.ugv.winch_view_line_speed_mps(), catch_mps, 1e-9);
      EXPECT_LE((now_m - line_m) / 0.05, catch_mps + 1e-6) << "at step " << i;
      if (std::abs(k.sim.base().speed_mps()) > 0.01) ++driving;
    }
    line_m = now_m;
  }
  EXPECT_GT(driving, 0) << "a robot that stands is not on its way";
  EXPECT_FALSE(k.ugv.holding());  // the UAV still speaks: not the watchdog's hold
}

TEST(UgvLinkEndpoint, ASearchAskedOfARobotWithNothingToSearchIsCounted) {
  SimClock clock;
  UgvLinkEndpoint ugv(clock, [](const link::UavRequest&) { return UgvLinkEndpoint::Deployment{}; });
  LinkedUgv uav(clock);
  uav.deploy({0.0, 0.0, 0.0}, 0.0);
  uav.recall("nothing");
  for (const auto& d : uav.session().take_outgoing()) ugv.session().receive(d);
  EXPECT_FALSE(ugv.tick());
  // One request at a time is in flight: the recall follows once the start is acknowledged.
  for (const auto& d : ugv.session().take_outgoing()) uav.session().receive(d);
  clock.set(0.2);
  for (const auto& d : uav.session().take_outgoing()) ugv.session().receive(d);
  (void)ugv.tick();
  EXPECT_EQ(ugv.requests_without_mission(), 2u);
  EXPECT_EQ(ugv.last_request_id(), 2u);
  EXPECT_EQ(ugv.mission(), nullptr);
  EXPECT_THROW(UgvLinkEndpoint(clock, nullptr), std::invalid_argument);
}

}  // namespace
}  // namespace ferret
