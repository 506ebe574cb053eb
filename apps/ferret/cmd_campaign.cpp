// `ferret campaign --runs N --seed S [--jobs J] [--shard I/N] -o DIR`: N simulated
// missions, each with a random mix of faults, each in a process of its own (a crash or
// a hang is caught and counted, and no run's state leaks into the next), classed by how
// they ended (mission/campaign.hpp, docs/safety.md "Campaigns").
// `ferret campaign merge -o DIR SHARD_DIR...`: the shards' campaign.csv merged into the
// unsharded run's, byte for byte.

#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli_options.hpp"
#include "command.hpp"
#include "ferret/core/data_path.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/output_set.hpp"
#include "ferret/mission/campaign.hpp"
#include "ferret/sim/fault_plan.hpp"

extern char** environ;

namespace ferret::cli {
namespace {

namespace fs = std::filesystem;

struct Options {
  std::size_t runs = 100;
  std::uint64_t seed = 1;
  int jobs = 2;
  std::string shard = "0/1", out;
  double run_timeout_s = 900.0;
  int min_faults = 1, max_faults = 4;
  bool shard_given = false, quiet = false;
  std::vector<std::string> worlds;
  // merge
  std::vector<std::string> shard_dirs;
};

constexpr int kMaxJobs = 256;
constexpr std::size_t kMaxRuns = 1'000'000;

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// One run's process: `ferret mission` on its world, seed and faults, its outputs in
// `dir`; stdout and stderr kept beside them.
struct Child {
  CampaignRun run;
  fs::path dir;
  pid_t pid = -1;
  std::chrono::steady_clock::time_point started;
};

pid_t spawn_mission(const CampaignRun& run, const fs::path& dir) {
  const std::string self = fs::read_symlink("/proc/self/exe").string();
  const std::vector<std::string> args = {self,
                                         "mission",
                                         "--world",
                                         run.world,
                                         "--seed",
                                         std::to_string(run.seed),
                                         "--faults",
                                         (dir / "faults.yaml").string(),
                                         "-q",
                                         "-o",
                                         (dir / "out").string()};
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, (dir / "stdout.txt").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, (dir / "stderr.txt").c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, self.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("campaign: could not start " + self);
  return pid;
}

// The run's class from its report; its outputs but the report removed (they are
// replayed with the command, not kept by the thousand).
CampaignResult collect(const Child& c, int status) {
  const fs::path report = c.dir / "out" / "report.json";
  CampaignResult r;
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(report)) {
    try {
      r = classify_campaign_run(c.run, nlohmann::json::parse(read_text(report)), report.string());
      fs::copy_file(report, c.dir / "report.json", fs::copy_options::overwrite_existing);
    } catch (const std::exception& e) {  // a run that wrote no readable report failed
      r = failed_campaign_run(c.run, std::string("crash: an unreadable report: ") + e.what());
    }
  } else if (WIFSIGNALED(status)) {
    r = failed_campaign_run(c.run, fmt::format("crash: signal {}", WTERMSIG(status)));
  } else {
    r = failed_campaign_run(c.run, fmt::format("crash: exit {}", WEXITSTATUS(status)));
  }
  std::error_code ec;
  fs::remove_all(c.dir / "out", ec);
  return r;
}

// The replay command's fault file, relative to the campaign's directory (the same in a
// shard, the unsharded campaign and the merge, which gathers the shards' runs/).
std::string run_faults_path(std::size_t index) {
  return (fs::path("runs") / fmt::format("{:06}", index) / "faults.yaml").string();
}

std::vector<std::string> default_worlds() {
  return {data_path("worlds/default.yaml").string(), data_path("worlds/two_sites.yaml").string(),
          data_path("worlds/small.yaml").string()};
}

void run(const Options& o) {
  const fs::path out = checked_out_dir(o.out, "an output directory");
  if (o.runs < 1 || o.runs > kMaxRuns)
    throw InputError("--runs", "", fmt::format("a number of missions in [1, {}]", kMaxRuns),
                     std::to_string(o.runs));
  if (o.jobs < 1 || o.jobs > kMaxJobs)
    throw InputError("--jobs", "", fmt::format("a number of processes in [1, {}]", kMaxJobs),
                     std::to_string(o.jobs));
  if (!(o.run_timeout_s >= 10.0 && o.run_timeout_s <= 86400.0))
    throw InputError("--run-timeout-s", "", "seconds in [10, 86400]",
                     fmt::format("{}", o.run_timeout_s));
  if (o.min_faults < 0 || o.max_faults < o.min_faults || o.max_faults > 16)
    throw InputError("--min-faults, --max-faults", "", "0 <= --min-faults <= --max-faults <= 16",
                     fmt::format("{} and {}", o.min_faults, o.max_faults));
  const auto [shard_index, shard_count] = parse_shard(o.shard, o.shard_given);
  CampaignOptions co;
  co.runs = o.runs;
  co.seed = o.seed;
  co.worlds = o.worlds.empty() ? default_worlds() : o.worlds;
  for (std::string& w : co.worlds) {
    if (!fs::is_regular_file(w)) throw InputError("--world", "", "a world YAML file", w);
    // Absolute, so that each run's replay command works from the campaign's directory
    // (and names the same file in every shard of a job array on a shared file system).
    w = fs::weakly_canonical(w).string();
  }
  co.draw.min_faults = o.min_faults;
  co.draw.max_faults = o.max_faults;
  co.draw.horizon_s = 600.0;  // within the shipped worlds' shortest mission
  const std::vector<CampaignRun> runs = plan_campaign(co, static_cast<std::size_t>(shard_index),
                                                      static_cast<std::size_t>(shard_count));

  OutputSet set(out, OutputKind::kDirectory);
  std::vector<CampaignResult> results;
  std::vector<Child> running;
  std::size_t next = 0, done = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const auto finish = [&](const Child& c, CampaignResult r) {
    ++done;
    if (!o.quiet) {
      const double wall_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - c.started).count();
      std::fprintf(stderr, "[%zu/%zu] run %zu %s seed %llu, %zu faults: %s%s%s (%.0f s)\n", done,
                   runs.size(), c.run.index, fs::path(c.run.world).stem().c_str(),
                   static_cast<unsigned long long>(c.run.seed), c.run.faults.faults.size(),
                   std::string(to_string(r.outcome)).c_str(), r.note.empty() ? "" : ": ",
                   r.note.c_str(), wall_s);
    }
    results.push_back(std::move(r));
  };
  while (next < runs.size() || !running.empty()) {
    while (next < runs.size() && running.size() < static_cast<std::size_t>(o.jobs)) {
      const CampaignRun& r = runs[next++];
      const fs::path dir = set.staging_dir() / "runs" / fmt::format("{:06}", r.index);
      fs::create_directories(dir);
      std::ofstream(dir / "faults.yaml") << fault_plan_to_yaml(r.faults);
      running.push_back({r, dir, spawn_mission(r, dir), std::chrono::steady_clock::now()});
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    for (auto it = running.begin(); it != running.end();) {
      int status = 0;
      const pid_t p = waitpid(it->pid, &status, WNOHANG);
      const double age_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - it->started).count();
      if (p == it->pid) {
        finish(*it, collect(*it, status));
        it = running.erase(it);
      } else if (age_s > o.run_timeout_s) {
        kill(it->pid, SIGKILL);
        waitpid(it->pid, &status, 0);
        finish(*it, failed_campaign_run(
                        it->run, fmt::format("hang: over {:.0f} s of wall time", o.run_timeout_s)));
        std::error_code ec;
        fs::remove_all(it->dir / "out", ec);
        it = running.erase(it);
      } else {
        ++it;
      }
    }
  }
  std::sort(results.begin(), results.end(),
            [](const auto& a, const auto& b) { return a.run.index < b.run.index; });
  std::string csv = campaign_csv_header();
  for (const CampaignResult& r : results)
    csv += campaign_csv_row(r, campaign_replay_command(r.run, run_faults_path(r.run.index)));
  const std::string verdict = campaign_verdict(csv);
  set.write_text("campaign.csv", csv);
  set.write_text("verdict.txt", verdict + "\n");
  set.commit();
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%s\nwrote %s (campaign.csv, verdict.txt, runs/) in %.0f s\n", verdict.c_str(),
              o.out.c_str(), wall_s);
  if (!campaign_passed(csv)) set_exit_code(1);
}

