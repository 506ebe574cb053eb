// `ferret flight-adapter`: the flight adapter protocol from the command line
// (docs/flight_adapter.md).
//   ferret flight-adapter serve --listen 127.0.0.1:47820 [--world W] [--robot URDF] ...
//       the reference adapter over the simulated M100, until interrupted (or --clients)
//   ferret flight-adapter check --adapter 192.168.1.10:47820
//       the ground checks against an adapter (a DJI one on the vehicle): nothing flies
// A bad address is bad input (exit 2); an adapter that does not answer or fails a check
// is a failed check (exit 1).

#include <cstdio>
#include <memory>
#include <string>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/data_path.hpp"
#include "ferret/core/error.hpp"
#include "ferret/link/message_stream.hpp"
#include "ferret/mission/mission_settings.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/sim/mission_run.hpp"
#include "ferret/sim/sim_flight_adapter.hpp"
#include "ferret/uav/flight_adapter_check.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::cli {
namespace {

struct Options {
  std::string listen = "127.0.0.1:47820";
  std::string world, robot, mission;
  std::uint64_t seed = 1;
  int clients = 0;
  bool real_time = false;
  std::string adapter;
  int timeout_ms = 2000;
};

void serve(const Options& o) {
  const link::Ipv4Address address = link::parse_ipv4_address(o.listen, "--listen", "", true);
  if (o.clients < 0)
    throw InputError("--clients", "", "a count >= 0 (0: serve until interrupted)",
                     std::to_string(o.clients));
  const MissionConfig mission = load_mission_or_defaults(o.mission);
  const RobotDescription uav = load_robot_description(resolve_robot(o.robot, "m100.urdf"), mission);
  const RobotDescription ugv = load_robot_description(data_path("models/miniugv.urdf"), mission);
  const PlanningWorld world = load_planning_world(o.world.empty() ? data_path("worlds/default.yaml")
                                                                  : std::filesystem::path(o.world));
  if (!world.spec)
    throw InputError(world.source.string(), "",
                     "a world YAML (an OctoMap file has no home or hidden spaces)");
  const MissionRunSettings settings = mission_settings_for(uav, ugv, mission, *world.spec);
  link::MessageListener listener(address, "--listen", "");
  SimFlightAdapter adapter(world, uav, settings, o.seed);
  std::fprintf(stderr, "flight adapter: reference (sim) adapter, protocol 1, listening on %s\n",
               link::Ipv4Address{address.ip, listener.port()}.to_string().c_str());
  for (int served = 0; o.clients == 0 || served < o.clients;) {
    auto stream = listener.accept(1000);
    if (!stream) continue;
    std::fprintf(stderr, "flight adapter: client %s\n", stream->peer().c_str());
    if (o.real_time)
      adapter.serve_in_real_time(*stream, [] { return true; });
    else
      adapter.serve(*stream, [] { return true; });
    std::fprintf(stderr, "flight adapter: client %s left at t = %.2f s\n", stream->peer().c_str(),
                 adapter.now_s());
    ++served;
  }
}

void check(const Options& o) {
  const link::Ipv4Address address = link::parse_ipv4_address(o.adapter, "--adapter");
  if (o.timeout_ms <= 0)
    throw InputError("--timeout-ms", "", "a reply timeout > 0", std::to_string(o.timeout_ms));
  std::unique_ptr<link::StreamRpcChannel> channel;
  try {
    channel = std::make_unique<link::StreamRpcChannel>(link::MessageStream::connect(address, 2.0),
                                                       o.timeout_ms);
  } catch (const link::StreamError& e) {
    throw CheckFailed(std::string("no flight adapter: ") + e.what());
  }
  int passed = 0;
  const std::vector<AdapterCheck> checks = check_flight_adapter(*channel);
  for (const AdapterCheck& c : checks) {
    std::printf("%s %s: %s\n", c.passed ? "PASS" : "FAIL", c.name.c_str(), c.detail.c_str());
    passed += c.passed ? 1 : 0;
  }
  std::printf("%d of %zu checks passed\n", passed, checks.size());
  if (passed != static_cast<int>(checks.size())) set_exit_code(1);
}

const CommandRegistration kFlightAdapter{
    "flight-adapter", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      auto* cmd =
          app.add_subcommand("flight-adapter", "Serve or check the flight adapter protocol");
      cmd->require_subcommand(1);
      auto* s = cmd->add_subcommand("serve", "Serve the reference adapter over the simulated M100");
      s->add_option("--listen", o->listen, "Address:port to listen on (port 0: any free one)")
          ->capture_default_str();
      s->add_option("--world", o->world, "World YAML (default: the shipped default world)");
      s->add_option("--robot", o->robot, "The UAV's URDF (default: the shipped m100)");
      s->add_option("--mission", o->mission, "Mission YAML (default: the built-in defaults)");
      add_seed_option(s, o->seed, "simulated cameras");
      s->add_option("--clients", o->clients,
                    "Clients to serve one after another, then exit (0: until interrupted)")
          ->capture_default_str();
      s->add_flag("--real-time", o->real_time,
                  "The vehicle moves by itself in wall time, as a real one (for ferret uav on hw "
                  "backends); "
                  "without it, only sim_advance moves it");
      s->callback([o] { serve(*o); });
      auto* c = cmd->add_subcommand("check",
                                    "Ground checks of an adapter: hello, state, frames, refusals");
      c->add_option("--adapter", o->adapter, "The adapter's address:port")->required();
      c->add_option("--timeout-ms", o->timeout_ms, "Reply timeout, milliseconds")
          ->capture_default_str();
      c->callback([o] { check(*o); });
    }};

}  // namespace
}  // namespace ferret::cli
