// The UAV's mission controller against fake hardware: its transitions and timeouts
// (the whole mission on the rendered world: tests/mission).

#include "ferret/uav/uav_mission.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "ferret/core/data_path.hpp"
#include "ferret/core/error.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

// A vehicle that flies straight at its setpoint at the commanded speed, or not at all
// (`stuck`), its battery draining at `drain_per_s`.
class FakeFlight final : public FlightController {
 public:
  bool stuck = false;
  double drain_per_s = 1.0 / 1200.0;
  [[nodiscard]] std::string backend() const override { return "fake"; }
  [[nodiscard]] FlightState state() const override { return s_; }
  void command_takeoff(double z_m) override {
    s_.on_ground = false;
    sp_ = {s_.p_W.x(), s_.p_W.y(), z_m};
    speed_ = 2.0;
    landing_ = false;
  }
  void command_position(const Eigen::Vector3d& p, double yaw, double speed) override {
    sp_ = p;
    s_.yaw_rad = yaw;
    speed_ = speed;
  }
  void command_land() override { landing_ = true; }
  void step(double dt) {
    if (s_.on_ground || stuck) return;
    if (landing_) sp_ = {s_.p_W.x(), s_.p_W.y(), 0.25};
    const Eigen::Vector3d d = sp_ - s_.p_W;
    const double step = std::min(d.norm(), std::max(speed_, 0.3) * dt);
    s_.v_W =
        d.norm() > 1e-9 ? Eigen::Vector3d(d.normalized() * step / dt) : Eigen::Vector3d::Zero();
    if (d.norm() < 1e-3) s_.v_W.setZero();
    s_.p_W += s_.v_W * dt;
    s_.battery_fraction -= drain_per_s * dt;
    if (landing_ && s_.p_W.z() <= 0.2501) s_.on_ground = true;
  }
  FlightState s_{Eigen::Vector3d(0, 0, 0.25), 0.0, Eigen::Vector3d::Zero(), true, 1.0};

 private:
  Eigen::Vector3d sp_ = Eigen::Vector3d::Zero();
  double speed_ = 0.0;
  bool landing_ = false;
};

// Frames of an empty grey field: no marker, never a safe zone.
class BlankCameras final : public UavCameras {
 public:
  BlankCameras(const CameraModel& m, const CameraModel& d) : m_(m), d_(d) {}
  CameraShot<GrayImage> marker_frame() override {
    ++frames;
    if (dropped) return {GrayImage{}, Pose3::Identity()};
    return {GrayImage(m_.width_px, m_.height_px, 128), Pose3::Identity()};
  }
  CameraShot<DepthImageMm> depth_frame() override {
    return {DepthImageMm(d_.width_px, d_.height_px, 0), Pose3::Identity()};
  }
  int frames = 0;
  bool dropped = false;  ///< every marker frame empty (none arrived)

 private:
  CameraModel m_, d_;
};

class FakeWinch final : public tether::Winch {
 public:
  void set_torque_enabled(bool) override {}
  void command_velocity_mps(double v) override { v_ = v; }
  tether::WinchState read_state() override { return {released_, v_, 0.5}; }

 private:
  double released_ = 0.0, v_ = 0.0;
};

class FakeUgv final : public UgvLink {
 public:
  void deploy(const Eigen::Vector3d&, double) override {}
  void retracted() override {}
  void release_object() override {}
  void abort(const std::string&) override {}
  void recall(const std::string&) override {}
  [[nodiscard]] UgvReport report() const override { return {}; }
};

struct Rig {
  SimClock clock;
  FakeFlight flight;
  CameraModel marker, depth;
  BlankCameras cameras;
  FakeWinch winch;
  FakeUgv ugv;
  TransitionLog log;
  int plans = 0;
  bool plans_fail = false;
  /// Every plan asked for, and the segments the planner does not pass straight.
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> calls;
  std::function<bool(const Eigen::Vector3d&, const Eigen::Vector3d&)> blocked;

  static CameraModel model(const char* name) {
    const RobotDescription m100 =
        load_robot_description(data_path("models/m100.urdf"), MissionConfig{});
    return camera_model(*m100.find_camera(name), m100.source);
  }
  Rig() : marker(model("marker_camera")), depth(model("depth_camera")), cameras(marker, depth) {}

