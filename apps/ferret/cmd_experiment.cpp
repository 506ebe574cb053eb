// `ferret experiment CONFIG.yaml -o DIR [--jobs N] [--shard I/N]`: the paper's
// exploration experiment (mission/experiment.hpp). Writes runs.csv, summary.csv and the
// sweep CSVs into DIR, then draws the plots with examples/plot_experiment.py when it
// can find it (unsharded runs only: shards are merged first, see docs/object_search.md).

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/data_path.hpp"
#include "ferret/core/error.hpp"
#include "ferret/mission/experiment.hpp"
#include "ferret/planning/exploration_policy.hpp"

namespace ferret::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::string config, out, shard = "0/1", plot_script;
  int jobs = 1;
  bool no_plots = false, quiet = false, shard_given = false;
  std::string planner =
      "grid";  // FrontierPlanner: "ompl" runs cdos and rapid as cdos+ompl, rapid+ompl
};

std::string format_duration(double s) {
  char buf[32];
  if (s >= 3600)
    std::snprintf(buf, sizeof buf, "%dh%02dm", static_cast<int>(s / 3600),
                  static_cast<int>(s / 60) % 60);
  else if (s >= 60)
    std::snprintf(buf, sizeof buf, "%dm%02ds", static_cast<int>(s / 60), static_cast<int>(s) % 60);
  else
    std::snprintf(buf, sizeof buf, "%.0fs", s);
  return buf;
}

fs::path find_plot_script(const Options& o) {
  if (!o.plot_script.empty()) return o.plot_script;
  if (const char* env = std::getenv("FERRET_PLOT_SCRIPT")) return env;
  // The script of the ferret this binary belongs to (installed, or the source tree of
  // a build), wherever the experiment config lies.
  try {
    return data_path("plot_experiment.py");
  } catch (const InputError&) {
    return {};
  }
}

// Draws the plots into the output set's staging directory, so they appear with the CSVs.
// A failed script is a warning: its partial plots are removed, the CSVs still appear.
// Returns the plots drawn.
std::vector<std::string> draw_plots(const fs::path& script, const fs::path& staging) {
  std::set<fs::path> before;
  for (const auto& e : fs::directory_iterator(staging)) before.insert(e.path());
  // Debian's python3 has python3-matplotlib; a python3 earlier on PATH (pyenv, venv) may not.
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  // Its stdout would name the staging directory: the command lists the plots instead.
  const std::string cmd = python + " '" + script.string() + "' '" + staging.string() + "'";
  const bool ok = std::system((cmd + " >/dev/null").c_str()) == 0;
  std::vector<std::string> drawn;
  for (const auto& e : fs::directory_iterator(staging)) {
    if (before.count(e.path()) != 0) continue;
    if (ok) {
      drawn.push_back(e.path().filename().string());
    } else {
      std::error_code ec;
      fs::remove_all(e.path(), ec);
    }
  }
  if (!ok)
    std::fprintf(stderr,
                 "ferret: warning: plotting failed (%s DIR); no plots written, the CSVs are "
                 "complete\n",
                 (python + " " + script.string()).c_str());
  std::sort(drawn.begin(), drawn.end());
  return drawn;
}

constexpr int kMaxJobs = 256;

void run(const Options& o) {
  const fs::path out = checked_out_dir(o.out, "an output directory");
  const auto [shard_index, shard_count] = parse_shard(o.shard, o.shard_given);
  // A bound, so that a typo (--jobs 100000) is an error and not a machine brought down.
  if (o.jobs < 1 || o.jobs > kMaxJobs)
    throw InputError("--jobs", "", fmt::format("a number of worker threads in [1, {}]", kMaxJobs),
                     std::to_string(o.jobs));
  ExperimentConfig config = load_experiment_config(o.config);
  // Each method as the frontier planner runs it (cdos: cdos+ompl), or an InputError
  // naming the method the planner does not serve.
  const FrontierPlanner planner = parse_frontier_planner(o.planner, "--planner");
  for (auto* list : {&config.methods, &config.sweep_methods})
    for (auto& m : *list) m = exploration_policy_for(m, planner);

  ExperimentOptions eo;
  eo.jobs = o.jobs;
  eo.shard_index = shard_index;
  eo.shard_count = shard_count;
  const auto t0 = std::chrono::steady_clock::now();
  auto last = t0 - std::chrono::seconds(10);
  if (!o.quiet)
    eo.progress = [&](std::size_t done, std::size_t total) {
      const auto now = std::chrono::steady_clock::now();
      if (done != total && now - last < std::chrono::milliseconds(500)) return;
      last = now;
      const double elapsed = std::chrono::duration<double>(now - t0).count();
      const double rate = elapsed > 0 ? done / elapsed : 0.0;
      const double left = rate > 0 ? (total - done) / rate : 0.0;
      std::fprintf(stderr, "\r%zu/%zu runs, %.1f runs/s, %s left   ", done, total, rate,
                   format_duration(left).c_str());
      if (done == total) std::fprintf(stderr, "\n");
      std::fflush(stderr);
    };
  fs::path script;
  if (!o.no_plots && shard_count == 1) {
    script = find_plot_script(o);
    if (script.empty())
      std::fprintf(stderr,
                   "ferret: warning: examples/plot_experiment.py not found; no plots drawn\n");
  }
  std::vector<std::string> plots;
  if (!script.empty())
    eo.before_commit = [&](const fs::path& staging) { plots = draw_plots(script, staging); };
  run_experiment(config, out, eo);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("wrote %s (runs.csv, summary.csv%s%s) in %s\n", o.out.c_str(),
              config.sweep_camera_fov_deg.empty() ? "" : ", sweep_camera_fov.csv",
              config.sweep_ir_fov_deg.empty() ? "" : ", sweep_ir_fov.csv",
              format_duration(elapsed).c_str());

  if (!plots.empty()) {
    std::string list;
    for (const auto& p : plots) list += " " + p;
    std::printf("plotted:%s\n", list.c_str());
  }
}

const CommandRegistration kExperiment{
    "experiment", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      auto* sub = app.add_subcommand(
          "experiment", "Run the object-search experiment of a config (CDOS vs. baselines)");
      sub->add_option("config", o->config, "Experiment YAML (docs/object_search.md)")->required();
      add_out_option(sub, o->out, "Output directory");
      sub->add_option("--jobs", o->jobs, "Worker threads")->capture_default_str();
      sub->add_option("--planner", o->planner,
                      "grid, or ompl: cdos and rapid with the OMPL frontier sampler")
          ->capture_default_str();
      sub->add_option("--shard", o->shard,
                      "Run slice I of N (groups g with g % N == I; default: the Slurm job "
                      "array's task, else 0/1)")
          ->capture_default_str();
      sub->add_option("--plot-script", o->plot_script,
                      "Plot script (default: the installed plot_experiment.py, data_path())");
      sub->add_flag("--no-plots", o->no_plots, "Write the CSVs only");
      sub->add_flag("--quiet", o->quiet, "No progress line");
      sub->callback([o, sub] {
        o->shard_given = sub->count("--shard") > 0;
        run(*o);
      });
    }};

}  // namespace
}  // namespace ferret::cli
