#include "ferret/sim/sim_world_server.hpp"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "ferret/core/error.hpp"
#include "ferret/link/json_dispatcher.hpp"
#include "ferret/link/lossy_channel.hpp"
#include "ferret/sim/mission_world.hpp"
#include "ferret/uav/flight_adapter_service.hpp"
#include "ferret/uav/remote_winch.hpp"
#include "ferret/ugv/remote_ugv_base.hpp"

namespace ferret {
namespace {

using link::MessageStream;
using link::StreamError;
using link::StreamMessage;
using nlohmann::json;

std::string dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

// The miniUGV's base as the robot process reaches it: the deployment's under way, or the
// last one's (aboard, its link endpoint still reads the base's status).
class ActiveBase final : public UgvBase {
 public:
  explicit ActiveBase(internal::SimHiddenSpaces& spaces) : spaces_(spaces) {}
  std::string backend() const override { return "sim"; }
  Pose2 odometry() const override { return base().odometry(); }
  double speed_mps() const override { return base().speed_mps(); }
  RangeScan ir_scan() override { return base().ir_scan(); }
  CameraFrame camera_frame(double time_s) override { return base().camera_frame(time_s); }
  void command_velocity(double v_mps, double w_radps) override {
    base().command_velocity(v_mps, w_radps);
  }
  void set_epm(bool on) override { base().set_epm(on); }
  UgvStatus status() const override { return base().status(); }

