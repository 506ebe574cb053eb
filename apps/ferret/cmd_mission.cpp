// `ferret mission`: the whole mission in the simulated world (docs/mission.md): the
// UAV searches, finds the marked openings, lands (or hovers) beside each, lowers the
// miniUGV, which searches the hidden space and brings the object out, and the UAV drops
// it in the drop zone and searches on.
//   ferret mission [--world W.yaml] [--robot-uav URDF] [--robot-ugv URDF]
//                  [--mission M.yaml] [--seed N] [--out DIR]
// Prints the transitions as they happen (simulated time) and a progress line a
// simulated minute on stderr, then a summary on stdout; --out writes report.json, the figures,
// map.bt and mission.mcap.

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/mission/mission_outputs.hpp"
#include "ferret/mission/mission_run.hpp"
#include "ferret/mission/mission_settings.hpp"
#include "ferret/mission/mission_setup.hpp"
#include "ferret/sim/mission_run.hpp"
#include "ferret/sim/robot_backends.hpp"

namespace ferret::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  MissionSetupOptions setup;
  std::string out;
  std::string link = "in-process";
  double link_loss = 0.0, link_reorder = 0.0;
  std::uint64_t seed = 1;
  bool quiet = false;
  bool render_every_frame = false;
};

void run(const Options& o) {
  if (o.link != "in-process" && o.link != "messages")
    throw InputError("--link", "", "in-process or messages", o.link);
  for (const auto& [option, value] :
       {std::pair{"--link-loss", o.link_loss}, std::pair{"--link-reorder", o.link_reorder}}) {
    if (!(std::isfinite(value) && value >= 0.0 && value <= 0.9))
      throw InputError(option, "", "a fraction of the datagrams in [0, 0.9]",
                       fmt::format("{}", value));
    if (value > 0.0 && o.link != "messages")
      throw InputError(option, "", "--link messages (in one process there are no messages to lose)",
                       fmt::format("{}", value));
  }
  if (!o.out.empty()) (void)check_output_target(o.out, OutputKind::kDirectory, "--out");
  MissionSetup setup = load_mission_setup(o.setup);
  require_all_sim(setup.backends, o.setup.mission,
                  "ferret mission runs both robots in its own simulator");
  const fs::path& world_path = setup.world_path;
  const MissionConfig& mission = setup.mission;
  const RobotBackends& backends = setup.backends;
  const RobotDescription& uav = setup.uav;
  const PlanningWorld& world = setup.world;
  MissionRunSettings& settings = setup.settings;
  settings.render_markerless_frames = o.render_every_frame;
  if (o.link == "messages") {
    link::LossyChannelOptions channel;
    channel.drop_fraction = o.link_loss;
    channel.reorder_fraction = o.link_reorder;
    settings.link_channel = channel;
  }

  // What the mission YAML asked for (all sim here), and what the run itself uses
  // besides: the rendered cameras and the miniUGV's link inside this process.
  if (!o.quiet) {
    std::string line = "backends: " + backends.summary();
    for (const auto& [name, backend] : mission_backends())
      if (name == "uav.cameras") line += ", " + name + ": " + backend;
    line += ", link: " +
            (o.link == "messages"
                 ? fmt::format("messages (loss {:g}, reordering {:g})", o.link_loss, o.link_reorder)
                 : o.link);
    std::fprintf(stderr, "%s\n", line.c_str());
  }
  TransitionLog log;
  double next_progress_s = 60.0;
  log.on_transition([&](const Transition& t) {
    if (o.quiet) return;
    std::fprintf(stderr, "%s\n", TransitionLog::format(t).c_str());
  });
  settings.on_sample = [&](double t_s, const MissionSim& m) {
    if (o.quiet || t_s < next_progress_s) return;
    next_progress_s += 60.0;
    const FlightState s = m.uav_truth();
    std::fprintf(stderr,
                 "  [%6.0f s] uav %s at (%.1f, %.1f, %.1f), battery %.0f %%, l_t %.2f m, %zu/%zu "
                 "waypoints\n",
                 t_s, std::string(to_string(m.uav().state())).c_str(), s.p_W.x(), s.p_W.y(),
                 s.p_W.z(), 100 * s.battery_fraction, m.released_m(), m.uav().pattern_done(),
                 m.uav().pattern().size());
  };
  const MissionRunResult r = run_mission(world, uav, settings, o.seed, &log);

  print_mission_summary(r);
  if (o.out.empty()) return;
  write_mission_outputs(
      fs::path(o.out), {world, world_path, o.seed, settings.uav, mission.tether.total_length_m}, r);
  std::printf(
      "wrote: %s (report.json, aerial.png, tether.png, battery.png, spaces/*/G.png O.png G_O.png, "
      "map.bt, mission.mcap)\n",
      o.out.c_str());
}

}  // namespace

const CommandRegistration kMission{
    "mission", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      auto* sub =
          app.add_subcommand("mission", "Simulate the whole mission: search, land, retrieve, drop");
      add_mission_setup_options(sub, o->setup);
      add_faults_option(sub, o->setup);
      add_seed_option(sub, o->seed, "mission");
      sub->add_option("-o,--out", o->out,
                      "Directory for report.json, aerial.png, tether.png, battery.png, spaces/*/, "
                      "map.bt, mission.mcap (default: none, summary only)");
      sub->add_option("--link", o->link,
                      "How the UAV and the miniUGV talk: in-process (calls) or messages (the robot "
                      "link's frames and "
                      "sessions through a simulated network, docs/link.md) (default: in-process)");
      sub->add_option(
          "--link-loss", o->link_loss,
          "With --link messages: the fraction of datagrams lost, each way (default: 0)");
      sub->add_option("--link-reorder", o->link_reorder,
                      "With --link messages: the fraction of datagrams held back past later ones, "
                      "each way (default: 0)");
      sub->add_flag("--render-every-frame", o->render_every_frame,
                    "Render and search every marker frame, also those no marker's quad lies in "
                    "(default: such "
                    "frames reach the mission empty; docs/mission.md)");
      sub->add_flag("-q,--quiet", o->quiet, "Print the summary only");
      sub->callback([o] { run(*o); });
    }};

}  // namespace ferret::cli
