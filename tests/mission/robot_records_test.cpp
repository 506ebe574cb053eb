// Each robot process's record (mission/robot_records.hpp, mission_outputs.hpp's RunSide):
// the UAV's from the readings its mission made, and each side's report.json with what
// that side knows and nothing it cannot.

#include "ferret/mission/robot_records.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "ferret/core/clock.hpp"
#include "ferret/core/error.hpp"
#include "ferret/mission/mission_assembly.hpp"
#include "ferret/mission/mission_outputs.hpp"
#include "ferret/uav/linked_ugv.hpp"
#include "support/cli_runner.hpp"
#include "two_sites_mission.hpp"

namespace ferret {
namespace {

// A vehicle flying along x at 1 m a reading; counts its readings.
class StepFlight final : public FlightController {
 public:
  std::string backend() const override { return "hw"; }
  FlightState state() const override {
    FlightState s;
    s.p_W = Eigen::Vector3d(static_cast<double>(reads_++), 0.0, 2.0);
    s.battery_fraction = 0.9;
    return s;
  }
  void command_takeoff(double) override {}
  void command_position(const Eigen::Vector3d&, double, double) override {}
  void command_land() override {}
  int reads() const { return reads_; }

 private:
  mutable int reads_ = 0;
};

class NoCameras final : public UavCameras {
 public:
  CameraShot<GrayImage> marker_frame() override { return {}; }
  CameraShot<DepthImageMm> depth_frame() override { return {}; }
};

class PayingOutWinch final : public tether::Winch {
 public:
  void set_torque_enabled(bool) override {}
  void command_velocity_mps(double) override {}
  tether::WinchState read_state() override {
    ++reads;
    return {0.1 * reads, 0.0, reads == 3 ? 4.0 : 1.0};
  }
  int reads = 0;
};

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

using Loaded = test::TwoSitesMission;

TEST(UavRunRecorder, RecordsTheReadingsTheMissionMadeAndNoOther) {
  const Loaded l;
  const MissionAssembly assembly(l.world, l.uav, l.settings, 1, "m.yaml");
  StepFlight flight;
  NoCameras cameras;
  PayingOutWinch winch;
  SimClock clock;
  LinkedUgv ugv(clock);
  UavRunRecorder recorder(flight, winch);
  TransitionLog log;
  const auto mission =
      assembly.uav_mission({recorder.flight(), cameras, recorder.winch(), ugv}, clock, &log);
  // Twenty ticks of 0.1 s, each reading the vehicle once and the winch on the first five.
  for (int k = 0; k < 20; ++k) {
    clock.set(0.1 * k);
    (void)recorder.flight().state();
    if (k < 5) (void)recorder.winch().read_state();
    recorder.after_tick(clock.now_s(), *mission);
  }
  EXPECT_EQ(flight.reads(), 20);  // nothing read behind the mission's back
  EXPECT_EQ(winch.reads, 5);
  const MissionRunResult r = recorder.result(mission.get(), clock.now_s(), log);
  EXPECT_DOUBLE_EQ(r.flown_m, 19.0);  // 1 m between readings
  EXPECT_DOUBLE_EQ(r.battery_left, 0.9);
  EXPECT_DOUBLE_EQ(r.max_released_m, 0.5);
  EXPECT_DOUBLE_EQ(r.max_tension_n, 4.0);
  ASSERT_EQ(r.samples.size(), 4u);  // every 0.5 s: 0, 0.5, 1.0, 1.5
  EXPECT_NEAR(r.samples[1].t_s, 0.5, 1e-9);
  EXPECT_DOUBLE_EQ(r.samples[1].p_W.x(), 5.0);
  EXPECT_DOUBLE_EQ(r.samples[1].released_m, 0.5);  // the last reading, held
  EXPECT_EQ(r.samples[1].state, "idle");
  EXPECT_EQ(r.pattern_waypoints, mission->pattern().size());
  EXPECT_EQ(r.outcome, mission->outcome());
}

TEST(RunOutputs, EachSideWritesWhatItKnowsAndLeavesOutTheRest) {
  const Loaded l;
  MissionRunResult r;
  r.time_s = 12.0;
  r.uav_collisions = 3;
  r.objects_dropped = 1;
  r.flown_m = 40.0;
  r.samples.push_back({0.0, Eigen::Vector3d(1, 2, 3), 0.1, "search", 0.9, 0.2, 0.3, 0.4, 0.8});
  UgvDeployment d;
  d.hidden_space = "kiln_void";
  d.deployed_s = 2.0;
  d.result.body_contacts = 2;
  d.result.decisions = 7;
  r.deployments.push_back(d);
  test::TempDir dir;
  const auto report = [&](RunSide side, const std::string& ended_early) {
    RunOutputsInput in = robot_side(side, 4, ended_early);
    const auto out = dir.path() / std::string(1, static_cast<char>('a' + static_cast<int>(side)));
    write_run_outputs(out, in, r);
    return nlohmann::json::parse(slurp(out / "report.json"));
  };
  const auto all = report(RunSide::kMission, "ignored");
  EXPECT_FALSE(all.contains("side"));
  EXPECT_FALSE(all.contains("ended_early"));
  EXPECT_EQ(all.at("summary").at("uav_collisions"), 3);
  EXPECT_EQ(all.at("samples").at(0).size(), 11u);

  const auto uav = report(RunSide::kUav, "lost the world");
  EXPECT_EQ(uav.at("side"), "uav");
  EXPECT_EQ(uav.at("ended_early"), "lost the world");
  EXPECT_EQ(uav.at("seed"), 4);
  for (const char* truth : {"uav_collisions", "objects_dropped", "ugv_body_contacts"})
    EXPECT_FALSE(uav.at("summary").contains(truth)) << truth;
  EXPECT_FALSE(uav.contains("ugv_deployments"));
  EXPECT_EQ(uav.at("summary").at("flown_m"), 40.0);
  EXPECT_EQ(uav.at("samples").at(0),
            nlohmann::json::parse(R"([0,1,2,3,0.1,"search",0.9,0.2,0.4])"));

  const auto world = report(RunSide::kWorld, "");
  EXPECT_TRUE(world.at("ended_early").is_null());
  EXPECT_FALSE(world.contains("outcome"));  // the UAV's, in its own summary
  EXPECT_FALSE(world.contains("hidden_spaces"));
  EXPECT_EQ(world.at("summary").at("uav_collisions"), 3);
  EXPECT_EQ(world.at("ugv_deployments").at(0).at("body_contacts"), 2);
  EXPECT_FALSE(world.at("ugv_deployments").at(0).contains("decisions"));

  const auto ugv = report(RunSide::kUgv, "");
  EXPECT_FALSE(ugv.contains("samples"));
  EXPECT_FALSE(ugv.contains("outcome"));
  EXPECT_FALSE(ugv.at("summary").contains("flown_m"));
  EXPECT_EQ(ugv.at("summary").at("searches"), 1);
  const auto& search = ugv.at("ugv_deployments").at(0);
  EXPECT_EQ(search.at("decisions"), 7);
  EXPECT_FALSE(search.contains("hidden_space"));  // the world's name
  EXPECT_FALSE(search.contains("body_contacts"));
}

TEST(RunOutputs, AnOutputThatCannotBeADirectoryIsBadInputNamingTheOption) {
  test::TempDir dir;
  const auto file = dir.path() / "a_file";
  std::ofstream(file) << "x";
  EXPECT_NO_THROW(check_record_target(""));
  EXPECT_NO_THROW(check_record_target((dir.path() / "new").string()));
  for (const auto& bad : {file, file / "under"}) {
    try {
      check_record_target(bad.string());
      FAIL() << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--out"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(slurp(file), "x");
}

}  // namespace
}  // namespace ferret