  std::unique_ptr<UavMission> mission(UavMissionOptions o) {
    FlightPlanner planner = [this](const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   bool) -> std::optional<std::vector<Eigen::Vector3d>> {
      ++plans;
      calls.emplace_back(a, b);
      if (plans_fail) return std::nullopt;
      if (blocked && blocked(a, b))
        return std::vector<Eigen::Vector3d>{a, 0.5 * (a + b) + Eigen::Vector3d(0, 1, 0), b};
      return std::vector<Eigen::Vector3d>{a, b};
    };
    return std::make_unique<UavMission>(UavMission::Hardware{flight, cameras, winch, ugv}, clock,
                                        planner, marker, depth, std::move(o), &log);
  }
  void run(UavMission& m, double limit_s) {
    m.start();
    for (int k = 0; k < static_cast<int>(limit_s / 0.02) && !m.done(); ++k) {
      clock.advance(0.02);
      m.tick();
      flight.step(0.02);
    }
  }
  [[nodiscard]] bool went_to(const std::string& state) const {
    return std::any_of(log.all().begin(), log.all().end(),
                       [&](const Transition& t) { return t.to == state; });
  }
};

UavMissionOptions small_area() {
  UavMissionOptions o;
  o.search_area_m = {0.0, 0.0, 12.0, 8.0};
  o.leg_spacing_m = 4.0;
  return o;
}

TEST(UavMission, FliesThePatternThenLandsAtHome) {
  Rig rig;
  auto m = rig.mission(small_area());
  // Two legs along x (8 m / 4 m), three along y (12 m / 4 m): a start and end each.
  ASSERT_EQ(m->pattern().size(), 2u * (2 + 3));
  EXPECT_EQ(m->first_pass_waypoints(), 4u);
  EXPECT_DOUBLE_EQ(m->pattern()[0].y(), 2.0);  // first leg in the middle of its strip
  EXPECT_DOUBLE_EQ(m->pattern()[1].x(), 12.0);
  EXPECT_DOUBLE_EQ(m->pattern()[2].x(), 12.0);  // the next leg comes back
  EXPECT_DOUBLE_EQ(m->pattern()[3].x(), 0.0);
  rig.run(*m, 600.0);
  ASSERT_TRUE(m->done());
  EXPECT_EQ(m->outcome(), UavMissionOutcome::kSearchComplete);
  EXPECT_EQ(m->pattern_done(), m->pattern().size());
  EXPECT_TRUE(rig.flight.state().on_ground);
  EXPECT_LT(rig.flight.state().p_W.head<2>().norm(), 0.5);  // home
  EXPECT_TRUE(rig.went_to("return_home"));
  EXPECT_TRUE(m->visits().empty());
  // A frame every frame_period_s of the search.
  EXPECT_NEAR(rig.cameras.frames, m->time_in_state().at("search") / 0.5, 3.0);
}

// A camera that delivers no frame (empty images: dropped, or the simulator's frames no
// marker can be in) is looked past: the search goes on and ends as usual.
TEST(UavMission, EmptyMarkerFramesAreCountedAndLookedPast) {
  Rig rig;
  rig.cameras.dropped = true;
  auto m = rig.mission(small_area());
  rig.run(*m, 600.0);
  ASSERT_TRUE(m->done());
  EXPECT_EQ(m->outcome(), UavMissionOutcome::kSearchComplete);
  EXPECT_TRUE(m->visits().empty());
  EXPECT_GT(rig.cameras.frames, 10);
  EXPECT_EQ(m->frames_processed(), rig.cameras.frames);
}

TEST(UavMission, TheLegSpacingFollowsTheMarkerCamera) {
  Rig rig;
  UavMissionOptions o = small_area();
  o.leg_spacing_m = 0.0;
  auto m = rig.mission(o);
  // d_max = fx * 0.15 m / 16 px; legs half that times tan(hfov / 2) apart.
  const double d_max = rig.marker.fx_px * 0.15 / 16.0;
  const double expected = 0.5 * d_max * (0.5 * rig.marker.width_px / rig.marker.fx_px);
  EXPECT_NEAR(m->leg_spacing_m(), expected, 1e-9);
}

TEST(UavMission, AMarkerOfSmallerCellsIsSearchedWithCloserLegs) {
  // The decoder needs pixels a cell: tag36h11's black square holds 8 cells to a 4x4
  // marker's 6, so it is read at 3/4 of the range and the legs close up to 3/4; a
  // tag16h5 (6 cells, like 4x4) keeps the 4x4 spacing.
  Rig rig;
  UavMissionOptions o = small_area();
  o.leg_spacing_m = 0.0;
  const double aruco_4x4 = rig.mission(o)->leg_spacing_m();
  o.marker.dictionary = {MarkerFamily::kAprilTag, "tag36h11"};
  EXPECT_NEAR(rig.mission(o)->leg_spacing_m(), 0.75 * aruco_4x4, 1e-9);
  o.marker.dictionary = {MarkerFamily::kAruco, "DICT_5X5_50"};
  EXPECT_NEAR(rig.mission(o)->leg_spacing_m(), 6.0 / 7.0 * aruco_4x4, 1e-9);
  o.marker.dictionary = {MarkerFamily::kAprilTag, "tag16h5"};
  EXPECT_NEAR(rig.mission(o)->leg_spacing_m(), aruco_4x4, 1e-9);
}

