// One process a robot (docs/robots.md, "One process a robot"): the world's process and
// the two robots' against it or on their hardware.
//   ferret sim-world [--world W] [--mission M] [--seed N] [--listen ADDR] [--link-loss F
//   --link-reorder F]
//       the simulated world, serving both robots' hardware and the link between them
//   ferret uav [--world W] [--mission M] [--seed N] [--sim-world ADDR | --link-bind A --link-peer A
//   --duration-s S] ferret ugv [--world W] [--mission M] [--seed N] [--sim-world ADDR | --link-bind
//   A --link-peer A --duration-s S]
//       the UAV's and the miniUGV's mission controllers, each in its process, against
//       the hardware interfaces the robots have: served by `ferret sim-world` when the
//       mission YAML's backends are sim, the robot's own devices when they are hw
//       (robots_on_hardware.cpp)
// The three read the same world, robots and mission YAML; with the same seed the run ends
// as `ferret mission --link messages` does.

#include "ferret/mission/robot_processes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ferret/core/clock.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/transition_log.hpp"
#include "ferret/link/ip_address.hpp"
#include "ferret/link/message_stream.hpp"
#include "ferret/mission/mission_assembly.hpp"
#include "ferret/mission/mission_setup.hpp"
#include "ferret/mission/robot_records.hpp"
#include "ferret/mission/robots_on_hardware.hpp"
#include "ferret/sim/sensor_sim.hpp"
#include "ferret/sim/sim_world_server.hpp"
#include "ferret/sim/ugv_mission_run.hpp"
#include "ferret/uav/adapter_flight_controller.hpp"
#include "ferret/uav/linked_ugv.hpp"
#include "ferret/uav/remote_winch.hpp"
#include "ferret/uav/uav_mission.hpp"
#include "ferret/ugv/mini_ugv_mission.hpp"
#include "ferret/ugv/remote_ugv_base.hpp"
#include "ferret/ugv/ugv_link_endpoint.hpp"

