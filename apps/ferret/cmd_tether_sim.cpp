// `ferret tether-sim`: a miniUGV trajectory through the tether model and the winch
// controller in closed loop.
//   ferret tether-sim [--trajectory FILE] [--controller mpc|baseline] [--seed N]
//                     [--mission FILE] [--sim-config FILE] [--horizon N] [--latency S] -o DIR
// Prints slack RMS, maximum slack, over-tension events and the time the tether limit
// was active; writes DIR/tether_<controller>.csv, .png (l_t, required length and
// slack over time) and .json (the figures). docs/tether.md describes the files.

#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/sim/tether_sim.hpp"
#include "ferret/tether_model/winch_controllers.hpp"

namespace ferret::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::string trajectory, controller = "mpc", out, mission, config;
  std::uint64_t seed = 1;
  std::optional<int> horizon;
  std::optional<double> latency_s;
};

void run(const Options& o) {
  tether::tether_controllers().check(o.controller, "--controller");
  const fs::path out = checked_out_dir(o.out, "the output directory");
  if (o.horizon && (*o.horizon < 2 || *o.horizon > 200))
    throw InputError("--horizon", "", "an integer in [2, 200]", std::to_string(*o.horizon));
  if (o.latency_s && !(*o.latency_s >= 0.0 && *o.latency_s <= 1.0))
    throw InputError("--latency", "", "seconds in [0, 1]", std::to_string(*o.latency_s));
  // All input is read and checked before anything is written.
  const MissionConfig mission = load_mission_or_defaults(o.mission);
  const sim::TetherScenario scenario = o.trajectory.empty()
                                           ? sim::default_tether_scenario()
                                           : sim::load_tether_scenario(o.trajectory);
  auto config = sim::TetherRunConfig::for_tether(mission.tether.total_length_m,
                                                 mission.tether.entry_offset_m);
  config.sim.control.ugv_max_speed_mps = mission.ugv_limits.max_velocity_mps;
  config.mpc.control = config.baseline.control = config.sim.control;
  if (!o.config.empty()) sim::apply_tether_run_config(o.config, config);
  if (o.horizon) config.mpc.horizon = *o.horizon;
  if (o.latency_s) config.sim.link_latency_s = *o.latency_s;
  config.sim.seed = o.seed;

  auto& options = config.sim;
  auto model = std::make_shared<tether::FixedWrapTether>(options.entry_offset_m, scenario.p_WE,
                                                         scenario.wrap_points);
  const std::unique_ptr<tether::TetherController> controller = tether::tether_controllers().make(
      o.controller, {options.control, {config.mpc, config.baseline}, model}, "--controller");
  // The MPC reports its QP fallbacks and the response it identified.
  const auto* mpc_controller = dynamic_cast<const tether::TautTetherMpc*>(controller.get());
  const sim::TetherSimResult r = sim::run_tether_sim(scenario, options, *controller);
  const auto& m = r.metrics;
  const auto& c = options.control;
  std::printf("scenario: %s\ncontroller: %s\nseed: %llu\nduration_s: %.2f\n", r.scenario.c_str(),
              r.controller.c_str(), static_cast<unsigned long long>(o.seed), m.duration_s);
  std::printf(
      "slack_rms_m: %.5f\nreachable_slack_rms_m: %.5f\nmax_slack_m: %.5f\nmin_slack_m: %.5f\n",
      m.slack_rms_m, m.reachable_slack_rms_m, m.max_slack_m, m.min_slack_m);
  std::printf(
      "over_tension_events: %d\nover_tension_time_s: %.3f\nmax_tension_n: %.2f (limit %.1f)\n",
      m.over_tension_events, m.over_tension_time_s, m.max_tension_n,
      c.slack_estimator.tension.max_tension_n);
  std::printf("tether_limit_active_s: %.2f\nmax_released_m: %.3f (L = %.2f)\ncycles_above_L: %d\n",
              m.limit_active_s, m.max_released_m, c.limits.total_length_m, m.released_over_limit);
  if (mpc_controller) std::printf("mpc_fallback_cycles: %d\n", mpc_controller->fallback_count());
  // The miniUGV's response as the MPC identified it by the end of the run.
  const auto& identifier = mpc_controller ? mpc_controller->estimator().response_identifier
                                          : std::optional<tether::UgvResponseIdentifier>();
  if (identifier)
    std::printf("identified_ugv_velocity_lag_s: %.2f\nidentified_ugv_tracking_time_s: %.2f\n",
                identifier->best().velocity_lag_s, identifier->best().tracking_time_s);
  std::printf("step_time_median_us: %.1f\nstep_time_max_us: %.1f\n", m.step_time_median_us,
              m.step_time_max_us);

  const std::string stem = "tether_" + o.controller;
  OutputSet files(out, OutputKind::kDirectory);  // CSV, plot and JSON: all or none
  sim::write_tether_sim_csv(r, files.path(stem + ".csv"));
  sim::write_tether_sim_plot(r, c.max_slack_m, c.limits.total_length_m, files.path(stem + ".png"));
  nlohmann::json j;
  j["scenario"] = r.scenario;
  j["trajectory"] = o.trajectory.empty() ? "(built-in default)" : o.trajectory;
  j["controller"] = r.controller;
  j["seed"] = o.seed;
  j["config"] = o.config.empty() ? nlohmann::json() : nlohmann::json(o.config);
  j["horizon"] = mpc_controller ? nlohmann::json(config.mpc.horizon) : nlohmann::json();
  j["link_latency_s"] = options.link_latency_s;
  j["ugv_velocity_lag_s"] = options.ugv_velocity_lag_s;
  j["ugv_slip_noise_mps"] = options.ugv_slip_noise_mps;
  j["total_length_m"] = c.limits.total_length_m;
  j["entry_offset_m"] = options.entry_offset_m;
  j["metrics"] = {{"slack_rms_m", m.slack_rms_m},
                  {"reachable_slack_rms_m", m.reachable_slack_rms_m},
                  {"max_slack_m", m.max_slack_m},
                  {"min_slack_m", m.min_slack_m},
                  {"over_tension_events", m.over_tension_events},
                  {"over_tension_time_s", m.over_tension_time_s},
                  {"max_tension_n", m.max_tension_n},
                  {"tether_limit_active_s", m.limit_active_s},
                  {"max_released_m", m.max_released_m},
                  {"cycles_above_L", m.released_over_limit},
                  {"duration_s", m.duration_s},
                  {"control_cycles", m.control_cycles}};
  if (mpc_controller) j["metrics"]["mpc_fallback_cycles"] = mpc_controller->fallback_count();
  if (identifier)
    j["identified_ugv_response"] = {{"velocity_lag_s", identifier->best().velocity_lag_s},
                                    {"tracking_time_s", identifier->best().tracking_time_s}};
  files.write_text(stem + ".json", j.dump(2) + "\n");
  files.commit();
}

