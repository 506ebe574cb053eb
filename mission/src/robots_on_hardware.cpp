#include "ferret/mission/robots_on_hardware.hpp"

#include <fmt/format.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "ferret/core/clock.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"
#include "ferret/core/transition_log.hpp"
#include "ferret/link/message_stream.hpp"
#include "ferret/link/udp_link.hpp"
#include "ferret/mission/mission_assembly.hpp"
#include "ferret/mission/robot_loop.hpp"
#include "ferret/mission/robot_records.hpp"
#include "ferret/sim/sensor_sim.hpp"
#include "ferret/sim/ugv_mission_run.hpp"
#include "ferret/tether_model/dynamixel_bus.hpp"
#include "ferret/tether_model/winch_factory.hpp"
#include "ferret/uav/flight_controller_config.hpp"
#include "ferret/uav/linked_ugv.hpp"
#include "ferret/uav/uav_mission.hpp"
#include "ferret/ugv/anchored_ugv_base.hpp"
#include "ferret/ugv/hw_ugv_base.hpp"
#include "ferret/ugv/mini_ugv_mission.hpp"
#include "ferret/ugv/ugv_base_factory.hpp"
#include "ferret/ugv/ugv_link_endpoint.hpp"

namespace ferret {
namespace {

constexpr double kUgvPeriodS = 0.05;  // the miniUGV's control and telemetry rate, 20 Hz
constexpr double kUavPeriodS = 0.02;  // the UAV's and the winch's control, 50 Hz
constexpr int kAdapterReplyTimeoutMs = 2000;

link::UdpLink open_link(const RobotOnHardwareOptions& o, std::string_view bind,
                        std::string_view peer) {
  link::UdpLinkOptions u;
  u.bind = o.link_bind.empty() ? std::string(bind) : o.link_bind;
  u.peer = o.link_peer.empty() ? std::string(peer) : o.link_peer;
  return link::UdpLink(u);
}

// Sends what the session has to send; a failed send is the lossy link's business.
void send_outgoing(link::UdpLink& udp, link::LinkSession& session) {
  for (const auto& datagram : session.take_outgoing()) (void)udp.send(datagram);
}

void receive_waiting(link::UdpLink& udp, link::LinkSession& session) {
  while (auto d = udp.receive(0)) session.receive(d->bytes);
}

// A device the file names that is not there is the file's mistake (exit 2, the field
// named); one that is there but silent or not what it should be fails the run (exit 1).
std::unique_ptr<UgvBase> bring_up_ugv_base(const MissionSetup& setup,
                                           const std::string& mission_path) {
  try {
    return ugv::make_ugv_base(setup.backends.ugv_base,
                              {setup.ugv, setup.mission.object_search, {}});
  } catch (const ugv::HwUgvError& e) {
    if (e.kind() == ugv::HwUgvError::Kind::kSerialMissing)
      throw InputError(mission_path, "ugv.base.serial.port", "a serial port that can be opened",
                       e.what());
    if (e.kind() == ugv::HwUgvError::Kind::kCameraMissing)
      throw InputError(mission_path, "ugv.base.camera.device", "a camera that can be opened",
                       e.what());
    throw CheckFailed(std::string("miniUGV bring-up: ") + e.what());
  }
}

std::unique_ptr<tether::Winch> bring_up_winch(const MissionSetup& setup,
                                              const std::string& mission_path) {
  try {
    return tether::make_winch(setup.backends.winch);
  } catch (const tether::DynamixelError& e) {
    throw CheckFailed(std::string("winch bring-up: ") + e.what());
  } catch (const tether::SerialError& e) {
    throw InputError(mission_path, "uav.winch.serial.port", "a serial port that can be opened",
                     e.what());
  }
}

}  // namespace

void print_transitions(TransitionLog& log, bool quiet) {
  log.on_transition([quiet](const Transition& t) {
    if (!quiet) std::fprintf(stderr, "%s\n", TransitionLog::format(t).c_str());
  });
}

int print_uav_outcome(const UavMission& mission, double time_s) {
  int retrieved = 0, dropped = 0;
  for (const HiddenSpaceVisit& v : mission.visits()) {
    retrieved += v.object_retrieved ? 1 : 0;
    dropped += v.object_dropped ? 1 : 0;
  }
  std::printf(
      "outcome: %s\ntime_s: %.1f\nhidden_spaces_found: %zu\nobjects_retrieved: "
      "%d\nobjects_dropped: %d\n",
      std::string(to_string(mission.outcome())).c_str(), time_s, mission.visits().size(), retrieved,
      dropped);
  for (const HiddenSpaceVisit& v : mission.visits())
    std::printf("  marker %d: %s%s, miniUGV %s%s\n", v.marker_id,
                std::string(to_string(v.state)).c_str(),
                v.state == VisitState::kServiced ? (v.landed ? " (landed)" : " (hovered)") : "",
                v.ugv_outcome.empty() ? "-" : v.ugv_outcome.c_str(),
                v.object_dropped ? ", object dropped" : "");
  return retrieved;
}

bool ugv_on_hardware(const MissionSetup& setup) { return !setup.backends.ugv_base.simulated(); }

bool uav_on_hardware(const MissionSetup& setup, const std::string& mission_path) {
  const bool winch_hw = !setup.backends.winch.simulated();
  const bool flight_hw = !setup.backends.flight_controller.simulated();
  if (winch_hw != flight_hw)
    throw InputError(
        mission_path, winch_hw ? "uav.flight_controller.backend" : "uav.winch.backend",
        "hw, as the other UAV interface (the UAV's own loop drives only hardware; ferret sim-world "
        "serves the simulated ones, all of them)",
        "sim");
  return winch_hw;
}

// --- miniUGV -------------------------------------------------------------------------

void run_ugv_on_hardware(const MissionSetup& setup, const RobotOnHardwareOptions& o) {
  const UgvMissionRunSettings& settings = setup.settings.ugv;
  if (!settings.map_window_m)
    throw std::logic_error("run_ugv_on_hardware: settings without the map window");
  const Eigen::Vector2d window_m = *settings.map_window_m;
  const double resolution_m = setup.world.tree->getResolution();
  link::UdpLink udp = open_link(o, link::kDefaultUgvAddress, link::kDefaultUavAddress);
  if (!o.quiet)
    std::fprintf(stderr, "backends: %s; link: UDP %s, the UAV at %s\n",
                 setup.backends.summary().c_str(), udp.local_address().to_string().c_str(),
                 udp.peer()->to_string().c_str());

  // Brings the robot up (throws HwUgvError naming the device that is missing or wrong).
  const std::unique_ptr<UgvBase> hw = bring_up_ugv_base(setup, o.mission_path);
  const auto* hw_base = dynamic_cast<const ugv::HwUgvBase*>(hw.get());
  if (!o.quiet && hw_base) std::fprintf(stderr, "ugv: base up: %s\n", hw_base->diagnosis().c_str());
  ugv::AnchoredUgvBase base(*hw);

  SteadyClock clock;
  TransitionLog log;
  print_transitions(log, o.quiet);
  std::vector<std::unique_ptr<MiniUgvMission>> missions;
  UgvRunRecorder recorder;
  // A search request: the mission from where the robot stands, which is where the winch
  // set it down: the request's entry E, heading into the space. Its map is the window
  // of the settings around E at the world's resolution (nothing of the space is known).
  UgvLinkEndpoint endpoint(clock, [&](const link::UavRequest& r) -> UgvLinkEndpoint::Deployment {
    const Pose2 entry{r.entry_x_m, r.entry_y_m, r.entry_yaw_rad};
    base.anchor(entry);
    const GridGeometry map =
        GridGeometry::centred_on(entry.position(), window_m.x(), window_m.y(), resolution_m);
    const std::uint64_t seed =
        derive_seed(o.seed, {static_cast<std::uint64_t>(missions.size() + 1)});
    missions.push_back(
        MissionAssembly::ugv_mission(settings, base, clock, map, seed, std::nullopt, &log));
    recorder.started(clock.now_s(), *missions.back());
    if (!o.quiet)
      std::fprintf(stderr,
                   "ugv: search %zu from (%.2f, %.2f) heading %.0f deg, a %.1f x %.1f m map\n",
                   missions.size(), entry.x_m, entry.y_m, entry.yaw_rad * 180.0 / std::numbers::pi,
                   window_m.x(), window_m.y());
    return {missions.back().get(), &base};
  });

  const PeriodicLoopResult loop = run_periodic(kUgvPeriodS, o.duration_s, [&] {
    receive_waiting(udp, endpoint.session());
    if (hw_base)
      if (const auto state = hw_base->telemetry().state)  // the IMU, for the UAV's touchdown check
        endpoint.set_attitude(state->roll_cdeg * std::numbers::pi / 18000.0,
                              state->pitch_cdeg * std::numbers::pi / 18000.0);
    const bool hold = endpoint.handle_requests();  // holding: the wheels were set to 0
    MiniUgvMission* mission = endpoint.mission();
    if (!hold && mission && mission->state() != UgvMissionState::kIdle && !mission->done() &&
        !mission->wants_retraction())
      mission->tick();
    recorder.after_tick(clock.now_s());
    endpoint.report();
    send_outgoing(udp, endpoint.session());
    return true;
  });
  base.command_velocity(0.0, 0.0);
  // The miniUGV runs until stopped: a search it had to cut short is what ended early.
  const bool cut_short =
      std::any_of(missions.begin(), missions.end(), [](const auto& m) { return !m->done(); });
  for (auto& mission : missions)
    if (!mission->done()) mission->stop("the process ended (" + loop.why_stopped + ")");

  for (std::size_t k = 0; k < missions.size(); ++k)
    std::printf("  miniUGV search %zu: %s\n", k + 1,
                std::string(to_string(missions[k]->outcome())).c_str());
  std::printf("searches: %zu\nholds: %llu\nlink: miniUGV end: %s\nloop: %s\n", missions.size(),
              static_cast<unsigned long long>(endpoint.holds()),
              endpoint.session().counters().summary().c_str(), loop.summary(kUgvPeriodS).c_str());
  if (hw_base) std::printf("base: %s\n", hw_base->diagnosis().c_str());
  std::fflush(stdout);
  MissionRunResult r = recorder.result(clock.now_s(), log);
  r.backends = {{"ugv.base", setup.backends.ugv_base.simulated() ? "sim" : "hw"}, {"link", "udp"}};
  r.link_counters = endpoint.session().counters().summary();
  write_robot_record(
      o.out,
      robot_side(RunSide::kUgv, o.seed,
                 cut_short ? "the process ended (" + loop.why_stopped + ") in a search" : ""),
      setup, r);
}

// --- UAV -----------------------------------------------------------------------------

void run_uav_on_hardware(const MissionSetup& setup, const RobotOnHardwareOptions& o) {
  const MissionAssembly assembly(setup.world, setup.uav, setup.settings, o.seed, o.mission_path);
  link::UdpLink udp = open_link(o, link::kDefaultUavAddress, link::kDefaultUgvAddress);
  const std::string& adapter_address = setup.backends.flight_controller.address;
  if (!o.quiet)
    std::fprintf(stderr, "backends: %s; link: UDP %s, the miniUGV at %s\n",
                 setup.backends.summary().c_str(), udp.local_address().to_string().c_str(),
                 udp.peer()->to_string().c_str());

  // Connects to the servo (throws SerialError / DynamixelError naming the port).
  const std::unique_ptr<tether::Winch> winch = bring_up_winch(setup, o.mission_path);
  if (!o.quiet)
    std::fprintf(stderr, "uav: winch up: l_t = %.3f m\n", winch->read_state().released_m);

  const std::unique_ptr<FlightBackend> vehicle =
      make_flight_backend(setup.backends.flight_controller, {}, kAdapterReplyTimeoutMs);
  UavRunRecorder recorder(vehicle->flight(), *winch);
  if (!o.quiet)
    std::fprintf(stderr, "uav: flight adapter '%s' at %s\n", vehicle->peer_name().c_str(),
                 adapter_address.c_str());
  SteadyClock clock;
  LinkedUgv ugv(clock);
  TransitionLog log;
  print_transitions(log, o.quiet);
  const std::unique_ptr<UavMission> uav = assembly.uav_mission(
      {recorder.flight(), vehicle->cameras(), recorder.winch(), ugv}, clock, &log);
  UavMission& mission = *uav;
  const auto write_record = [&](const std::string& ended_early) {
    MissionRunResult r = recorder.result(&mission, clock.now_s(), log);
    r.backends = {{"uav.flight_controller", vehicle->flight().backend()},
                  {"uav.cameras", "hw"},
                  {"uav.winch", "hw"},
                  {"link", "udp"}};
    r.link_counters = ugv.session().counters().summary();
    write_robot_record(o.out, robot_side(RunSide::kUav, o.seed, ended_early), setup, r);
  };
  PeriodicLoopResult loop;
  recording_failures(
      [&] {
        mission.start();
        loop = run_periodic(kUavPeriodS, o.duration_s, [&] {
          receive_waiting(udp, ugv.session());
          mission.tick();
          recorder.after_tick(clock.now_s(), mission);
          send_outgoing(udp, ugv.session());
          return !mission.done();
        });
      },
      write_record);
  std::string ended_early;
  if (!mission.done()) {
    ended_early = "the process ended (" + loop.why_stopped + ")";
    mission.stop(ended_early);
  }
  winch->command_velocity_mps(0.0);  // hold the tether's length; the servo keeps its torque
  // Tell the miniUGV, once, if a search was under way (the link is lossy: best effort).
  send_outgoing(udp, ugv.session());

  (void)print_uav_outcome(mission, clock.now_s());
  std::printf("link: UAV end: %s\nloop: %s\n", ugv.session().counters().summary().c_str(),
              loop.summary(kUavPeriodS).c_str());
  std::fflush(stdout);
  write_record(ended_early);
}

}  // namespace ferret