namespace ferret {
namespace {

using link::MessageStream;
using link::StreamError;
using link::StreamMessage;
using nlohmann::json;

constexpr int kReplyTimeoutMs = 60'000;

std::string dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

// The options of one mode given in the other are a mistake worth naming.
void check_mode_options(const RobotProcessOptions& o, bool on_hardware) {
  if (on_hardware && o.sim_world_given)
    throw InputError("--sim-world", "",
                     "no --sim-world: the mission YAML's backends are hw (the robot's own loop)",
                     o.address);
  if (on_hardware) {
    if (!(std::isfinite(o.duration_s) && o.duration_s >= 0.0 && o.duration_s <= 1e6))
      throw InputError("--duration-s", "", "seconds in [0, 1e6] (0: until done or interrupted)",
                       fmt::format("{}", o.duration_s));
    return;
  }
  for (const auto& [option, given] : {std::pair{"--link-bind", !o.link_bind.empty()},
                                      std::pair{"--link-peer", !o.link_peer.empty()},
                                      std::pair{"--duration-s", o.duration_s != 0.0}})
    if (given)
      throw InputError(option, "",
                       "only with hw backends (under ferret sim-world the world relays the link "
                       "and keeps the time)",
                       "given");
}

// The robot processes sim-world waits for, by the role each says in its hello.
enum class Robot { kUav, kUgv };
constexpr std::array<std::pair<std::string_view, Robot>, 2> kRoles{{
    {"uav", Robot::kUav},
    {"ugv", Robot::kUgv},
}};

RobotOnHardwareOptions hardware_options(const RobotProcessOptions& o) {
  return {o.setup.mission, o.link_bind, o.link_peer, o.duration_s, o.seed, o.quiet, o.out};
}

// What drives each interface of a robot served by sim-world, as its record says.
constexpr const char* kServed = "sim (served)";
constexpr const char* kRelayed = "messages (relayed)";

// --- sim-world ---------------------------------------------------------------------

}  // namespace

void run_sim_world_process(const RobotProcessOptions& o) {
  check_record_target(o.out);
  for (const auto& [option, value] :
       {std::pair{"--link-loss", o.link_loss}, std::pair{"--link-reorder", o.link_reorder}})
    if (!(std::isfinite(value) && value >= 0.0 && value <= 0.9))
      throw InputError(option, "", "a fraction of the datagrams in [0, 0.9]",
                       fmt::format("{}", value));
  const link::Ipv4Address address = link::parse_ipv4_address(o.address, "--listen", "", true);
  MissionSetup setup = load_mission_setup(o.setup);
  MissionRunSettings& settings = setup.settings;
  settings.render_markerless_frames = o.render_every_frame;
  link::LossyChannelOptions channel;
  channel.drop_fraction = o.link_loss;
  channel.reorder_fraction = o.link_reorder;
  settings.link_channel = channel;

  link::MessageListener listener(address, "--listen", "");
  std::fprintf(stderr, "sim-world: %s, seed %llu, listening on %s for the uav and ugv processes\n",
               setup.world_path.string().c_str(), static_cast<unsigned long long>(o.seed),
               link::Ipv4Address{address.ip, listener.port()}.to_string().c_str());
  std::optional<MessageStream> uav, ugv;
  while (!uav || !ugv) {
    std::optional<MessageStream> s = listener.accept(1000);
    if (!s) continue;
    std::optional<StreamMessage> hello;
    try {
      hello = s->receive(10'000);
    } catch (const StreamError&) {
      continue;
    }
    const json h = hello ? json::parse(hello->header, nullptr, false) : json();
    const std::string role = h.is_object() && h.contains("role") && h["role"].is_string()
                                 ? h["role"].get<std::string>()
                                 : "";
    const bool ours = h.is_object() && h.value("op", "") == "robot_hello" &&
                      h.value("protocol", 0) == kSimWorldProtocol;
    // The role read once: which process's slot the stream fills.
    const auto it =
        std::find_if(kRoles.begin(), kRoles.end(), [&](const auto& r) { return r.first == role; });
    std::optional<MessageStream>* slot =
        it == kRoles.end() ? nullptr : (it->second == Robot::kUav ? &uav : &ugv);
    if (!ours || slot == nullptr || slot->has_value()) {
      s->send(
          dump({{"ok", false},
                {"error", "expected robot_hello of protocol " + std::to_string(kSimWorldProtocol) +
                              " with role uav or ugv, each once"}}));
      continue;
    }
    s->send(dump({{"ok", true}, {"protocol", kSimWorldProtocol}, {"seed", o.seed}}));
    std::fprintf(stderr, "sim-world: %s process at %s\n", role.c_str(), s->peer().c_str());
    *slot = std::move(s);
  }
  TransitionLog log;
  const SimWorldReport r =
      run_sim_world(setup.world, setup.uav, settings, o.seed, *uav, *ugv, log, kReplyTimeoutMs);
  const MissionRunResult& t = r.truth;
  std::printf(
      "time_s: %.1f\nobjects_dropped: %d of %d\nflown_m: %.1f\nbattery_left: %.3f\ntether_max_m: "
      "%.2f\n"
      "tether_over_tension_events: %d\nuav_collisions: %d\nlink: %s\n",
      t.time_s, t.objects_dropped, t.objects_in_world, t.flown_m, t.battery_left, t.max_released_m,
      t.over_tension_events, t.uav_collisions, t.link_counters.c_str());
  for (const UgvDeployment& d : t.deployments)
    std::printf("  miniUGV in %s: %.1f m driven, battery %.2f%s\n",
                d.hidden_space.empty() ? "(none)" : d.hidden_space.c_str(), d.result.path_m,
                d.result.battery_left, d.result.object_held ? ", holding the object" : "");
  std::printf("uav: %s\nugv: %s\n", r.uav_summary.c_str(), r.ugv_summary.c_str());
  RunOutputsInput record = robot_side(RunSide::kWorld, o.seed, r.lost_peer);
  record.world = &setup.world;
  record.robot_summaries = {{"uav", r.uav_summary}, {"ugv", r.ugv_summary}};
  MissionRunResult truth = t;
  truth.transitions = log.all();
  write_robot_record(o.out, record, setup, truth);
  if (!r.lost_peer.empty()) throw StreamError(r.lost_peer);
}

namespace {

// --- the robots' lockstep loop -------------------------------------------------------

// Connects to sim-world and says which robot this is.
link::StreamRpcChannel connect_to_world(const RobotProcessOptions& o, const std::string& role) {
  const link::Ipv4Address address = link::parse_ipv4_address(o.address, "--sim-world", "", false);
  link::StreamRpcChannel channel(MessageStream::connect(address, 30.0), kReplyTimeoutMs);
  const json hello = json::parse(
      channel.call(dump({{"op", "robot_hello"}, {"role", role}, {"protocol", kSimWorldProtocol}}))
          .header,
      nullptr, false);
  if (!hello.is_object() || !hello.value("ok", false))
    throw StreamError("sim-world at " + o.address + " refused the " + role + " process: " +
                      (hello.is_object() ? hello.value("error", std::string("no reason given"))
                                         : "not a JSON reply"));
  if (hello.value("seed", o.seed) != o.seed)
    std::fprintf(stderr, "%s: sim-world runs seed %llu, this process %llu\n", role.c_str(),
                 static_cast<unsigned long long>(hello.value("seed", o.seed)),
                 static_cast<unsigned long long>(o.seed));
  return channel;
}

// Waits for sim-world's next lockstep message (it may be building its world first).
std::pair<json, StreamMessage> next_step(MessageStream& stream) {
  for (;;) {
    std::optional<StreamMessage> m = stream.receive(1000);
    if (!m) continue;
    json j = json::parse(m->header, nullptr, false);
    if (!j.is_object() || !j.contains("op") || !j["op"].is_string())
      throw StreamError("sim-world sent a message without an 'op'");
    return {std::move(j), std::move(*m)};
  }
}

// The ops sim-world steps each robot with (sim/sim_world_server.hpp), parsed where they
// arrive: the loops switch on them.
enum class UavStep { kStart, kTick, kLink, kEnd };
enum class UgvStep { kStart, kStep, kReport, kEnd };
constexpr std::array<std::pair<std::string_view, UavStep>, 4> kUavSteps{{
    {"start", UavStep::kStart},
    {"tick", UavStep::kTick},
    {"link", UavStep::kLink},
    {"end", UavStep::kEnd},
}};
constexpr std::array<std::pair<std::string_view, UgvStep>, 4> kUgvSteps{{
    {"start", UgvStep::kStart},
    {"step", UgvStep::kStep},
    {"report", UgvStep::kReport},
    {"end", UgvStep::kEnd},
}};

// The step `j` ("op") asks `robot` for; an op not in `steps` is sim-world's mistake.
template <class Step, std::size_t N>
Step step_of(const json& j, const std::array<std::pair<std::string_view, Step>, N>& steps,
             const std::string& robot) {
  const std::string op = j["op"].get<std::string>();
  const auto it = std::find_if(steps.begin(), steps.end(),
                               [&](const auto& entry) { return entry.first == op; });
  if (it == steps.end())
    throw StreamError("sim-world sent the " + robot + " an op it does not know: '" + printable(op) +
                      "'");
  return it->second;
}

double time_of(const json& j) {
  if (!j.contains("t_s") || !j["t_s"].is_number() || !std::isfinite(j["t_s"].get<double>()))
    throw StreamError("sim-world's '" + j["op"].get<std::string>() + "' has no time 't_s'");
  return j["t_s"].get<double>();
}

// --- uav -----------------------------------------------------------------------------

// The miniUGV over the robot link, as the UAV's mission sees it, with what lowering and
// lifting it does done by the simulated world (on the robot: the winch and gravity).
class SimWorldUgvLink final : public UgvLink {
 public:
  SimWorldUgvLink(LinkedUgv& linked, link::RpcChannel& world) : linked_(linked), world_(world) {}
  void deploy(const Eigen::Vector3d& p_WE, double entry_yaw_rad) override {
    effect({{"op", "ugv_put_down"},
            {"p_WE", {p_WE.x(), p_WE.y(), p_WE.z()}},
            {"entry_yaw_rad", entry_yaw_rad}});
    linked_.deploy(p_WE, entry_yaw_rad);
  }
  void retracted() override {
    linked_.retracted();
    effect({{"op", "ugv_lift"}});
  }
  void release_object() override {
    effect({{"op", "ugv_release"}});
    linked_.release_object();
  }
  void abort(const std::string& reason) override { linked_.abort(reason); }
  void recall(const std::string& reason) override { linked_.recall(reason); }
  [[nodiscard]] UgvReport report() const override {
    return lonely_ ? UgvReport::nothing_to_search() : linked_.report();
  }
  void set_lonely(bool lonely) { lonely_ = lonely; }

 private:
  void effect(const json& request) {
    const json r = json::parse(world_.call(dump(request)).header, nullptr, false);
    if (!r.is_object() || !r.value("ok", false))
      throw StreamError(
          "sim-world refused '" + request["op"].get<std::string>() + "': " +
          (r.is_object() ? r.value("error", std::string("no reason given")) : "not a JSON reply"));
    lonely_ = r.value("lonely", false);
  }
  LinkedUgv& linked_;
  link::RpcChannel& world_;
  bool lonely_ = false;
};

}  // namespace

void run_uav_process(const RobotProcessOptions& o) {
  check_record_target(o.out);
  const MissionSetup setup = load_mission_setup(o.setup);
  const bool on_hardware = uav_on_hardware(setup, o.setup.mission);
  check_mode_options(o, on_hardware);
  if (on_hardware) return run_uav_on_hardware(setup, hardware_options(o));
  (void)link::parse_ipv4_address(o.address, "--sim-world", "", false);
  require_all_sim(setup.backends, o.setup.mission,
                  "ferret uav under ferret sim-world: every interface simulated; all of the UAV's "
                  "hw for its own loop");
  const MissionAssembly assembly(setup.world, setup.uav, setup.settings, o.seed,
                                 o.setup.mission.empty() ? "(built-in defaults)" : o.setup.mission);

  if (!o.quiet)  // the log's first line: what drives each interface
    std::fprintf(
        stderr,
        "backends: %s; served by sim-world at %s: uav.flight_controller (flight adapter protocol), "
        "uav.cameras, uav.winch; link: relayed by sim-world\n",
        setup.backends.summary().c_str(), o.address.c_str());
  link::StreamRpcChannel channel = connect_to_world(o, "uav");
  RemoteWinch winch(channel);
  SimClock clock;
  LinkedUgv linked(clock);
  SimWorldUgvLink ugv(linked, channel);
  TransitionLog log;
  print_transitions(log, o.quiet);
  // Requests go out only inside a lockstep step (between sim-world's message and this
  // process's answer), so the adapter's greeting waits for "start".
  std::optional<AdapterFlightController> flight;
  std::optional<UavRunRecorder> recorder;  // the UAV's own record, from "start"
  std::unique_ptr<UavMission> started;
  const auto mission_or_throw = [&]() -> UavMission& {
    if (!started) throw StreamError("sim-world stepped the UAV before its 'start'");
    return *started;
  };
  const auto state = [&] {
    const UavMission& mission = mission_or_throw();
    return json{{"state", std::string(to_string(mission.state()))}, {"done", mission.done()}};
  };
  const auto write_record = [&](const std::string& ended_early) {
    MissionRunResult r =
        recorder ? recorder->result(started.get(), clock.now_s(), log) : MissionRunResult{};
    r.backends = {{"uav.flight_controller", kServed},
                  {"uav.cameras", kServed},
                  {"uav.winch", kServed},
                  {"link", kRelayed}};
    r.link_counters = linked.session().counters().summary();
    write_robot_record(o.out, robot_side(RunSide::kUav, o.seed, ended_early), setup, r);
  };
  MessageStream& stream = channel.stream();
  recording_failures(
      [&] {
        for (;;) {
          auto [j, m] = next_step(stream);
          switch (step_of(j, kUavSteps, "UAV")) {
            case UavStep::kStart: {
              flight.emplace(channel, "sim");
              recorder.emplace(*flight, winch);
              started = assembly.uav_mission({recorder->flight(), *flight, recorder->winch(), ugv},
                                             clock, &log);
              started->start();
              json r = state();
              r["op"] = "start_done";
              stream.send(dump(r));
              break;
            }
            case UavStep::kTick: {
              clock.set(time_of(j));
              ugv.set_lonely(j.value("lonely", false));
              mission_or_throw().tick();
              recorder->after_tick(clock.now_s(), *started);
              json r = state();
              r["op"] = "tick_done";
              stream.send(dump(r));
              break;
            }
            case UavStep::kLink:
              clock.set(time_of(j));
              for (const auto& d : link::unpack_datagrams(m.blob)) linked.session().receive(d);
              stream.send(StreamMessage{R"({"op":"link_done"})",
                                        link::pack_datagrams(linked.session().take_outgoing())});
              break;
            case UavStep::kEnd: {
              clock.set(time_of(j));
              UavMission& mission = mission_or_throw();
              if (!mission.done()) mission.stop("the simulation's time limit");
              const int retrieved = print_uav_outcome(mission, clock.now_s());
              json visits = json::array();
              for (const HiddenSpaceVisit& v : mission.visits())
                visits.push_back({{"marker_id", v.marker_id},
                                  {"state", std::string(to_string(v.state))},
                                  {"landed", v.landed},
                                  {"ugv_outcome", v.ugv_outcome},
                                  {"object_retrieved", v.object_retrieved},
                                  {"object_dropped", v.object_dropped}});
              std::printf("link: UAV end: %s\n", linked.session().counters().summary().c_str());
              std::fflush(stdout);
              stream.send(dump({{"op", "end_done"},
                                {"outcome", std::string(to_string(mission.outcome()))},
                                {"hidden_spaces_found", mission.visits().size()},
                                {"objects_retrieved", retrieved},
                                {"visits", visits}}));
              write_record("");
              return;
            }
          }
        }
      },
      write_record);
}

// --- ugv -----------------------------------------------------------------------------

void run_ugv_process(const RobotProcessOptions& o) {
  check_record_target(o.out);
  const MissionSetup setup = load_mission_setup(o.setup);
  const bool on_hardware = ugv_on_hardware(setup);
  check_mode_options(o, on_hardware);
  if (on_hardware) return run_ugv_on_hardware(setup, hardware_options(o));
  (void)link::parse_ipv4_address(o.address, "--sim-world", "", false);
  require_all_sim(
      setup.backends, o.setup.mission,
      "ferret ugv under ferret sim-world: every interface simulated; ugv.base hw for its own loop");
  const UgvMissionRunSettings& settings = setup.settings.ugv;
  if (!o.quiet)
    std::fprintf(stderr,
                 "backends: %s; served by sim-world at %s: ugv.base (base protocol); link: relayed "
                 "by sim-world\n",
                 setup.backends.summary().c_str(), o.address.c_str());
  link::StreamRpcChannel channel = connect_to_world(o, "ugv");
  std::optional<RemoteUgvBase> base;  // greets the world's base at "start"
  SimClock clock;
  TransitionLog log;
  print_transitions(log, o.quiet);
  std::vector<std::unique_ptr<MiniUgvMission>> missions;
  UgvRunRecorder recorder;
  // A search request: the mission for where the winch set the robot down. On the robot
  // it starts where it stands; here the world says where that is, with the search's seed.
  UgvLinkEndpoint endpoint(clock, [&](const link::UavRequest&) -> UgvLinkEndpoint::Deployment {
    const json d = json::parse(channel.call(R"({"op":"ugv_deployment"})").header, nullptr, false);
    if (!d.is_object() || !d.value("ok", false))
      throw StreamError("sim-world did not say where the miniUGV is");
    if (!d.value("set_down", false)) return {};
    const json& s = d.at("start");
    const Pose2 start{s.at(0).get<double>(), s.at(1).get<double>(), s.at(2).get<double>()};
    const json& map = d.at("map");
    GridGeometry truth{map.at("origin_m").at(0).get<double>(),
                       map.at("origin_m").at(1).get<double>(), map.at("resolution_m").get<double>(),
                       map.at("cells").at(0).get<int>(), map.at("cells").at(1).get<int>()};
    const std::uint64_t seed = d.at("seed").get<std::uint64_t>();
    if (!base) throw StreamError("sim-world asked the miniUGV to search before its 'start'");
    missions.push_back(MissionAssembly::ugv_mission(
        settings, *base, clock, ugv_mission_map(truth, start, settings), seed, std::nullopt, &log));
    recorder.started(clock.now_s(), *missions.back());
    return {missions.back().get(), &*base};
  });
  const auto write_record = [&](const std::string& ended_early) {
    MissionRunResult r = recorder.result(clock.now_s(), log);
    r.backends = {{"ugv.base", kServed}, {"link", kRelayed}};
    r.link_counters = endpoint.session().counters().summary();
    write_robot_record(o.out, robot_side(RunSide::kUgv, o.seed, ended_early), setup, r);
  };
  MessageStream& stream = channel.stream();
  recording_failures(
      [&] {
        for (;;) {
          auto [j, m] = next_step(stream);
          switch (step_of(j, kUgvSteps, "miniUGV")) {
            case UgvStep::kStart:
              base.emplace(channel, "sim");
              stream.send(R"({"op":"start_done"})");
              break;
            case UgvStep::kStep: {
              clock.set(time_of(j));
              for (const auto& d : link::unpack_datagrams(m.blob)) endpoint.session().receive(d);
              const json& a = j.at("attitude_rad");
              endpoint.set_attitude(a.at(0).get<double>(), a.at(1).get<double>());
              const bool hold = endpoint.handle_requests();
              MiniUgvMission* mission = endpoint.mission();
              const bool set_down = j.value("set_down", false);
              // The world steps a base whose controller is done or waits to be lifted no more.
              const bool stopped =
                  set_down && mission && (mission->done() || mission->wants_retraction());
              if (set_down && !stopped && !hold && mission &&
                  mission->state() != UgvMissionState::kIdle)
                mission->tick();
              recorder.after_tick(clock.now_s());
              // Its state, for the world's fault plan (faults started by a state) and
              // invariants (each state within its timeout).
              const std::string state = !mission ? ""
                                        : hold   ? "link_hold"
                                                 : std::string(to_string(mission->state()));
              stream.send(dump(
                  {{"op", "step_done"}, {"hold", hold}, {"stopped", stopped}, {"state", state}}));
              break;
            }
            case UgvStep::kReport:
              clock.set(time_of(j));
              endpoint.report();
              stream.send(StreamMessage{R"({"op":"report_done"})",
                                        link::pack_datagrams(endpoint.session().take_outgoing())});
              break;
            case UgvStep::kEnd: {
              clock.set(time_of(j));
              json deployments = json::array();
              for (auto& mission : missions) {
                if (!mission->done()) mission->stop("the mission ended");
                std::printf("  miniUGV search: %s\n",
                            std::string(to_string(mission->outcome())).c_str());
                deployments.push_back(std::string(to_string(mission->outcome())));
              }
              std::printf("link: miniUGV end: %s\n",
                          endpoint.session().counters().summary().c_str());
              std::fflush(stdout);
              stream.send(dump({{"op", "end_done"}, {"searches", deployments}}));
              write_record("");
              return;
            }
          }
        }
      },
      write_record);
}

}  // namespace ferret
