// The flight adapter protocol (docs/robots.md) end to end: ferret's client
// (uav/adapter_flight_controller.hpp) against the reference adapter over the simulated
// M100 (sim/sim_flight_adapter.hpp), over TCP on loopback as `ferret uav` meets a DJI
// adapter; and both halves against peers that break the protocol.

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>

#include "ferret/core/data_path.hpp"
#include "ferret/mission/mission_settings.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/sim/sensor_sim.hpp"
#include "ferret/sim/sim_flight_adapter.hpp"
#include "ferret/uav/adapter_flight_controller.hpp"
#include "ferret/uav/flight_adapter_check.hpp"
#include "ferret/uav/flight_controller_config.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

using link::MessageListener;
using link::MessageStream;
using link::StreamError;
using link::StreamMessage;
using nlohmann::json;

struct World {
  MissionConfig mission;
  RobotDescription uav = load_robot_description(data_path("models/m100.urdf"), mission);
  RobotDescription ugv = load_robot_description(data_path("models/miniugv.urdf"), mission);
  PlanningWorld world = load_planning_world(data_path("worlds/small.yaml"));
  MissionRunSettings settings = mission_settings_for(uav, ugv, mission, *world.spec);
};
World& world() {
  static World w;  // built once: the collision maps take a moment
  return w;
}

// The reference adapter served on a loopback port from a thread, as
// `ferret flight-adapter serve` serves it (one client at a time).
class ServedAdapter {
 public:
  explicit ServedAdapter(std::uint64_t seed)
      : adapter_(world().world, world().uav, world().settings, seed),
        listener_(link::parse_ipv4_address("127.0.0.1:0", "test", "listen", true), "test",
                  "listen"),
        thread_([this] {
          while (!stop_) {
            if (auto stream = listener_.accept(50))
              adapter_.serve(*stream, [this] { return !stop_.load(); });
          }
        }) {}
  ~ServedAdapter() {
    stop_ = true;
    thread_.join();
  }
  [[nodiscard]] link::Ipv4Address address() const { return {{127, 0, 0, 1}, listener_.port()}; }

 private:
  SimFlightAdapter adapter_;
  MessageListener listener_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// The client's RpcChannel straight into an adapter, no socket (the same bytes).
class DirectChannel final : public link::RpcChannel {
 public:
  explicit DirectChannel(SimFlightAdapter& a) : adapter_(a) {}
  StreamMessage call(const std::string& request) override { return adapter_.handle({request, {}}); }

