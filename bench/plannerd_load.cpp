// ferret-plannerd-load: drives a planner service (ferret-plannerd) on loopback with
// mixed requests at a given concurrency for a bounded time and count, and reports
// throughput, p50/p99 latency and the answers by status and code (docs/service.md,
// "Load test"). Without --port it starts the service in this process.
//
//   ferret-plannerd-load --world examples/worlds/default.yaml --concurrency 4 --duration 20
//
// Each client is closed-loop (the next request when the last is answered), so
// --concurrency bounds the load; a client answered 503 waits its Retry-After only with
// --honour-retry-after (overload runs leave it off to offer as much as they can).

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "ferret/service/planner_service.hpp"

// clang-format off: httplib after every header that includes Eigen
#include <httplib.h>  // after Eigen (service/src/planner_service_impl.hpp says why)
// clang-format on

namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Space {
  std::string name;
  double x0, y0, x1, y1;
};

struct Sample {
  std::string route, code;
  int status = 0;
  double latency_s = 0.0;
};

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(
      std::clamp(p * static_cast<double>(v.size()), 0.0, static_cast<double>(v.size() - 1)));
  return v[k];
}

std::uint64_t rss_from_metrics(httplib::Client& c) {
  const auto m = c.Get("/metrics");
  if (!m) return 0;
  const std::string key = "\nprocess_resident_memory_bytes ";  // the sample, not its HELP line
  const auto at = m->body.find(key);
  return at == std::string::npos ? 0 : std::stoull(m->body.substr(at + key.size()));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ferret-plannerd-load: a load test of the planner service"};
  int port = 0, concurrency = 4, ugv_weight = 9, return_weight = 1, uav_weight = 0;
  double duration_s = 20.0, deadline_s = 1.0, replace_every_s = 0.0, sample_every_s = 10.0;
  std::size_t count = 0;
  std::uint64_t seed = 1;
  std::string world = "examples/worlds/default.yaml", token_file, map = "site", json_out;
  bool honour_retry = false;
  int workers = 2, queue = 32;
  app.add_option("--port", port,
                 "a running service on 127.0.0.1:PORT (default: start one in this process)");
  app.add_option("--token-file", token_file, "the service's bearer token, first line of this file");
  app.add_option("--world", world, "the map to upload first (and to replace with --replace-every)")
      ->capture_default_str();
  app.add_option("--map", map, "the map's name")->capture_default_str();
  app.add_option("--concurrency", concurrency, "closed-loop clients")->capture_default_str();
  app.add_option("--duration", duration_s, "seconds to run")->capture_default_str();
  app.add_option("--count", count, "stop after this many answers (0: no limit)")
      ->capture_default_str();
  app.add_option("--deadline", deadline_s, "each request's deadline_s")->capture_default_str();
  app.add_option("--ugv", ugv_weight, "weight of POST /v1/plan/ugv")->capture_default_str();
  app.add_option("--return", return_weight, "weight of POST /v1/plan/ugv/return")
      ->capture_default_str();
  app.add_option("--uav", uav_weight, "weight of POST /v1/plan/uav")->capture_default_str();
  app.add_option("--replace-every", replace_every_s,
                 "PUT the map again every S seconds (0: never)");
  app.add_option("--sample-every", sample_every_s, "seconds between resident-memory samples")
      ->capture_default_str();
  app.add_option("--seed", seed, "seed of the requests' poses")->capture_default_str();
  app.add_option("--workers", workers, "in-process service: workers")->capture_default_str();
  app.add_option("--queue", queue, "in-process service: queue")->capture_default_str();
  app.add_flag("--honour-retry-after", honour_retry, "wait Retry-After after a 503");
  app.add_option("--json", json_out, "also write the report as JSON to this file");
  CLI11_PARSE(app, argc, argv);

  std::unique_ptr<ferret::PlannerService> local;
  if (port == 0) {
    ferret::PlannerServiceOptions o;
    o.port = 0;
    o.workers = workers;
    o.queue = queue;
    local = std::make_unique<ferret::PlannerService>(o);
    port = local->start();
  }
  std::string token;
  if (!token_file.empty()) {
    token = slurp(token_file);
    token = token.substr(0, token.find('\n'));
  }
  const auto client = [&] {
    auto c = std::make_unique<httplib::Client>("127.0.0.1", port);
    c->set_read_timeout(std::chrono::seconds(120));
    c->set_keep_alive(true);
    c->set_tcp_nodelay(true);
    if (!token.empty()) c->set_bearer_token_auth(token);
    return c;
  };
  const std::string world_bytes = slurp(world);
  auto admin = client();
  const auto put = admin->Put("/v1/maps/" + map, world_bytes, "application/yaml");
  if (!put || put->status >= 300) {
    std::cerr << "ferret-plannerd-load: PUT /v1/maps/" << map
              << " failed: " << (put ? put->body : "no answer") << "\n";
    return 2;
  }
  std::vector<Space> spaces;
  const json meta = json::parse(put->body);
  for (const json& h : meta["hidden_spaces"])
    spaces.push_back({h["name"], h["bounds_xy_m"][0], h["bounds_xy_m"][1], h["bounds_xy_m"][2],
                      h["bounds_xy_m"][3]});
  if (spaces.empty() && (ugv_weight > 0 || return_weight > 0)) {
    std::cerr << "ferret-plannerd-load: the world has no hidden space for miniUGV requests\n";
    return 2;
  }

  std::mutex samples_mutex;
  std::vector<Sample> samples;
  std::atomic<std::size_t> answered{0};
  std::atomic<bool> stop{false};
  const auto t0 = Clock::now();
  const auto until =
      t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(duration_s));

  const auto run_client = [&](int k) {
    auto c = client();
    std::mt19937_64 rng(seed * 1000003u + static_cast<std::uint64_t>(k));
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int total = ugv_weight + return_weight + uav_weight;
    std::vector<Sample> mine;
    while (!stop && Clock::now() < until) {
      const double pick = u(rng) * total;
      json j{{"map", map}, {"deadline_s", deadline_s}, {"seed", rng() % 1000 + 1}};
      std::string route;
      if (pick < ugv_weight + return_weight) {
        const Space& s = spaces[rng() % spaces.size()];
        const auto pose = [&] {
          return json{s.x0 + 0.5 + (s.x1 - s.x0 - 1.0) * u(rng),
                      s.y0 + 0.5 + (s.y1 - s.y0 - 1.0) * u(rng), -3.14 + 6.28 * u(rng)};
        };
        j["hidden_space"] = s.name;
        j["start"] = pose();
        j["goal"] = pose();
        route = pick < ugv_weight ? "/v1/plan/ugv" : "/v1/plan/ugv/return";
      } else {
        j["start"] = {-20.0, -20.0, 3.0, 0.0};
        j["goal"] = {-20.0 + 40.0 * u(rng), -20.0 + 40.0 * u(rng), 3.0, 0.0};
        route = "/v1/plan/uav";
      }
      const auto t = Clock::now();
      const auto r = c->Post(route, j.dump(), "application/json");
      Sample s{route, "", r ? r->status : 0,
               std::chrono::duration<double>(Clock::now() - t).count()};
      if (r && r->status != 200) {
        const auto b = json::parse(r->body, nullptr, false);
        if (b.is_object() && b.contains("error")) s.code = b["error"].value("code", "");
      }
      if (!r) s.code = "NO_ANSWER";
      mine.push_back(s);
      if (count > 0 && ++answered >= count) stop = true;
      if (honour_retry && r && r->status == 503)
        std::this_thread::sleep_for(std::chrono::seconds(1));
    }
    const std::lock_guard lock(samples_mutex);
    samples.insert(samples.end(), mine.begin(), mine.end());
  };

  std::vector<std::thread> threads;
  for (int k = 0; k < concurrency; ++k) threads.emplace_back(run_client, k);
  // Meanwhile: the map replaced every few seconds, resident memory sampled.
  std::vector<std::pair<double, std::uint64_t>> rss, steady;
  std::size_t replaced = 0;
  auto next_replace = t0 + std::chrono::duration_cast<Clock::duration>(
                               std::chrono::duration<double>(replace_every_s));
  auto next_sample = t0;
  while (!stop && Clock::now() < until) {
    const auto now = Clock::now();
    if (now >= next_sample) {
      rss.emplace_back(std::chrono::duration<double>(now - t0).count(), rss_from_metrics(*admin));
      next_sample += std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(sample_every_s));
    }
    if (replace_every_s > 0 && now >= next_replace) {
      // Resident memory just before each replacement: one map held, the same phase of
      // every cycle (a sample during a rebuild holds two maps and the build's scratch).
      steady.emplace_back(std::chrono::duration<double>(now - t0).count(),
                          rss_from_metrics(*admin));
      const auto r = admin->Put("/v1/maps/" + map, world_bytes, "application/yaml");
      if (r && r->status < 300) ++replaced;
      next_replace += std::chrono::duration_cast<Clock::duration>(
          std::chrono::duration<double>(replace_every_s));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  for (auto& t : threads) t.join();
  const double elapsed_s = std::chrono::duration<double>(Clock::now() - t0).count();
  rss.emplace_back(elapsed_s, rss_from_metrics(*admin));

  std::map<std::string, std::size_t> by_answer;
  std::vector<double> all, accepted, solved;
  for (const Sample& s : samples) {
    ++by_answer[fmt::format("{} {}", s.status, s.code.empty() ? "ok" : s.code)];
    all.push_back(s.latency_s);
    if (s.status != 503 && s.status != 0) accepted.push_back(s.latency_s);
    if (s.status == 200) solved.push_back(s.latency_s);
  }
  json report{
      {"concurrency", concurrency},
      {"elapsed_s", elapsed_s},
      {"requests", samples.size()},
      {"throughput_per_s", static_cast<double>(samples.size()) / elapsed_s},
      {"solved_per_s", static_cast<double>(solved.size()) / elapsed_s},
      {"latency_s", {{"p50", percentile(all, 0.5)}, {"p99", percentile(all, 0.99)}}},
      {"accepted_latency_s",
       {{"p50", percentile(accepted, 0.5)},
        {"p99", percentile(accepted, 0.99)},
        {"max", accepted.empty() ? 0.0 : *std::max_element(accepted.begin(), accepted.end())}}},
      {"solved_latency_s", {{"p50", percentile(solved, 0.5)}, {"p99", percentile(solved, 0.99)}}},
      {"answers", by_answer},
      {"map_replacements", replaced},
      {"deadline_s", deadline_s}};
  json mem = json::array(), before_replacement = json::array();
  for (const auto& [t, b] : rss) mem.push_back({t, b});
  for (const auto& [t, b] : steady) before_replacement.push_back({t, b});
  report["resident_memory_bytes"] = mem;
  report["resident_memory_before_replacement_bytes"] = before_replacement;
  std::cout << fmt::format("{} requests in {:.1f} s with {} clients: {:.0f}/s ({:.0f} solved/s)\n",
                           samples.size(), elapsed_s, concurrency,
                           report["throughput_per_s"].get<double>(),
                           report["solved_per_s"].get<double>());
  std::cout << fmt::format(
      "latency p50 {:.1f} ms, p99 {:.1f} ms; accepted p99 {:.1f} ms (deadline {:.0f} ms); solved "
      "p99 {:.1f} ms\n",
      percentile(all, 0.5) * 1e3, percentile(all, 0.99) * 1e3, percentile(accepted, 0.99) * 1e3,
      deadline_s * 1e3, percentile(solved, 0.99) * 1e3);
  for (const auto& [answer, n] : by_answer) std::cout << fmt::format("  {:>7}  {}\n", n, answer);
  if (rss.size() >= 2) {
    std::uint64_t lo = rss.front().second, hi = lo;
    for (const auto& [t, b] : rss) lo = std::min(lo, b), hi = std::max(hi, b);
    std::cout << fmt::format(
        "resident memory: first {:.1f} MiB, last {:.1f} MiB, min {:.1f}, max {:.1f} ({} samples, "
        "{} map replacements)\n",
        rss.front().second / 1048576.0, rss.back().second / 1048576.0, lo / 1048576.0,
        hi / 1048576.0, rss.size(), replaced);
  }
  if (steady.size() >= 2) {
    // The soak's measure: memory at the same phase of each replacement cycle, after the
    // first minute's warm-up (the allocator's pools and every thread's first plans).
    std::uint64_t lo = UINT64_MAX, hi = 0, first = 0;
    for (const auto& [t, b] : steady)
      if (t >= std::min(60.0, duration_s / 2)) {
        if (first == 0) first = b;
        lo = std::min(lo, b), hi = std::max(hi, b);
      }
    if (first > 0)
      std::cout << fmt::format(
          "before each replacement, after warm-up: first {:.1f} MiB, last {:.1f} MiB, min {:.1f}, "
          "max {:.1f} ({:+.1f} % / {:+.1f} % of the first)\n",
          first / 1048576.0, steady.back().second / 1048576.0, lo / 1048576.0, hi / 1048576.0,
          100.0 * (static_cast<double>(lo) / first - 1.0),
          100.0 * (static_cast<double>(hi) / first - 1.0));
  }
  if (!json_out.empty()) std::ofstream(json_out) << report.dump(2) << "\n";
  if (local) local->stop();
  return 0;
}
