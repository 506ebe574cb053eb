#include "ferret/ugv/remote_ugv_base.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <thread>

#include "ferret/core/clock.hpp"
#include "ferret/core/transition_log.hpp"
#include "ferret/link/json_dispatcher.hpp"
#include "ferret/mission/mission_assembly.hpp"
#include "ferret/mission/ugv_mission_run.hpp"
#include "ferret/sim/ugv_mission_run.hpp"
#include "ferret/ugv/mini_ugv_mission.hpp"
#include "support/test_maps.hpp"

namespace ferret {
namespace {

using link::StreamMessage;
using nlohmann::json;

// A base that answers with fixed values and records the commands it gets.
class FixedBase final : public UgvBase {
 public:
  std::string backend() const override { return "hw"; }
  Pose2 odometry() const override { return {1.25, -0.5, 0.1 + 1e-17}; }
  double speed_mps() const override { return 0.3; }
  RangeScan ir_scan() override {
    RangeScan s;
    s.X_WS = {0.1, 0.2, 0.3};
    s.max_range_m = 0.8;
    s.beams = {{-0.5, 0.25}, {0.0, std::numeric_limits<double>::infinity()}, {0.5, 0.8}};
    return s;
  }
  CameraFrame camera_frame(double time_s) override {
    CameraFrame f;
    f.time_s = time_s;
    f.view = ir_scan();
    f.detections = {{0.2, 1.5, 1.0 / 3.0}};
    return f;
  }
  void command_velocity(double v, double w) override {
    v_mps = v;
    w_radps = w;
    ++commands;
  }
  void set_epm(bool on) override {
    epm = on;
    ++commands;
  }
  UgvStatus status() const override { return {0.75, epm, true, 0x21u}; }

  double v_mps = 0.0, w_radps = 0.0;
  bool epm = false;
  int commands = 0;
};

class DirectChannel final : public link::RpcChannel {
 public:
  explicit DirectChannel(UgvBaseService& s) : service_(s) {}
  StreamMessage call(const std::string& request) override { return service_.handle({request, {}}); }