void merge(const Options& o) {
  const fs::path out = checked_out_dir(o.out, "an output directory");
  std::vector<std::string> texts, sources;
  for (const std::string& d : o.shard_dirs) {
    const fs::path csv = fs::path(d) / "campaign.csv";
    if (!fs::is_regular_file(csv))
      throw InputError(csv.string(), "", "a shard's campaign.csv", "no such file");
    texts.push_back(read_text(csv));
    sources.push_back(csv.string());
  }
  const std::string merged = merge_campaign_csv(texts, sources);
  const std::string verdict = campaign_verdict(merged);
  OutputSet set(out, OutputKind::kDirectory);
  for (const std::string& d : o.shard_dirs)  // each run's faults and report, for its replay
    if (fs::is_directory(fs::path(d) / "runs"))
      fs::copy(fs::path(d) / "runs", set.staging_dir() / "runs",
               fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  set.write_text("campaign.csv", merged);
  set.write_text("verdict.txt", verdict + "\n");
  set.commit();
  std::printf("%s\n", verdict.c_str());
  if (!campaign_passed(merged)) set_exit_code(1);
}

const CommandRegistration kCampaign{
    "campaign", [](CLI::App& app) {
      auto o = std::make_shared<Options>();
      auto* sub = app.add_subcommand(
          "campaign", "Run many simulated missions with random faults and class how each ended");
      sub->add_option("--runs", o->runs, "Missions to run")->capture_default_str();
      add_seed_option(sub, o->seed, "campaign");
      sub->add_option("--jobs", o->jobs, "Missions at once, each in its own process")
          ->capture_default_str();
      sub->add_option("--shard", o->shard,
                      "Run slice I of N (runs r with r % N == I; default: the Slurm job array's "
                      "task, else 0/1)")
          ->capture_default_str();
      sub->add_option("--world", o->worlds,
                      "A world YAML to draw from (repeatable; default: the shipped worlds)");
      sub->add_option("--run-timeout-s", o->run_timeout_s,
                      "Wall-clock seconds after which a run counts as hung")
          ->capture_default_str();
      sub->add_option("--max-faults", o->max_faults, "Faults a run draws at most")
          ->capture_default_str();
      sub->add_option("--min-faults", o->min_faults, "Faults a run draws at least")
          ->capture_default_str();
      sub->add_flag("-q,--quiet", o->quiet, "No progress lines");
      add_out_option(sub, o->out, "Output directory");
      sub->callback([o, sub] {
        if (sub->got_subcommand("merge")) return;
        o->shard_given = sub->count("--shard") > 0;
        run(*o);
      });
      auto m = std::make_shared<Options>();
      auto* mc = sub->add_subcommand(
          "merge", "Merge the shards' campaign.csv into the unsharded campaign's");
      mc->add_option("shards", m->shard_dirs, "The shards' output directories")->required();
      add_out_option(mc, m->out, "Output directory");
      mc->callback([m] { merge(*m); });
    }};

}  // namespace
}  // namespace ferret::cli