const CommandRegistration kTetherSim{
    "tether-sim", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      auto* sub = app.add_subcommand(
          "tether-sim", "Run a miniUGV trajectory through the tether model and winch controller");
      sub->add_option("--trajectory", o->trajectory,
                      "trajectory CSV or YAML (default: the built-in scripted one)");
      sub->add_option("--controller", o->controller,
                      tether::tether_controllers().expected() + " (winch controllers)")
          ->capture_default_str();
      add_seed_option(sub, o->seed, "seed of the sensor noise");
      add_out_option(sub, o->out, "output directory (created)");
      sub->add_option("--mission", o->mission,
                      "mission YAML with tether.total_length_m (L) and entry_offset_m (l_0) "
                      "(default: the built-in values)");
      sub->add_option(
          "--sim-config", o->config,
          "YAML with controller and simulation settings, docs/tether.md (default: none, "
          "the built-in values)");
      add_hidden_alias(sub, "--config", o->config);
      sub->add_option("--horizon", o->horizon,
                      "MPC horizon in prediction steps (default 20 of 0.02 s)");
      sub->add_option("--latency", o->latency_s,
                      "link latency of the miniUGV's pose, seconds (default 0.06)");
      sub->callback([o] { run(*o); });
    }};

}  // namespace
}  // namespace ferret::cli