TEST(UavMission, ATakeoffThatNeverClimbsTimesOut) {
  Rig rig;
  rig.flight.stuck = true;
  UavMissionOptions o = small_area();
  o.takeoff_timeout_s = 10.0;
  auto m = rig.mission(o);
  rig.run(*m, 60.0);
  ASSERT_TRUE(m->done());
  EXPECT_EQ(m->outcome(), UavMissionOutcome::kTakeoffFailed);
  EXPECT_NEAR(rig.clock.now_s(), 10.0, 0.1);
}

TEST(UavMission, TheBatteryCallsTheReturnBeforeThePatternEnds) {
  Rig rig;
  rig.flight.drain_per_s = 1.0 / 60.0;  // a minute of flight
  UavMissionOptions o = small_area();
  o.flight_endurance_s = 60.0;
  auto m = rig.mission(o);
  rig.run(*m, 600.0);
  ASSERT_TRUE(m->done());
  EXPECT_EQ(m->outcome(), UavMissionOutcome::kFlightBudget);
  EXPECT_LT(m->pattern_done(), m->pattern().size());
  EXPECT_GT(rig.flight.state().battery_fraction, 0.0);  // the reserve was kept
  const auto t = std::find_if(rig.log.all().begin(), rig.log.all().end(),
                              [](const Transition& x) { return x.to == "return_home"; });
  ASSERT_NE(t, rig.log.all().end());
  EXPECT_NE(t->reason.find("battery"), std::string::npos);
}

// The battery calls the UAV home in the middle of a leg, at search speed: the way home
// is planned from where it stops, after a check of the braking line.
TEST(UavMission, APathPlannedInFlightStartsWhereTheUavStops) {
  for (const bool braking_line_clear : {true, false}) {
    SCOPED_TRACE(braking_line_clear ? "braking line clear" : "braking line blocked");
    Rig rig;
    rig.flight.drain_per_s = 1.0 / 60.0;
    UavMissionOptions o = small_area();
    o.flight_endurance_s = 60.0;
    auto m = rig.mission(o);
    std::optional<FlightState> at_call;
    std::size_t calls_before = 0;
    Eigen::Vector3d corner = Eigen::Vector3d::Zero();
    m->start();
    for (int k = 0; k < 30000 && !m->done(); ++k) {
      rig.clock.advance(0.02);
      const FlightState before = rig.flight.state();
      const std::size_t n = rig.calls.size();
      if (!braking_line_clear && !rig.blocked)
        rig.blocked = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
          return (b - a).norm() < 3.0 && (b - a).norm() > 2.0;
        };
      m->tick();
      if (!at_call && m->state() == UavMissionState::kReturnHome) {
        at_call = before;
        calls_before = n;
        // The leg it was on ends at the pattern's next waypoint.
        corner = m->pattern()[m->pattern_done()];
      }
      rig.flight.step(0.02);
    }
    ASSERT_TRUE(at_call);
    ASSERT_GT(at_call->v_W.norm(), 2.9);  // mid-leg at 3 m/s
    // 3 m/s braking at 1.6 m/s^2: 9 / 3.2 = 2.8125 m on along the way it flew.
    const Eigen::Vector3d stop = at_call->p_W + at_call->v_W.normalized() * 2.8125;
    ASSERT_GE(rig.calls.size(), calls_before + 2);
    EXPECT_LT((rig.calls[calls_before].first - at_call->p_W).norm(), 1e-9);
    EXPECT_LT((rig.calls[calls_before].second - stop).norm(), 1e-6);
    const Eigen::Vector3d start = rig.calls[calls_before + 1].first;
    if (braking_line_clear)
      EXPECT_LT((start - stop).norm(), 1e-6);
    else
      EXPECT_LT((start - corner).norm(), 1e-6)
          << start.transpose() << " vs corner " << corner.transpose();
    EXPECT_EQ(m->outcome(), UavMissionOutcome::kFlightBudget);
  }
}

