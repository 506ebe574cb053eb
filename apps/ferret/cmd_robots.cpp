// One process a robot (docs/robots.md, "One process a robot"):
//   ferret sim-world [--world W] [--mission M] [--seed N] [-o DIR] [--listen ADDR] [--link-loss F
//   --link-reorder F]
//       the simulated world, serving both robots' hardware and the link between them
//   ferret uav [--world W] [--mission M] [--seed N] [--sim-world ADDR | --link-bind A --link-peer A
//   --duration-s S] ferret ugv [--world W] [--mission M] [--seed N] [--sim-world ADDR | --link-bind
//   A --link-peer A --duration-s S]
//       the UAV's and the miniUGV's mission controllers, each in its process
//       (mission/robot_processes.hpp)

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/link/message_stream.hpp"
#include "ferret/mission/robot_processes.hpp"

namespace ferret::cli {
namespace {

using Options = RobotProcessOptions;
using link::StreamError;

// A robot process or the world that loses its peer, or hears what it cannot follow, ends
// as a failed run (exit 1), not as an internal error.
template <class Run>
void failing_on_stream_errors(const Run& run, const Options& o) {
  try {
    run(o);
  } catch (const StreamError& e) {
    throw CheckFailed(e.what());
  } catch (const nlohmann::json::exception& e) {
    throw CheckFailed(std::string("a lockstep message without the fields it needs: ") + e.what());
  }
}

void add_common(CLI::App* sub, Options& o) {
  add_mission_setup_options(sub, o.setup);
  add_seed_option(sub, o.seed, "mission");
  sub->add_flag("-q,--quiet", o.quiet, "Print the summary only");
  sub->add_option("-o,--out", o.out,
                  "Directory for this process's record of the run: report.json and the pictures "
                  "and mission.mcap it has the data for (docs/robots.md) (default: none, summary "
                  "only)");
}

void add_robot_options(CLI::App* sub, Options& o, const std::string& own_port,
                       const std::string& peer_default) {
  sub->add_option("--sim-world", o.address,
                  "With sim backends: the ferret sim-world's address:port")
      ->capture_default_str();
  sub->add_option("--link-bind", o.link_bind,
                  "With hw backends: this robot's robot-link address:port (default: 127.0.0.1:" +
                      own_port + ")");
  sub->add_option(
      "--link-peer", o.link_peer,
      "With hw backends: the other robot's address:port (default: " + peer_default + ")");
  sub->add_option(
      "--duration-s", o.duration_s,
      "With hw backends: stop after this many seconds (default: when done, or at SIGINT/SIGTERM)");
}

}  // namespace

const CommandRegistration kSimWorld{
    "sim-world", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      auto* sub = app.add_subcommand(
          "sim-world", "Serve the simulated world to a ferret uav and a ferret ugv process");
      add_common(sub, *o);
      add_faults_option(sub, o->setup);
      sub->add_option("--listen", o->address, "Address:port to listen on (port 0: any free one)")
          ->capture_default_str();
      sub->add_option("--link-loss", o->link_loss,
                      "The fraction of the robot link's datagrams lost, each way (default: 0)");
      sub->add_option("--link-reorder", o->link_reorder,
                      "The fraction of the robot link's datagrams held back past later ones, each "
                      "way (default: 0)");
      sub->add_flag(
          "--render-every-frame", o->render_every_frame,
          "Render every marker frame, also those no marker's quad lies in (docs/mission.md)");
      sub->callback([o] { failing_on_stream_errors(run_sim_world_process, *o); });
    }};

const CommandRegistration kUav{
    "uav", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      auto* sub = app.add_subcommand("uav",
                                     "Run the UAV's mission controller: on its hardware (hw "
                                     "backends) or against ferret sim-world (sim)");
      add_common(sub, *o);
      add_robot_options(sub, *o, "47810", "the miniUGV's, 127.0.0.1:47811");
      sub->callback([o, sub] {
        o->sim_world_given = sub->count("--sim-world") > 0;
        failing_on_stream_errors(run_uav_process, *o);
      });
    }};

const CommandRegistration kUgv{"ugv", [](CLI::App& app) {
                                 auto o = std::make_shared<Options>();
                                 auto* sub = app.add_subcommand(
                                     "ugv",
                                     "Run the miniUGV's mission controller: on its hardware (hw "
                                     "backend) or against ferret sim-world (sim)");
                                 add_common(sub, *o);
                                 add_robot_options(sub, *o, "47811", "the UAV's, 127.0.0.1:47810");
                                 sub->callback([o, sub] {
                                   o->sim_world_given = sub->count("--sim-world") > 0;
                                   failing_on_stream_errors(run_ugv_process, *o);
                                 });
                               }};

}  // namespace ferret::cli