 private:
  SimFlightAdapter& adapter_;
};

void advance(link::RpcChannel& channel, double seconds) {
  const json r =
      json::parse(channel.call(json{{"op", "sim_advance"}, {"seconds", seconds}}.dump()).header);
  ASSERT_TRUE(r.value("ok", false)) << r.dump();
}

TEST(FlightAdapter, TheHwBackendOfTheRegistryConnectsToTheConfiguredAdapter) {
  ServedAdapter served(1);
  FlightControllerConfig config;
  config.backend = "hw";
  config.address = served.address().to_string();
  const std::unique_ptr<FlightBackend> vehicle = make_flight_backend(config);
  EXPECT_EQ(vehicle->peer_name(), "sim");  // what the reference adapter says in its hello
  EXPECT_EQ(vehicle->flight().backend(), "hw");
  EXPECT_TRUE(vehicle->flight().state().on_ground);
}

TEST(FlightAdapter, TheClientFliesTheReferenceAdapterOverTcp) {
  ServedAdapter served(1);
  link::StreamRpcChannel channel(MessageStream::connect(served.address(), 5.0), 10'000);
  AdapterFlightController flight(channel, "sim");
  EXPECT_EQ(flight.adapter_name(), "sim");
  EXPECT_EQ(flight.backend(), "sim");

  const FlightState start = flight.state();
  EXPECT_TRUE(start.on_ground);
  EXPECT_DOUBLE_EQ(start.battery_fraction, 1.0);
  flight.command_position(start.p_W + Eigen::Vector3d(1, 0, 0), 0.0, 1.0);  // ignored on the ground
  advance(channel, 1.0);
  EXPECT_NEAR((flight.state().p_W - start.p_W).norm(), 0.0, 1e-12);

  flight.command_takeoff(start.p_W.z() + 4.0);
  advance(channel, 8.0);
  FlightState s = flight.state();
  EXPECT_FALSE(s.on_ground);
  EXPECT_NEAR(s.p_W.z(), start.p_W.z() + 4.0, 0.02);
  EXPECT_LT(s.battery_fraction, 1.0);  // hovering costs charge

  const Eigen::Vector3d goal = s.p_W + Eigen::Vector3d(1.0, 0.5, 0.0);
  flight.command_position(goal, 0.5, 2.0);
  advance(channel, 8.0);
  s = flight.state();
  EXPECT_NEAR((s.p_W - goal).norm(), 0.0, 0.02);
  EXPECT_NEAR(s.yaw_rad, 0.5, 1e-3);

  // A velocity set-point of 1 m/s along x for 2 s: 0.5 s at the M100's 2 m/s^2 to reach
  // it (0.25 m), then 1.5 s at speed (1.5 m).
  const double x0 = s.p_W.x();
  flight.command_velocity({1.0, 0.0, 0.0}, 0.0);
  advance(channel, 2.0);
  EXPECT_NEAR(flight.state().p_W.x() - x0, 1.75, 0.03);

  flight.command_land();
  advance(channel, 20.0);
  s = flight.state();
  EXPECT_TRUE(s.on_ground);
  EXPECT_NEAR(s.v_W.norm(), 0.0, 1e-12);
  EXPECT_NEAR(s.p_W.z(), start.p_W.z(), 0.05);  // flat ground round home
}

TEST(FlightAdapter, FramesCrossTheSocketBitForBit) {
  // Two adapters with the same seed: one over TCP, one called directly. The same
  // frames, pixel for pixel, with the camera's pose, at the URDF camera's size.
  ServedAdapter served(7);
  SimFlightAdapter local(world().world, world().uav, world().settings, 7);
  link::StreamRpcChannel tcp(MessageStream::connect(served.address(), 5.0), 10'000);
  DirectChannel direct(local);
  AdapterFlightController a(tcp, "sim"), b(direct, "sim");
  a.command_takeoff(3.0);
  b.command_takeoff(3.0);
  advance(tcp, 5.0);
  advance(direct, 5.0);
  const CameraShot<GrayImage> ma = a.marker_frame(), mb = b.marker_frame();
  const CameraSensor& cam = camera_for(world().uav, false, "marker_camera");
  EXPECT_EQ(ma.image.width_px, cam.image_width_px);
  EXPECT_EQ(ma.image.height_px, cam.image_height_px);
  EXPECT_EQ(ma.image.data, mb.image.data);
  EXPECT_TRUE(ma.X_WC.matrix().isApprox(mb.X_WC.matrix(), 1e-12));
  // The optical frame sits on the vehicle (within its arm's reach of base_link).
  EXPECT_LT((ma.X_WC.translation() - a.state().p_W).norm(), 0.5);
  const CameraShot<DepthImageMm> da = a.depth_frame(), db = b.depth_frame();
  const CameraSensor& depth = camera_for(world().uav, true, "depth_camera");
  EXPECT_EQ(da.image.width_px, depth.image_width_px);
  EXPECT_EQ(da.image.data, db.image.data);
  // Looking down from 3 m at flat ground: most pixels have a return near 3 m.
  int near_3m = 0;
  for (const std::uint16_t mm : da.image.data)
    near_3m += std::abs(static_cast<int>(mm) - 3000) < 400;
  EXPECT_GT(near_3m, static_cast<int>(da.image.data.size()) / 2);
}

json refused(SimFlightAdapter& a, const std::string& request) {
  const json r = json::parse(a.handle({request, {}}).header);
  EXPECT_FALSE(r.value("ok", true)) << request;
  return r;
}

TEST(FlightAdapter, TheAdapterRefusesBadRequestsNamingTheField) {
  SimFlightAdapter a(world().world, world().uav, world().settings, 1);
  EXPECT_NE(refused(a, "takeoff").value("error", "").find("not a JSON object"), std::string::npos);
  EXPECT_NE(refused(a, R"({"op": 5})").value("error", "").find("'op'"), std::string::npos);
  EXPECT_NE(refused(a, R"({"op": "fly"})").value("error", "").find("'fly' is not an op"),
            std::string::npos);
  EXPECT_NE(refused(a, R"({"op": "takeoff"})").value("error", "").find("'z_m'"), std::string::npos);
  EXPECT_NE(refused(a, R"({"op": "position", "p_W": [1, 2], "yaw_rad": 0, "speed_mps": 1})")
                .value("error", "")
                .find("'p_W': expected an array of 3"),
            std::string::npos);
  EXPECT_NE(refused(a, R"({"op": "position", "p_W": [1e9, 0, 0], "yaw_rad": 0, "speed_mps": 1})")
                .value("error", "")
                .find("'p_W'"),
            std::string::npos);
  EXPECT_NE(refused(a, R"({"op": "position", "p_W": [1, 0, 0], "yaw_rad": 0, "speed_mps": -1})")
                .value("error", "")
                .find("'speed_mps'"),
            std::string::npos);
  EXPECT_NE(refused(a, R"({"op": "hello", "protocol": 2})").value("error", "").find("speaks 1"),
            std::string::npos);
  EXPECT_NE(
      refused(a, R"({"op": "sim_advance", "seconds": -1})").value("error", "").find("'seconds'"),
      std::string::npos);
  // Nothing refused moved the vehicle.
  const json s = json::parse(a.handle({R"({"op": "state"})", {}}).header);
  EXPECT_TRUE(s.value("on_ground", false));
}

// A fake adapter that answers every request with `reply` (or not at all).
class FakeAdapter {
 public:
  explicit FakeAdapter(std::optional<StreamMessage> reply)
      : listener_(link::parse_ipv4_address("127.0.0.1:0", "test", "listen", true), "test",
                  "listen"),
        thread_([this, reply] {
          auto stream = listener_.accept(5000);
          if (!stream) return;
          try {
            while (!stop_)
              if (stream->receive(50) && reply) stream->send(*reply);
          } catch (const StreamError&) {
          }
        }) {}
  ~FakeAdapter() {
    stop_ = true;
    thread_.join();
  }
  [[nodiscard]] link::Ipv4Address address() const { return {{127, 0, 0, 1}, listener_.port()}; }

 private:
  MessageListener listener_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

std::string client_error(const std::optional<StreamMessage>& reply, int timeout_ms = 2000) {
  FakeAdapter fake(reply);
  link::StreamRpcChannel channel(MessageStream::connect(fake.address(), 5.0), timeout_ms);
  try {
    AdapterFlightController flight(channel, "hw");
    (void)flight.state();
  } catch (const StreamError& e) {
    return e.what();
  }
  return "";
}

TEST(FlightAdapter, TheClientRefusesAnAdapterThatBreaksTheProtocol) {
  EXPECT_NE(client_error(StreamMessage{R"({"ok": true, "protocol": 2, "adapter": "x"})", {}})
                .find("protocol 2"),
            std::string::npos);
  EXPECT_NE(client_error(StreamMessage{R"({"ok": false, "error": "motors locked"})", {}})
                .find("motors locked"),
            std::string::npos);
  EXPECT_NE(client_error(StreamMessage{"[1, 2]", {}}).find("not a JSON object"), std::string::npos);
  EXPECT_NE(client_error(std::nullopt, 300).find("did not answer within 300 ms"),
            std::string::npos);
  // Fields of the wrong type are the adapter's error, named (not a JSON library's).
  EXPECT_NE(client_error(StreamMessage{R"({"ok": true, "protocol": 1, "adapter": 0})", {}})
                .find("'adapter'"),
            std::string::npos);
  EXPECT_NE(client_error(StreamMessage{R"({"ok": "yes", "protocol": 1})", {}}).find("'ok'"),
            std::string::npos);
  EXPECT_NE(client_error(StreamMessage{R"({"ok": true, "protocol": "1"})", {}}).find("'protocol'"),
            std::string::npos);
  // An adapter whose hello is right but whose state is not: every field is checked.
  EXPECT_NE(client_error(StreamMessage{R"({"ok": true, "protocol": 1, "p_W": [0, 0]})", {}})
                .find("'p_W'"),
            std::string::npos);
}

int passed(const std::vector<AdapterCheck>& checks) {
  int n = 0;
  for (const AdapterCheck& c : checks) n += c.passed ? 1 : 0;
  return n;
}

TEST(FlightAdapter, TheReferenceAdapterPassesTheGroundChecks) {
  ServedAdapter served(3);
  link::StreamRpcChannel channel(MessageStream::connect(served.address(), 5.0), 10'000);
  const std::vector<AdapterCheck> checks = check_flight_adapter(channel);
  ASSERT_EQ(checks.size(), 9u);
  for (const AdapterCheck& c : checks) EXPECT_TRUE(c.passed) << c.name << ": " << c.detail;
}

TEST(FlightAdapter, TheGroundChecksCatchAnAdapterThatSaysYesToEverything) {
  // Hello is right, so the suite goes on; every other answer is a bare "ok".
  FakeAdapter yes(StreamMessage{R"({"ok": true, "protocol": 1, "adapter": "yes-man"})", {}});
  link::StreamRpcChannel channel(MessageStream::connect(yes.address(), 5.0), 2000);
  const std::vector<AdapterCheck> checks = check_flight_adapter(channel);
  ASSERT_EQ(checks.size(), 9u);
  EXPECT_TRUE(checks[0].passed) << checks[0].detail;  // hello
  EXPECT_FALSE(checks[1].passed);                     // state without p_W
  EXPECT_NE(checks[1].detail.find("'p_W'"), std::string::npos) << checks[1].detail;
  EXPECT_FALSE(checks[2].passed);        // no frame
  for (std::size_t i = 4; i < 8; ++i) {  // the refusals: all accepted
    EXPECT_FALSE(checks[i].passed) << checks[i].name;
    EXPECT_NE(checks[i].detail.find("accepted"), std::string::npos) << checks[i].detail;
  }
  EXPECT_EQ(passed(checks), 1);
}

TEST(FlightAdapter, ASilentAdapterFailsHelloAndNothingElseRuns) {
  FakeAdapter silent(std::nullopt);
  link::StreamRpcChannel channel(MessageStream::connect(silent.address(), 5.0), 200);
  const std::vector<AdapterCheck> checks = check_flight_adapter(channel);
  ASSERT_FALSE(checks.empty());
  EXPECT_EQ(passed(checks), 0);
  EXPECT_NE(checks[0].detail.find("did not answer"), std::string::npos) << checks[0].detail;
  for (std::size_t i = 1; i < checks.size(); ++i)
    EXPECT_EQ(checks[i].detail.rfind("not run", 0), 0u);
}

TEST(FlightAdapter, NothingListeningIsAnErrorNamingTheAddress) {
  MessageListener probe(link::parse_ipv4_address("127.0.0.1:0", "test", "listen", true), "test",
                        "listen");
  const link::Ipv4Address free{{127, 0, 0, 1}, probe.port()};
  probe = MessageListener(link::parse_ipv4_address("127.0.0.1:0", "test", "listen", true), "test",
                          "listen");
  try {
    (void)MessageStream::connect(free, 0.2);
    FAIL() << "connected to a closed port";
  } catch (const StreamError& e) {
    EXPECT_NE(std::string(e.what()).find(free.to_string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ferret