 private:
  UgvBaseService& service_;
};

// Answers every request with one fixed reply (after a good hello).
class Replay final : public link::RpcChannel {
 public:
  std::string reply;
  StreamMessage call(const std::string& request) override {
    if (json::parse(request)["op"] == "hello")
      return {R"({"ok":true,"protocol":1,"server":"replay"})", {}};
    return {reply, {}};
  }
};

TEST(RemoteUgvBase, EveryCallCarriesItsValuesExactly) {
  FixedBase fixed;
  UgvBaseService service(fixed, "fixture");
  DirectChannel channel(service);
  RemoteUgvBase remote(channel, "sim");
  EXPECT_EQ(remote.backend(), "sim");
  EXPECT_EQ(remote.server_name(), "fixture");
  EXPECT_EQ(remote.odometry().yaw_rad, fixed.odometry().yaw_rad);  // bit for bit
  EXPECT_EQ(remote.odometry().x_m, 1.25);
  EXPECT_EQ(remote.speed_mps(), 0.3);
  const RangeScan s = remote.ir_scan();
  ASSERT_EQ(s.beams.size(), 3u);
  EXPECT_EQ(s.max_range_m, 0.8);
  EXPECT_EQ(s.X_WS.yaw_rad, 0.3);
  EXPECT_EQ(s.beams[0].range_m, 0.25);
  EXPECT_TRUE(std::isinf(s.beams[1].range_m));  // no return travels as null
  const CameraFrame f = remote.camera_frame(12.5);
  EXPECT_EQ(f.time_s, 12.5);
  ASSERT_EQ(f.detections.size(), 1u);
  EXPECT_EQ(f.detections[0].confidence, 1.0 / 3.0);
  EXPECT_EQ(f.view.beams.size(), 3u);
  remote.command_velocity(0.2, -0.7);
  EXPECT_EQ(fixed.v_mps, 0.2);
  EXPECT_EQ(fixed.w_radps, -0.7);
  remote.set_epm(true);
  const UgvStatus st = remote.status();
  EXPECT_EQ(st.battery_fraction, 0.75);
  EXPECT_TRUE(st.epm_on);
  EXPECT_TRUE(st.contact);
  EXPECT_EQ(st.faults, 0x21u);
  EXPECT_EQ(fixed.commands, 2);
}

TEST(RemoteUgvBase, TheServiceRefusesBadRequestsWithoutActingOnThem) {
  FixedBase fixed;
  UgvBaseService service(fixed, "fixture");
  const auto refused = [&](const std::string& request, const std::string& error_part) {
    const json r = json::parse(service.handle({request, {}}).header);
    EXPECT_FALSE(r.at("ok").get<bool>()) << request;
    EXPECT_NE(r.value("error", "").find(error_part), std::string::npos)
        << request << ": " << r.dump();
  };
  refused("not json", "not a JSON object");
  refused("[1, 2]", "not a JSON object");
  refused(R"({"v_mps": 1})", "'op'");
  refused(R"({"op": "fly"})", "'fly' is not an op");
  refused(R"({"op": "hello", "protocol": 2})", "speaks 1");
  refused(R"({"op": "velocity", "v_mps": 0.1})", "'w_radps'");
  refused(R"({"op": "velocity", "v_mps": 1e300, "w_radps": 0})", "'v_mps'");
  refused(R"({"op": "velocity", "v_mps": "fast", "w_radps": 0})", "'v_mps'");
  refused(R"({"op": "epm", "on": 1})", "'on'");
  refused(R"({"op": "camera_frame"})", "'time_s'");
  refused("{\"op\": \"\xff\xfe\"}", "not a JSON object");  // not UTF-8
  EXPECT_EQ(fixed.commands, 0);
}

TEST(RemoteUgvBase, TheClientRefusesBrokenReplies) {
  Replay replay;
  RemoteUgvBase remote(replay, "sim");
  const auto broken = [&](const std::string& reply, const std::function<void()>& call) {
    replay.reply = reply;
    EXPECT_THROW(call(), UgvBaseProtocolError) << reply;
  };
  const auto scan = [&] { (void)remote.ir_scan(); };
  broken("", [&] { (void)remote.odometry(); });
  broken(R"({"ok":true})", [&] { (void)remote.odometry(); });
  broken(R"({"ok":true,"pose":[1,2]})", [&] { (void)remote.odometry(); });
  broken(R"({"ok":true,"pose":[1,2,"x"]})", [&] { (void)remote.odometry(); });
  broken(R"({"ok":false,"error":"motor fault"})", [&] { remote.command_velocity(0, 0); });
  broken(R"({"ok":true,"scan":{"X_WS":[0,0,0],"max_range_m":1,"beams":[0.1]}})", scan);
  broken(R"({"ok":true,"scan":{"X_WS":[0,0,0],"max_range_m":0,"beams":[]}})", scan);
  broken(R"({"ok":true,"scan":{"X_WS":[0,0,0],"max_range_m":1,"beams":[0.1,-1]}})", scan);
  broken(R"({"ok":true,"scan":{"X_WS":[0,0,0],"max_range_m":1,"beams":[0.1,1e999]}})", scan);
  broken(R"({"ok":true,"battery_fraction":1,"epm_on":false,"contact":false,"faults":-1})",
         [&] { (void)remote.status(); });
  broken(R"({"ok":true,"battery_fraction":1,"epm_on":false,"contact":false,"faults":4294967296})",
         [&] { (void)remote.status(); });
  broken(
      R"({"ok":true,"frame":{"time_s":0,"view":{"X_WS":[0,0,0],"max_range_m":1,"beams":[]},"detections":[[0,0,1]]}})",
      [&] { (void)remote.camera_frame(0); });
  // Too many beams for one scan: broken, not a long allocation.
  std::string many = R"({"ok":true,"scan":{"X_WS":[0,0,0],"max_range_m":1,"beams":[)";
  for (std::size_t k = 0; k <= kMaxRemoteBeams; ++k) many += (k ? ",0,1" : "0,1");
  broken(many + "]}}", scan);
  // A server of another protocol version is refused at the greeting.
  class OtherVersion final : public link::RpcChannel {
    StreamMessage call(const std::string&) override { return {R"({"ok":true,"protocol":2})", {}}; }
  } other;
  EXPECT_THROW(RemoteUgvBase(other, "sim"), UgvBaseProtocolError);
}

// The miniUGV's whole mission with its base served over loopback TCP by a thread (as the
// simulated world serves it to a robot process), stepped by a "sim_step" op after each
// tick: the same trajectory, transitions and outcome as with the base in the process.
TEST(RemoteUgvBase, AMissionOverTheProtocolIsTheMissionInProcess) {
  const auto map = test::small_hidden_space();
  const Pose2 entry{0.5, 1.0, 0.0};
  const Eigen::Vector2d object(1.6, 1.0);
  UgvMissionRunSettings settings;
  settings.exploration.method = "cdos";
  settings.exploration.record = true;
  settings.ugv.explore_timeout_s = 200.0;
  const std::uint64_t seed = 2;
  const UgvMissionRunResult reference = run_ugv_mission(map, entry, object, settings, seed);
  ASSERT_EQ(reference.outcome, UgvMissionOutcome::kObjectRetrieved);

  UgvMissionSim world(map, entry, object, settings, seed);  // the base alone
  UgvBaseService service(world.base(), "sim");
  service.dispatcher().add("sim_step", [&](const link::JsonRequest& r) -> link::JsonReply {
    world.step(r.fields.at("dt_s").get<double>());
    return {};
  });
  link::MessageListener listener(link::parse_ipv4_address("127.0.0.1:0", "test", "listen", true),
                                 "test", "listen");
  std::atomic<bool> stop{false};
  std::thread server([&] {
    std::optional<link::MessageStream> stream;
    while (!stop && !stream) stream = listener.accept(50);
    while (stream && !stop) {
      try {
        if (auto request = stream->receive(50)) stream->send(service.handle(*request));
      } catch (const link::StreamError&) {
        return;
      }
    }
  });
  {
    link::StreamRpcChannel channel(
        link::MessageStream::connect({{127, 0, 0, 1}, listener.port()}, 5.0), 10'000);
    RemoteUgvBase base(channel, "sim");
    SimClock clock;
    TransitionLog log;
    MiniUgvMission mission(base, clock, ugv_mission_map(map.geometry, entry, settings),
                           ugv_mission_options(settings, seed, object, map.geometry), &log);
    // run_ugv_mission's loop, the base stepped by its server.
    const double dt = world.tick_s();
    std::optional<double> retract_at_s;
    mission.start();
    for (long step = 0; step < static_cast<long>(settings.time_limit_s / dt) && !mission.done();
         ++step) {
      clock.set(static_cast<double>(step) * dt);
      if (mission.wants_retraction()) {
        if (!retract_at_s) retract_at_s = clock.now_s() + settings.retract_time_s;
        if (clock.now_s() >= *retract_at_s) {
          mission.retracted();
          break;
        }
      }
      mission.tick();
      (void)channel.call(json{{"op", "sim_step"}, {"dt_s", dt}}.dump());
    }
    EXPECT_EQ(mission.outcome(), reference.outcome);
    EXPECT_EQ(clock.now_s(), reference.time_s);
    ASSERT_EQ(log.all().size(), reference.transitions.size());
    for (std::size_t k = 0; k < log.all().size(); ++k) {
      EXPECT_EQ(log.all()[k].to, reference.transitions[k].to) << k;
      EXPECT_EQ(log.all()[k].t_s, reference.transitions[k].t_s) << k;
    }
  }
  stop = true;
  server.join();
  const UgvMissionRunResult served = world.result(TransitionLog{});
  ASSERT_EQ(served.trajectory.size(), reference.trajectory.size());
  for (std::size_t k = 0; k < served.trajectory.size(); ++k) {
    ASSERT_EQ(served.trajectory[k].x_m, reference.trajectory[k].x_m) << k;
    ASSERT_EQ(served.trajectory[k].y_m, reference.trajectory[k].y_m) << k;
  }
  EXPECT_EQ(served.path_m, reference.path_m);
  EXPECT_TRUE(served.object_held);
}

}  // namespace
}  // namespace ferret