 private:
  SimUgvBase& base() const {
    SimUgvBase* b = spaces_.last_base();
    if (!b) throw std::runtime_error("the miniUGV has not been set down yet");
    return *b;
  }
  internal::SimHiddenSpaces& spaces_;
};

bool flag_at(const json& j, const char* key) {
  if (!j.contains(key) || !j[key].is_boolean())
    throw std::runtime_error(std::string("'") + key + "': expected a boolean");
  return j[key].get<bool>();
}

// One lockstep exchange: `message` to the robot, then its hardware requests answered by
// `serve` until its reply to the message ("<op>_done") comes.
template <class Serve>
std::pair<json, std::vector<std::uint8_t>> exchange(MessageStream& robot, const std::string& role,
                                                    const json& message,
                                                    const std::vector<std::uint8_t>& blob,
                                                    int timeout_ms, Serve&& serve) {
  const std::string done = message.at("op").get<std::string>() + "_done";
  std::optional<StreamMessage> m;
  try {  // the stream's errors name the address; the run's, which robot that was
    robot.send(StreamMessage{dump(message), blob});
    for (;;) {
      m = robot.receive(timeout_ms);
      if (!m) break;
      json j = json::parse(m->header, nullptr, false);
      if (j.is_object() && j.contains("op") && j["op"] == done)
        return {std::move(j), std::move(m->blob)};
      robot.send(serve(*m));
    }
  } catch (const StreamError& e) {
    throw StreamError("lost the " + role + " process: " + e.what());
  }
  throw StreamError("the " + role + " process did not answer '" + done.substr(0, done.size() - 5) +
                    "' for " + std::to_string(timeout_ms / 1000) + " s");
}

}  // namespace

SimWorldReport run_sim_world(const PlanningWorld& world, const RobotDescription& uav_robot,
                             const MissionRunSettings& settings, std::uint64_t seed,
                             MessageStream& uav, MessageStream& ugv, TransitionLog& log,
                             int reply_timeout_ms) {
  internal::MissionWorld sim(world, uav_robot, settings, seed, log);
  internal::SimHiddenSpaces& spaces = sim.spaces();
  // The robot link's network, as `ferret mission --link messages` simulates it.
  const link::LossyChannelOptions channel =
      settings.link_channel.value_or(link::LossyChannelOptions{});
  const auto seeded = [&](std::uint64_t way) {
    link::LossyChannelOptions o = channel;
    o.seed = seed * 1000003u + way;
    return o;
  };
  link::LossyChannel up(seeded(1)), down(seeded(2));  // UAV -> miniUGV, miniUGV -> UAV

  // The UAV's hardware: the flight adapter's ops, the winch's, and what lowering and
  // lifting the miniUGV does to the world, on one connection.
  const auto lonely = [&] { return spaces.lonely() && !spaces.active(); };
  FlightAdapterService flight_service(
      sim.flight(), sim.cameras(), "sim",
      FlightAdapterService::Hooks{[&](const Eigen::Vector3d& v_W, double yaw_rate_radps) {
        sim.flight().command_velocity(v_W, yaw_rate_radps);
      }});
  link::JsonDispatcher& uav_ops = flight_service.dispatcher();
  add_winch_ops(uav_ops, sim.winch());
  const auto set_down_reply = [&]() -> link::JsonReply { return json{{"lonely", lonely()}}; };
  uav_ops.add("ugv_put_down", [&](const link::JsonRequest& r) -> link::JsonReply {
    const json& j = r.fields;
    if (!j.contains("p_WE") || !j["p_WE"].is_array() || j["p_WE"].size() != 3)
      throw std::runtime_error("'p_WE': expected an array of 3 numbers");
    spaces.put_down(
        {j["p_WE"][0].get<double>(), j["p_WE"][1].get<double>(), j["p_WE"][2].get<double>()},
        false);
    return set_down_reply();
  });
  uav_ops.add("ugv_lift", [&](const link::JsonRequest&) {
    (void)spaces.lift();
    return set_down_reply();
  });
  uav_ops.add("ugv_release", [&](const link::JsonRequest&) {
    spaces.release_object();
    return set_down_reply();
  });
  // The miniUGV's: its base, and where it was set down.
  ActiveBase active_base(spaces);
  UgvBaseService base_service(active_base, "sim");
  base_service.dispatcher().add("ugv_deployment", [&](const link::JsonRequest&) -> link::JsonReply {
    if (!spaces.active()) return json{{"set_down", false}};
    const Pose2& p = spaces.start_pose();
    const GridGeometry& g = spaces.truth_geometry();
    return json{{"set_down", true},
                {"start", {p.x_m, p.y_m, p.yaw_rad}},
                {"seed", spaces.deployment_seed()},
                {"map",
                 {{"origin_m", {g.origin_x_m, g.origin_y_m}},
                  {"resolution_m", g.resolution_m},
                  {"cells", {g.width, g.height}}}}};
  });
  const auto serve_uav = [&](const StreamMessage& m) { return flight_service.handle(m); };
  const auto serve_ugv = [&](const StreamMessage& m) { return base_service.handle(m); };

  // A robot lost (StreamError) ends the run where it is; the world's truth up to then is
  // still reported (SimWorldReport::lost_peer).
  std::string lost_peer;
  const auto guarded = [&](const auto& exchanges) {
    if (!lost_peer.empty()) return;
    try {
      exchanges();
    } catch (const StreamError& e) {
      lost_peer = e.what();
    }
  };
  std::string uav_state;
  bool uav_done = false, ugv_stopped = false;
  const auto uav_said = [&](const json& j) {
    if (!j.contains("state") || !j["state"].is_string())
      throw StreamError("the UAV process's reply has no 'state'");
    uav_state = j["state"].get<std::string>();
    uav_done = flag_at(j, "done");
  };
  guarded([&] {
    uav_said(exchange(uav, "UAV", {{"op", "start"}}, {}, reply_timeout_ms, serve_uav).first);
    (void)exchange(ugv, "miniUGV", {{"op", "start"}}, {}, reply_timeout_ms, serve_ugv);
  });

  internal::MissionControllers controllers;
  controllers.uav_tick = [&] {
    guarded([&] {
      uav_said(exchange(uav, "UAV",
                        {{"op", "tick"}, {"t_s", sim.clock().now_s()}, {"lonely", lonely()}}, {},
                        reply_timeout_ms, serve_uav)
                   .first);
    });
  };
  controllers.uav_done = [&] { return uav_done || !lost_peer.empty(); };
  controllers.uav_state = [&] { return uav_state; };
  controllers.ugv_tick = [] {};
  controllers.ugv_stopped = [&] { return ugv_stopped; };
  std::string ugv_state;
  controllers.ugv_state = [&] { return ugv_state; };
  // The fault plan's link faults on the network between the robots, as in one process.
  const double delivery_s = 1.0 / settings.ugv.exploration.sensors.ir_rate_hz;
  controllers.link_receive = [&] {
    // Set down, the robot stands level; hanging or aboard, its IMU reads where it would
    // touch down (the UAV's check while it lowers).
    const ImuReading& hanging = spaces.touchdown();
    const bool set_down = spaces.active() != nullptr;
    const json step{
        {"op", "step"},
        {"t_s", sim.clock().now_s()},
        {"set_down", set_down},
        {"attitude_rad",
         set_down ? json::array({0.0, 0.0}) : json::array({hanging.roll_rad, hanging.pitch_rad})}};
    bool hold = false;
    if (const FaultSchedule* faults = sim.faults()) {
      up.set_impairment(faults->link_impairment(FaultTarget::kUavToUgv, delivery_s));
      down.set_impairment(faults->link_impairment(FaultTarget::kUgvToUav, delivery_s));
    }
    guarded([&] {
      const auto [r, blob] = exchange(ugv, "miniUGV", step, link::pack_datagrams(up.deliver()),
                                      reply_timeout_ms, serve_ugv);
      ugv_stopped = flag_at(r, "stopped");
      hold = flag_at(r, "hold");
      ugv_state = r.value("state", std::string());
    });
    return hold;
  };
  controllers.link_send = [&] {
    guarded([&] {
      const auto [r, sent] =
          exchange(ugv, "miniUGV", {{"op", "report"}, {"t_s", sim.clock().now_s()}}, {},
                   reply_timeout_ms, serve_ugv);
      down.send(link::unpack_datagrams(sent));
      const auto [r2, reply] =
          exchange(uav, "UAV", {{"op", "link"}, {"t_s", sim.clock().now_s()}},
                   link::pack_datagrams(down.deliver()), reply_timeout_ms, serve_uav);
      up.send(link::unpack_datagrams(reply));
    });
  };
  sim.run(controllers, {});
  const json end{{"op", "end"}, {"t_s", sim.clock().now_s()}};
  SimWorldReport report;
  guarded([&] {
    report.uav_summary = dump(exchange(uav, "UAV", end, {}, reply_timeout_ms, serve_uav).first);
    report.ugv_summary = dump(exchange(ugv, "miniUGV", end, {}, reply_timeout_ms, serve_ugv).first);
  });
  report.lost_peer = lost_peer;
  spaces.close();
  report.truth = std::move(sim.result());
  report.truth.deployments = std::move(spaces.deployments());
  report.truth.backends = {{"uav.flight_controller", "sim (served)"},
                           {"uav.cameras", "sim (served)"},
                           {"uav.winch", "sim (served)"},
                           {"ugv.base", "sim (served)"},
                           {"link", "messages (relayed)"}};
  report.truth.link_counters =
      "UAV -> miniUGV: " + std::to_string(up.counters().delivered) +
      " delivered; miniUGV -> UAV: " + std::to_string(down.counters().delivered) + " delivered";
  return report;
}

}  // namespace ferret