TEST(UavMission, LegsWithoutAPlanAreSkippedAndTheMissionStillEnds) {
  Rig rig;
  rig.plans_fail = true;
  auto m = rig.mission(small_area());
  rig.run(*m, 600.0);
  ASSERT_TRUE(m->done());
  EXPECT_EQ(m->outcome(), UavMissionOutcome::kSearchComplete);
  EXPECT_GE(m->plans_failed(), static_cast<int>(m->pattern().size()));
}

// The survey's hover: a dropped depth frame (0 x 0) does not count toward
// uav.survey_frames, and the frames taken are fused with their own poses, at the first's.
TEST(SurveyFrames, DroppedFramesAreNotCountedAndTheFramesAreFusedAtTheFirstPose) {
  SurveyFrames frames(CameraModel::from_fov("depth", 4, 3, 1.0));
  Pose3 a = Pose3::Identity(), b = Pose3::Identity();
  a.translation() = Eigen::Vector3d(1, 2, 3);
  b.translation() = Eigen::Vector3d(1.01, 2, 3);  // 1 cm: under a pixel at 1.2 m
  EXPECT_FALSE(frames.add({DepthImageMm{}, a}, 2));
  EXPECT_EQ(frames.size(), 0u);
  EXPECT_FALSE(frames.add({DepthImageMm(4, 3, 1000), a}, 2));
  EXPECT_FALSE(frames.add({DepthImageMm(4, 0, 0), b}, 2));
  EXPECT_EQ(frames.size(), 1u);
  EXPECT_TRUE(frames.add({DepthImageMm(4, 3, 1200), b}, 2));
  EXPECT_EQ(frames.size(), 2u);
  EXPECT_TRUE(frames.fused().X_WC().isApprox(a));
  const DepthImageMm fused = frames.fused().fused();
  EXPECT_EQ(fused.at(0, 0), 1100);
  EXPECT_EQ(fused.at(2, 1), 1100);
  // A frame of another size than the depth camera's is refused, and not counted.
  EXPECT_THROW((void)frames.add({DepthImageMm(5, 3, 1000), a}, 3), InputError);
  EXPECT_EQ(frames.size(), 2u);
  frames.clear();
  EXPECT_EQ(frames.size(), 0u);
  EXPECT_TRUE(frames.add({DepthImageMm(4, 3, 1500), b}, 1));
  EXPECT_TRUE(frames.fused().X_WC().isApprox(b));
  EXPECT_EQ(frames.fused().fused().at(3, 2), 1500);
}

TEST(UavMission, BadOptionsNameTheField) {
  const auto field_of = [](UavMissionOptions o) {
    try {
      o.validate("mission.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  UavMissionOptions o;
  o.passes = 3;
  EXPECT_NE(field_of(o).find("uav.passes"), std::string::npos);
  // no_landing_zone is an enum: its words are checked where they are read.
  for (const NoLandingZone c : {NoLandingZone::kHover, NoLandingZone::kSkip})
    EXPECT_EQ(parse_no_landing_zone(std::string(to_string(c)), "mission.yaml"), c);
  try {
    (void)parse_no_landing_zone("crash", "mission.yaml", "uav.no_landing_zone");
    ADD_FAILURE() << "crash accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "uav.no_landing_zone");
    EXPECT_EQ(e.expected(), "hover or skip");
  }
  o = {};
  o.search_altitude_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(field_of(o).find("uav.search_altitude_m"), std::string::npos);
  o = {};
  o.search_area_m = {5, 0, 1, 8};
  EXPECT_NE(field_of(o).find("uav.search_area_m"), std::string::npos);
  o = {};
  o.tether.entry_offset_m = 20.0;
  EXPECT_NE(field_of(o).find("tether.entry_offset_m"), std::string::npos);
  EXPECT_EQ(field_of(UavMissionOptions{}), "");
}

// report.json and the mission YAML carry these words: the enums must print them.
TEST(UavMission, VisitStatesAndReleaseModesPrintTheirWords) {
  EXPECT_EQ(to_string(VisitState::kDetected), "detected");
  EXPECT_EQ(to_string(VisitState::kSkipped), "skipped");
  EXPECT_EQ(to_string(VisitState::kServiced), "serviced");
  EXPECT_EQ(HiddenSpaceVisit{}.state, VisitState::kDetected);
  EXPECT_EQ(to_string(ReleaseMode::kLand), "land");
  EXPECT_EQ(to_string(ReleaseMode::kHover), "hover");
  EXPECT_EQ(UavMissionOptions{}.release, ReleaseMode::kLand);
}

}  // namespace
}  // namespace ferret
