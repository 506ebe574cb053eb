#include "ferret/service/planner_service.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <arpa/inet.h>
#include <malloc.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <octomap/OcTree.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cerrno>
#include <deque>
#include <filesystem>
#include <future>
#include <iostream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>
#include <unordered_map>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/mapping/occupancy_map_2d.hpp"
#include "ferret/mapping/world_octree.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "ferret/planning/next_goal.hpp"
#include "ferret/planning/plan_file.hpp"
#include "ferret/planning/plan_validation.hpp"
#include "ferret/planning/planning_world.hpp"
#include "ferret/planning/uav_approach.hpp"
#include "ferret/planning/ugv_path.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "service_metrics.hpp"

// After every header that includes Eigen: httplib pulls in <resolv.h>, whose `_res`
// macro breaks Eigen's templates that name a parameter _res.
#include <httplib.h>

namespace ferret {
namespace {

using json = nlohmann::json;
using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------------------------
// Errors: one JSON shape for every failure, {"error": {"code", "message", "field"}}.

struct ApiError {
  int http = 400;
  std::string code;  // docs/service.md's set
  std::string message;
  std::string field;
};

[[noreturn]] void bad_request(const std::string& field, const std::string& expected,
                              const std::string& got = {}) {
  throw ApiError{400, "INVALID_REQUEST",
                 got.empty() ? fmt::format("{}: expected {}", field, expected)
                             : fmt::format("{}: expected {} (got {})", field, expected,
                                           printable(got, 80)),
                 field};
}

json error_body(const ApiError& e) {
  // Every part may hold the request's bytes (an unknown key, a part's name): printable
  // ASCII, so the answer is JSON whatever the request held.
  json err{{"code", printable(e.code, 64)}, {"message", printable(e.message)}};
  if (!e.field.empty()) err["field"] = printable(e.field, 120);
  return json{{"error", err}};
}

// A library InputError about a request field, as the service's 400 (or 404 for a
// hidden space the map does not have: the client named something that is not there).
ApiError from_input_error(const InputError& e, const std::map<std::string, std::string>& fields) {
  const auto it = fields.find(e.field());
  const std::string field = it != fields.end() ? it->second : e.field();
  std::string message = e.what();
  // The library names its own request struct; the client knows its JSON field.
  const std::string head = e.source() + ": " + e.field() + ": ";
  if (message.rfind(head, 0) == 0) message = field + ": " + message.substr(head.size());
  return ApiError{400, "INVALID_REQUEST", printable(message), field};
}

// Planning outcomes (PlanFailure) as the service's codes, in the manner of nav2's
// planner server: each a reason a client can act on.
const char* failure_code(PlanFailure f) {
  switch (f) {
    case PlanFailure::kStartInvalid: return "START_OCCUPIED";
    case PlanFailure::kGoalInvalid: return "GOAL_OCCUPIED";
    case PlanFailure::kStartOutside: return "START_OUTSIDE_MAP";
    case PlanFailure::kGoalOutside: return "GOAL_OUTSIDE_MAP";
    case PlanFailure::kTetherTooShort: return "TETHER_TOO_SHORT";
    case PlanFailure::kTimeout: return "TIMEOUT";
    case PlanFailure::kCancelled: return "CANCELLED";
    case PlanFailure::kNoPath:
    case PlanFailure::kNone: break;
  }
  return "NO_VALID_PATH";
}

// ---------------------------------------------------------------------------------
// Request bodies: strict JSON (unknown keys are errors, so a typo is not ignored).

class Body {
 public:
  Body(const std::string& text, std::vector<std::string> known) {
    try {
      j_ = json::parse(text);
    } catch (const json::exception&) {
      bad_request("body", "a JSON object");
    }
    if (!j_.is_object()) bad_request("body", "a JSON object");
    for (const auto& [key, value] : j_.items())
      if (std::find(known.begin(), known.end(), key) == known.end())
        bad_request(key, fmt::format("one of the fields {}", fmt::join(known, ", ")), key);
  }
  [[nodiscard]] bool has(const std::string& key) const {
    return j_.contains(key) && !j_.at(key).is_null();
  }
  [[nodiscard]] const json& at(const std::string& key) const { return j_.at(key); }
  [[nodiscard]] std::string text(const std::string& key, const std::string& fallback = {}) const {
    if (!has(key)) return fallback;
    if (!at(key).is_string()) bad_request(key, "a string");
    return at(key).get<std::string>();
  }
  [[nodiscard]] std::string required_text(const std::string& key) const {
    if (!has(key)) bad_request(key, "a string (required)");
    return text(key);
  }
  [[nodiscard]] double number(const std::string& key, double lo, double hi,
                              const std::string& what) const {
    return number_of(at(key), key, lo, hi, what);
  }
  [[nodiscard]] std::optional<double> optional_number(const std::string& key, double lo, double hi,
                                                      const std::string& what) const {
    if (!has(key)) return std::nullopt;
    return number(key, lo, hi, what);
  }
  [[nodiscard]] std::vector<double> numbers(const std::string& key, std::size_t n,
                                            const std::string& what) const {
    if (!has(key)) bad_request(key, what + " (required)");
    return numbers_of(at(key), key, n, what);
  }
  [[nodiscard]] std::uint64_t seed() const {
    if (!has("seed")) return 1;
    const json& v = at("seed");
    if (!v.is_number_unsigned()) bad_request("seed", "an unsigned integer");
    return v.get<std::uint64_t>();
  }
  [[nodiscard]] std::optional<Aabb3> bounds() const {
    if (!has("bounds")) return std::nullopt;
    const auto v = numbers_of(at("bounds"), "bounds", 6, "[x0, y0, z0, x1, y1, z1] in metres");
    Aabb3 b{{v[0], v[1], v[2]}, {v[3], v[4], v[5]}};
    if (!(b.lo.array() < b.hi.array()).all())
      bad_request("bounds", "[x0, y0, z0, x1, y1, z1] with min < max on every axis");
    return b;
  }

  static double number_of(const json& v, const std::string& field, double lo, double hi,
                          const std::string& what) {
    if (!v.is_number()) bad_request(field, what, v.dump());
    const double x = v.get<double>();
    if (!(std::isfinite(x) && x >= lo && x <= hi)) bad_request(field, what, v.dump());
    return x;
  }
  static std::vector<double> numbers_of(const json& v, const std::string& field, std::size_t n,
                                        const std::string& what) {
    if (!v.is_array() || v.size() != n) bad_request(field, what, v.dump());
    std::vector<double> out;
    for (std::size_t k = 0; k < n; ++k)
      out.push_back(number_of(v[k], fmt::format("{}[{}]", field, k), -1e6, 1e6, what));
    return out;
  }

 private:
  json j_;
};

// ---------------------------------------------------------------------------------
// Maps: immutable snapshots. A PUT swaps the pointer; a plan running on the old map
// keeps it alive until it finishes. Each map keeps the setups its plans need (the
// distance field and tether corners of a hidden space, a UAV geofence's snapshot),
// built once by the first request that needs one; later ones wait for it.

struct MapEntry {
  MapEntry() = default;
  MapEntry(const MapEntry&) = delete;
  MapEntry& operator=(const MapEntry&) = delete;
  // A map is millions of small nodes, built on whichever HTTP thread took the PUT, so
  // in whichever malloc arena that thread uses. glibc keeps a freed map's pages in its
  // arena; over many replacements every arena holds one and the service's memory grows
  // with the number of threads. Trimming returns them to the system.
  ~MapEntry() {
    world = {};
    ugv.setups.clear();
    uav.setups.clear();
    validation.setups.clear();
    malloc_trim(0);
  }
  std::string name, format;
  std::size_t bytes = 0;
  PlanningWorld world;
  std::string loaded_at;  // ISO 8601, UTC

  template <typename Setup>
  struct Cache {
    std::mutex mutex;
    std::deque<std::string> order;
    std::unordered_map<std::string, std::shared_future<std::shared_ptr<const Setup>>> setups;
  };
  Cache<UgvPathSetup> ugv;
  Cache<UavApproachSetup> uav;
  // The collision maps validations built, by their options: building one is most of a
  // validation (0.76 s of 0.77 for a UAV plan on the default world).
  struct ValidationMap {
    std::shared_ptr<const CollisionMap> map;
  };
  Cache<ValidationMap> validation;
};

constexpr std::size_t kSetupsPerMap = 16;

// Keeps `future` under `key` (the cache's mutex held), the oldest setup making room.
template <typename Setup>
void keep_setup(MapEntry::Cache<Setup>& cache, const std::string& key,
                std::shared_future<std::shared_ptr<const Setup>> future) {
  if (cache.order.size() >= kSetupsPerMap) {
    cache.setups.erase(cache.order.front());
    cache.order.pop_front();
  }
  cache.setups.emplace(key, std::move(future));
  cache.order.push_back(key);
}

template <typename Setup, typename Make>
std::shared_ptr<const Setup> cached_setup(MapEntry::Cache<Setup>& cache, const std::string& key,
                                          Make make) {
  std::promise<std::shared_ptr<const Setup>> promise;
  std::shared_future<std::shared_ptr<const Setup>> future;
  bool build = false;
  {
    const std::lock_guard lock(cache.mutex);
    const auto it = cache.setups.find(key);
    if (it != cache.setups.end()) {
      future = it->second;
    } else {
      future = promise.get_future().share();
      keep_setup(cache, key, future);
      build = true;
    }
  }
  if (build) {
    try {
      promise.set_value(std::make_shared<const Setup>(make()));
    } catch (...) {
      promise.set_exception(std::current_exception());
      const std::lock_guard lock(cache.mutex);  // a bad request is not kept
      cache.setups.erase(key);
      cache.order.erase(std::find(cache.order.begin(), cache.order.end(), key));
    }
  }
  return future.get();
}

// Puts a setup another request built into `cache` (unless one is there already).
template <typename Setup>
void offer_setup(MapEntry::Cache<Setup>& cache, const std::string& key, Setup setup) {
  std::promise<std::shared_ptr<const Setup>> promise;
  promise.set_value(std::make_shared<const Setup>(std::move(setup)));
  const std::lock_guard lock(cache.mutex);
  if (!cache.setups.count(key)) keep_setup(cache, key, promise.get_future().share());
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

bool valid_map_name(const std::string& name) {
  if (name.empty() || name.size() > 64) return false;
  return std::all_of(name.begin(), name.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '-' || c == '.';
  });
}

// ---------------------------------------------------------------------------------
// Admission: at most `workers` requests work at once and `queue` wait; the rest are
// told to come back (503, Retry-After). A waiting request gives up at its deadline.

class Admission {
 public:
  Admission(int workers, int queue) : workers_(workers), queue_(queue) {}
  enum class Result { kAdmitted, kOverloaded, kDeadline };
  Result enter(Clock::time_point deadline) {
    std::unique_lock lock(mutex_);
    if (active_ < workers_ && waiting_ == 0) {
      ++active_;
      return Result::kAdmitted;
    }
    if (waiting_ >= queue_) return Result::kOverloaded;
    ++waiting_;
    const bool got = cv_.wait_until(lock, deadline, [&] { return active_ < workers_; });
    --waiting_;
    if (!got) return Result::kDeadline;
    ++active_;
    return Result::kAdmitted;
  }
  void leave() {
    {
      const std::lock_guard lock(mutex_);
      --active_;
    }
    cv_.notify_one();
  }
  [[nodiscard]] std::pair<int, int> load() const {
    const std::lock_guard lock(mutex_);
    return {active_, waiting_};
  }

 private:
  const int workers_, queue_;
  mutable std::mutex mutex_;
  std::condition_variable cv_;
  int active_ = 0, waiting_ = 0;
};

// Every map is built on this one thread, which also hands freed memory back to the
// system every few seconds. A map is millions of small blocks that live as
// long as it does; built on whichever HTTP thread took the PUT, they land in the malloc
// arenas where plans make their short-lived blocks, and a replaced map's holes there stay
// partly in use: over a 10-minute soak with the map replaced every 3 s the resident
// memory crept by 5 %. On one thread (with an arena of its own, ferret-plannerd's main
// allows one a thread), each new map fills the holes the last but one left.
class MapBuilder {
 public:
  MapBuilder() : thread_([this] { run(); }) {
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [&] { return ready_; });  // its arena is taken before the HTTP threads start
  }
  ~MapBuilder() {
    {
      const std::lock_guard lock(mutex_);
      stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  MapBuilder(const MapBuilder&) = delete;
  MapBuilder& operator=(const MapBuilder&) = delete;

  /// Runs `work` on the builder's thread and returns what it returns (or throws what it threw).
  template <typename Work>
  auto run_here(Work work) -> decltype(work()) {
    auto task = std::make_shared<std::packaged_task<decltype(work())()>>(std::move(work));
    auto result = task->get_future();
    {
      const std::lock_guard lock(mutex_);
      tasks_.emplace_back([task] { (*task)(); });
    }
    cv_.notify_all();
    return result.get();
  }

 private:
  void run() {
    std::unique_lock lock(mutex_);
    tasks_.reserve(4);  // a first allocation: this thread's arena, now
    ready_ = true;
    cv_.notify_all();
    auto next_trim = std::chrono::steady_clock::now() + kTrimEvery;
    for (;;) {
      cv_.wait_until(lock, next_trim, [&] { return stop_ || !tasks_.empty(); });
      if (stop_ && tasks_.empty()) return;
      if (tasks_.empty()) {
        // Plans free all they take, but the pages stay with the arena of the thread that
        // freed them: without a trim the resident memory grew 374 -> 576 MiB in two
        // minutes at 2500 plans/s on one map while the heap in use stayed at 190 MiB.
        lock.unlock();
        malloc_trim(0);
        lock.lock();
        next_trim = std::chrono::steady_clock::now() + kTrimEvery;
        continue;
      }
      auto task = std::move(tasks_.front());
      tasks_.erase(tasks_.begin());
      lock.unlock();
      task();
      lock.lock();
    }
  }

  static constexpr std::chrono::seconds kTrimEvery{5};
  std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<std::function<void()>> tasks_;
  bool ready_ = false, stop_ = false;
  std::thread thread_;  // last: started once the members above exist
};

bool same_token(const std::string& a, const std::string& b) {
  // Constant time in the token's length: no early exit on the first wrong byte.
  unsigned char diff = a.size() == b.size() ? 0 : 1;
  for (std::size_t k = 0; k < a.size(); ++k) diff |= a[k] ^ (k < b.size() ? b[k] : 0);
  return diff == 0;
}

// The socket of the connection a request came on. cpp-httplib 0.11 does not hand it to
// a handler, so it is found by the peer's address and port among this process's
// sockets (they stay open while the handler runs, so the descriptor cannot be reused
// under it). -1 when not found: the search then ends by its deadline only.
int connection_fd(const std::string& remote_addr, int remote_port, int want_local_port) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", ec)) {
    int fd = -1;
    try {
      fd = std::stoi(entry.path().filename().string());
    } catch (const std::exception&) {
      continue;
    }
    sockaddr_storage peer{}, local{};
    socklen_t peer_len = sizeof peer, local_len = sizeof local;
    if (::getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &peer_len) != 0) continue;
    if (::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &local_len) != 0) continue;
    char host[INET6_ADDRSTRLEN] = {};
    int peer_port = -1, local_port = -1;
    if (peer.ss_family == AF_INET) {
      const auto* a = reinterpret_cast<const sockaddr_in*>(&peer);
      ::inet_ntop(AF_INET, &a->sin_addr, host, sizeof host);
      peer_port = ntohs(a->sin_port);
      local_port = ntohs(reinterpret_cast<const sockaddr_in*>(&local)->sin_port);
    } else if (peer.ss_family == AF_INET6) {
      const auto* a = reinterpret_cast<const sockaddr_in6*>(&peer);
      ::inet_ntop(AF_INET6, &a->sin6_addr, host, sizeof host);
      peer_port = ntohs(a->sin6_port);
      local_port = ntohs(reinterpret_cast<const sockaddr_in6*>(&local)->sin6_port);
    } else {
      continue;
    }
    if (peer_port == remote_port && local_port == want_local_port && remote_addr == host) return fd;
  }
  return -1;
}

// Has the peer closed its end? A peek that reads 0 bytes is an orderly close; bytes
// waiting (a pipelined request) or nothing yet both mean the client is still there.
bool peer_closed(int fd) {
  char c = 0;
  const ssize_t n = ::recv(fd, &c, 1, MSG_PEEK | MSG_DONTWAIT);
  if (n == 0) return true;
  return n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR;
}

}  // namespace

// ---------------------------------------------------------------------------------

void check_planner_service_options(const PlannerServiceOptions& o) {
  if (o.port < 0 || o.port > 65535) throw InputError("--listen", "port", "a port in [0, 65535]", std::to_string(o.port));
  if (o.workers < 1 || o.workers > 256) throw InputError("--workers", "", "an integer in [1, 256]", std::to_string(o.workers));
  if (o.queue < 0 || o.queue > 10000) throw InputError("--queue", "", "an integer in [0, 10000]", std::to_string(o.queue));
  if (o.max_body_bytes < 1024 || o.max_body_bytes > (std::size_t{4} << 30))
    throw InputError("--max-body-bytes", "", "bytes in [1024, 4 GiB]", std::to_string(o.max_body_bytes));
  if (!(std::isfinite(o.max_deadline_s) && o.max_deadline_s > 0 && o.max_deadline_s <= 3600))
    throw InputError("--max-deadline", "", "seconds in (0, 3600]", fmt::format("{}", o.max_deadline_s));
  if (!(std::isfinite(o.default_deadline_s) && o.default_deadline_s > 0 &&
        o.default_deadline_s <= o.max_deadline_s))
    throw InputError("--deadline", "", "seconds in (0, --max-deadline]", fmt::format("{}", o.default_deadline_s));
  if (o.max_maps < 1 || o.max_maps > 4096) throw InputError("--max-maps", "", "an integer in [1, 4096]", std::to_string(o.max_maps));
  // Both robots must load: a service that cannot plan should not start.
  (void)load_plan_robot(PlanRobot::kUav, {o.robot_uav, false}, o.mission, 0.0, "--robot-uav", "");
  (void)load_plan_robot(PlanRobot::kUgv, {o.robot_ugv, false}, o.mission, 0.0, "--robot-ugv", "");
}

struct PlannerService::Impl {
  explicit Impl(PlannerServiceOptions o)
      : options(std::move(o)), admission(options.workers, options.queue) {}

  PlannerServiceOptions options;
  MapBuilder map_builder;  // before the server: its thread's arena comes first
  httplib::Server server;
  std::thread thread;
  Admission admission;
  internal::ServiceMetrics metrics;
  std::atomic<bool> draining{false}, cancel_all{false};
  std::atomic<int> in_flight{0};

  mutable std::mutex maps_mutex;
  std::map<std::string, std::shared_ptr<MapEntry>> maps;

  // -- helpers ---------------------------------------------------------------------

  std::shared_ptr<MapEntry> find_map(const std::string& name) const {
    const std::lock_guard lock(maps_mutex);
    const auto it = maps.find(name);
    if (it == maps.end())
      throw ApiError{404, "UNKNOWN_MAP", fmt::format("map: no map called '{}' (PUT /v1/maps/{{name}} first)", printable(name, 64)), "map"};
    return it->second;
  }

  std::size_t map_count() const {
    const std::lock_guard lock(maps_mutex);
    return maps.size();
  }

  static void send(httplib::Response& res, int status, const json& body) {
    res.status = status;
    // A string that is not UTF-8 is a bug upstream; it must not turn the answer into a 500.
    res.set_content(body.dump(-1, ' ', false, json::error_handler_t::replace) + "\n", "application/json");
  }

  // A deadline from the request (seconds from arrival), within the service's bounds.
  Clock::time_point deadline_of(const Body& body, Clock::time_point arrived) const {
    double d = options.default_deadline_s;
    if (body.has("deadline_s"))
      d = body.number("deadline_s", 1e-3, options.max_deadline_s,
                      fmt::format("seconds in [0.001, {:g}]", options.max_deadline_s));
    return arrived + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(d));
  }

  // Runs `work` holding a worker, or answers 503 / TIMEOUT without it.
  template <typename Work>
  void with_worker(httplib::Response& res, Clock::time_point deadline, Work work) {
    switch (admission.enter(deadline)) {
      case Admission::Result::kOverloaded:
        res.set_header("Retry-After", "1");
        throw ApiError{503, "OVERLOADED", "every worker is busy and the queue is full: retry later", ""};
      case Admission::Result::kDeadline:
        throw ApiError{422, "TIMEOUT", "the deadline passed while the request waited for a worker", "deadline_s"};
      case Admission::Result::kAdmitted:
        break;
    }
    struct Leave {
      Admission& a;
      ~Leave() { a.leave(); }
    } leave{admission};
    work();
  }

  static double seconds_left(Clock::time_point deadline) {
    return std::chrono::duration<double>(deadline - Clock::now()).count();
  }

  // The search stops when the service shuts down or the client hangs up. Most plans
  // end within milliseconds, so the client's socket is looked for only once a search
  // has run 10 ms, and then peeked at every 10 ms at most (a search's checks stay cheap).
  std::function<bool()> cancel_flag(const httplib::Request& req) {
    struct Watch {
      std::string remote_addr;
      int remote_port = -1, local_port = -1;
      int fd = -2;  // -2: not looked for yet; -1: not found
      Clock::time_point next{};
      bool gone = false;
    };
    auto watch = std::make_shared<Watch>();
    watch->remote_addr = req.remote_addr;
    watch->remote_port = req.remote_port;
    watch->local_port = req.local_port;
    watch->next = Clock::now() + std::chrono::milliseconds(10);
    return [this, watch] {
      if (cancel_all.load(std::memory_order_relaxed)) return true;
      if (watch->gone || watch->fd == -1) return watch->gone;
      const auto now = Clock::now();
      if (now < watch->next) return false;
      watch->next = now + std::chrono::milliseconds(10);
      if (watch->fd == -2) watch->fd = connection_fd(watch->remote_addr, watch->remote_port, watch->local_port);
      watch->gone = watch->fd >= 0 && peer_closed(watch->fd);
      return watch->gone;
    };
  }

  json plan_response(const PlanResult& r, double wall_s, httplib::Response& res) {
    metrics.record_plan(r.solved ? "solved" : r.failure == PlanFailure::kCancelled ? "cancelled" : "failed");
    if (!r.solved) {
      const ApiError e{422, failure_code(r.failure), r.status, ""};
      json body = error_body(e);
      body["planning_time_s"] = wall_s;
      res.status = e.code == std::string("CANCELLED") ? 503 : 422;
      return body;
    }
    res.status = 200;
    return json{{"status", "solved"}, {"planning_time_s", wall_s}, {"plan", json::parse(plan_to_json(r.plan))}};
  }

  // -- maps ------------------------------------------------------------------------

  // The map in a body: an OctoMap file (by its header line) or a world YAML; or a
  // map_server map as its YAML's text and its image's bytes (`map_2d`), the YAML's
  // `image` key never opened (a request must not make the service read its files).
  // InputError naming `source` (for a map_server map: "yaml" or "image") when the
  // bytes are not a map.
  struct Map2DUpload {
    std::string yaml, image;                      // the YAML's text, the image's bytes
    std::string yaml_source = "yaml", image_source = "image";  // what errors name
  };
  struct MapUpload {
    std::string body;
    std::optional<Map2DUpload> map_2d;
  };
  std::shared_ptr<MapEntry> load_map(const std::string& name, const MapUpload& upload, const std::string& source) {
    auto entry = std::make_shared<MapEntry>();
    entry->name = name;
    entry->loaded_at = utc_now();
    const std::string& body = upload.body;
    const bool bt = body.rfind("# Octomap OcTree binary file", 0) == 0;
    const bool ot = !bt && body.rfind("# Octomap OcTree file", 0) == 0;
    if (upload.map_2d) {
      const Map2DUpload& u = *upload.map_2d;
      entry->bytes = u.yaml.size() + u.image.size();
      entry->format = "map_server";
      const MapServerMeta meta = parse_map_server_meta(u.yaml, u.yaml_source);
      Map2DExtrusion extrusion;
      extrusion.max_voxels = options.max_map_nodes;
      entry->world = planning_world_from_map_2d(map_from_image(meta, decode_map_image(u.image, u.image_source)),
                                                u.yaml_source, extrusion);
    } else if (bt || ot) {
      entry->bytes = body.size();
      entry->format = bt ? "octomap_bt" : "octomap_ot";
      entry->world.tree = parse_octree(body, bt, source);
    } else {
      entry->bytes = body.size();
      if (first_invalid_utf8(body) != std::string::npos)
        throw InputError(source, "", "an OctoMap file (it starts '# Octomap OcTree') or a world YAML (UTF-8 text)");
      entry->format = "world_yaml";
      WorldSpec spec = parse_world(body, source);
      WorldBuildOptions build;
      build.max_nodes = options.max_map_nodes;
      entry->world.tree = build_world_octree(spec, build);
      entry->world.spec = std::move(spec);
    }
    entry->world.source = "maps/" + name;
    // Each hidden space's setup now, so the first plans there are as quick as the rest.
    if (entry->world.spec)
      for (const HiddenSpace& h : entry->world.spec->hidden_spaces) {
        UgvPathRequest r = ugv_defaults();
        r.hidden_space = h.name;
        const HiddenSpaceFrame space = ugv_request_space(entry->world, r);
        (void)cached_setup(entry->ugv, ugv_key(space), [&] {
          metrics.record_setup_built("ugv");
          return prepare_ugv_path(entry->world, r, space);
        });
      }
    return entry;
  }

  json map_metadata(const MapEntry& m) const {
    const octomap::OcTree& t = *m.world.tree;
    json j{{"name", m.name},
           {"format", m.format},
           {"bytes", m.bytes},
           {"loaded_at", m.loaded_at},
           {"resolution_m", t.getResolution()},
           {"nodes", t.size()}};
    if (t.size() > 0) {
      double x0, y0, z0, x1, y1, z1;
      t.getMetricMin(x0, y0, z0);
      t.getMetricMax(x1, y1, z1);
      j["known_bounds_m"] = {x0, y0, z0, x1, y1, z1};
    }
    json spaces = json::array();
    if (m.world.spec)
      for (const HiddenSpace& h : m.world.spec->hidden_spaces) {
        const HiddenSpaceFrame f = hidden_space_frame(h);
        spaces.push_back({{"name", h.name},
                          {"floor_z_m", f.floor_z_m},
                          {"bounds_xy_m", {f.lo_m.x(), f.lo_m.y(), f.hi_m.x(), f.hi_m.y()}},
                          {"entry_m", {f.p_WE.x(), f.p_WE.y()}}});
      }
    j["hidden_spaces"] = spaces;
    if (m.world.map_2d) {
      const GridGeometry& g = *m.world.map_2d;
      const HiddenSpaceFrame f = map_2d_frame(g);
      j["map_2d"] = {{"origin_m", {g.origin_x_m, g.origin_y_m}},
                     {"resolution_m", g.resolution_m},
                     {"width", g.width},
                     {"height", g.height},
                     {"bounds_xy_m", {f.lo_m.x(), f.lo_m.y(), f.hi_m.x(), f.hi_m.y()}},
                     {"floor_z_m", f.floor_z_m}};
    }
    return j;
  }

  // A PUT's map: the whole body, or a map_server map as multipart/form-data with the
  // parts "yaml" and "image" (nothing else).
  static MapUpload map_upload(const httplib::Request& req) {
    MapUpload u;
    if (!req.is_multipart_form_data()) {
      u.body = req.body;
      return u;
    }
    for (const auto& [key, part] : req.files)
      if (key != "yaml" && key != "image")
        throw ApiError{400, "INVALID_MAP", fmt::format("{}: expected only the parts yaml and image (a map_server map)", printable(key, 64)), printable(key, 64)};
    for (const char* key : {"yaml", "image"}) {
      if (req.files.count(key) != 1)
        throw ApiError{400, "INVALID_MAP", fmt::format("{0}: expected one part called {0} (a map_server map: its YAML and its image)", key), key};
    }
    u.map_2d = Map2DUpload{req.get_file_value("yaml").content, req.get_file_value("image").content};
    return u;
  }

  // -- plans -----------------------------------------------------------------------

  UgvPathRequest ugv_defaults() const {
    UgvPathRequest r;
    r.robot = {options.robot_ugv, false};
    r.mission = options.mission;
    return r;
  }

  static std::string ugv_key(const HiddenSpaceFrame& s) {
    return fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}", s.lo_m.x(), s.lo_m.y(),
                       s.hi_m.x(), s.hi_m.y(), s.floor_z_m, s.p_WE.x(), s.p_WE.y());
  }

  void plan_ugv(const httplib::Request& req, httplib::Response& res, bool return_path) {
    const auto arrived = Clock::now();
    const Body body(req.body, {"map", "start", "goal", "hidden_space", "bounds", "floor_z_m", "entry",
                               "tether_budget_m", "driven", "deadline_s", "seed"});
    const auto deadline = deadline_of(body, arrived);
    const auto map = find_map(body.required_text("map"));
    UgvPathRequest r = ugv_defaults();
    const auto s = body.numbers("start", 3, "[x, y, yaw] in metres and radians");
    const auto g = body.numbers("goal", 3, "[x, y, yaw] in metres and radians");
    r.start = {s[0], s[1], s[2]};
    r.goal = {g[0], g[1], g[2]};
    r.hidden_space = body.text("hidden_space");
    r.bounds = body.bounds();
    r.floor_z_m = body.optional_number("floor_z_m", -1e6, 1e6, "a height in metres");
    if (body.has("entry")) {
      const auto e = body.numbers("entry", 2, "[x, y] in metres");
      r.p_WE = Eigen::Vector2d(e[0], e[1]);
    }
    r.tether_budget_m = body.optional_number("tether_budget_m", 1e-3, 1000.0, "metres in (0, 1000]");
    if (body.has("driven")) {
      const json& d = body.at("driven");
      if (!d.is_array() || d.size() > 10000) bad_request("driven", "an array of at most 10000 [x, y] points");
      for (std::size_t k = 0; k < d.size(); ++k) {
        const auto p = Body::numbers_of(d[k], fmt::format("driven[{}]", k), 2, "[x, y] in metres");
        r.driven.emplace_back(p[0], p[1]);
      }
    }
    r.mode = return_path ? UgvPathMode::kReturnAlongTether : UgvPathMode::kPlan;
    r.seed = body.seed();
    r.cancelled = cancel_flag(req);
    const std::map<std::string, std::string> fields{{"start", "start"}, {"goal", "goal"},
                                                    {"hidden_space", "hidden_space"}, {"bounds", "bounds"},
                                                    {"p_WE", "entry"}, {"floor_z_m", "floor_z_m"},
                                                    {"tether_budget_m", "tether_budget_m"}, {"driven", "driven"},
                                                    {"time_limit_s", "deadline_s"}};
    with_worker(res, deadline, [&] {
      try {
        const HiddenSpaceFrame space = ugv_request_space(map->world, r);
        const auto setup = cached_setup(map->ugv, ugv_key(space), [&] {
          metrics.record_setup_built("ugv");
          return prepare_ugv_path(map->world, r, space);
        });
        const double left_s = seconds_left(deadline);
        if (left_s < 1e-3) throw ApiError{422, "TIMEOUT", "the deadline passed before the search could start", "deadline_s"};
        r.time_limit_s = std::min(left_s, 3600.0);
        const UgvPathResult result = plan_ugv_path(map->world, r, *setup);
        json out = plan_response(result, std::chrono::duration<double>(Clock::now() - arrived).count(), res);
        if (result.solved) {
          json wraps = json::array();
          for (const WrapPoint& w : result.final_wraps) wraps.push_back({w.p_W.x(), w.p_W.y()});
          out["tether"] = {{"budget_m", result.tether_budget_m},
                           {"length_at_goal_m", result.plan.states.back().tether_length_m},
                           {"wraps_at_goal_m", wraps}};
        }
        send(res, res.status, out);
      } catch (const InputError& e) {
        throw from_input_error(e, fields);
      }
    });
  }

  static std::string uav_key(const UavApproachRequest& r) {
    std::string k = fmt::format("{},{}", to_string(r.unknown), r.tether_released_m ? fmt::format("{:.17g}", *r.tether_released_m) : "-");
    if (r.bounds)
      k += fmt::format(",{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}", r.bounds->lo.x(), r.bounds->lo.y(),
                       r.bounds->lo.z(), r.bounds->hi.x(), r.bounds->hi.y(), r.bounds->hi.z());
    return k;
  }

  void plan_uav(const httplib::Request& req, httplib::Response& res) {
    const auto arrived = Clock::now();
    const Body body(req.body, {"map", "start", "goal", "hidden_space", "tether_released_m", "bounds", "unknown",
                               "planner", "deadline_s", "seed"});
    const auto deadline = deadline_of(body, arrived);
    const auto map = find_map(body.required_text("map"));
    UavApproachRequest r;
    r.robot = {options.robot_uav, false};
    r.mission = options.mission;
    const auto s = body.numbers("start", 4, "[x, y, z, yaw] in metres and radians");
    r.start.x_m = s[0];
    r.start.y_m = s[1];
    r.start.z_m = s[2];
    r.start.yaw_rad = s[3];
    if (body.has("goal")) {
      const auto g = body.numbers("goal", 4, "[x, y, z, yaw] in metres and radians");
      Waypoint w;
      w.x_m = g[0];
      w.y_m = g[1];
      w.z_m = g[2];
      w.yaw_rad = g[3];
      r.goal = w;
    }
    r.hidden_space = body.text("hidden_space");
    if (r.goal.has_value() == !r.hidden_space.empty()) bad_request("goal", "either goal [x, y, z, yaw] or hidden_space (not both)");
    r.tether_released_m = body.optional_number("tether_released_m", 0.0, 100.0, "metres in [0, 100]");
    r.bounds = body.bounds();
    try {
      r.unknown = parse_unknown_policy(body.text("unknown", "free"), "unknown");
    } catch (const InputError&) {
      bad_request("unknown", "free or occupied", body.text("unknown"));
    }
    r.planner = body.text("planner", "rrtconnect");
    r.seed = body.seed();
    r.cancelled = cancel_flag(req);
    const std::map<std::string, std::string> fields{{"start", "start"}, {"goal", "goal"}, {"hidden_space", "hidden_space"},
                                                    {"tether_released_m", "tether_released_m"}, {"bounds", "bounds"},
                                                    {"planner", "planner"}, {"time_limit_s", "deadline_s"}};
    with_worker(res, deadline, [&] {
      try {
        const auto setup = cached_setup(map->uav, uav_key(r), [&] {
          metrics.record_setup_built("uav");
          UavApproachSetup made = prepare_uav_approach(map->world, r);
          // The same collision map checks this map's UAV plans: validating a plan
          // just made costs no second build.
          offer_setup(map->validation,
                      collision_map_options_key(uav_map_options(map->world.spec, r.unknown, made.geofence)),
                      MapEntry::ValidationMap{made.map});
          return made;
        });
        const double left_s = seconds_left(deadline);
        if (left_s < 1e-3) throw ApiError{422, "TIMEOUT", "the deadline passed before the search could start", "deadline_s"};
        r.time_limit_s = std::min(left_s, 3600.0);
        const PlanResult result = plan_uav_approach(map->world, r, *setup);
        const json out = plan_response(result, std::chrono::duration<double>(Clock::now() - arrived).count(), res);
        send(res, res.status, out);
      } catch (const InputError& e) {
        throw from_input_error(e, fields);
      }
    });
  }

  void validate(const httplib::Request& req, httplib::Response& res) {
    const auto arrived = Clock::now();
    const Body body(req.body, {"map", "plan", "builtin_shapes", "bounds", "tether_budget_m", "entry", "unknown",
                               "floor_z_m", "deadline_s"});
    const auto deadline = deadline_of(body, arrived);
    const auto map = find_map(body.required_text("map"));
    if (!body.has("plan") || !body.at("plan").is_object()) bad_request("plan", "a plan JSON object (docs/planning.md)");
    PlanFile plan;
    try {
      plan = parse_plan(body.at("plan").dump(), "plan");
    } catch (const InputError& e) {
      throw ApiError{400, "INVALID_REQUEST", printable(e.what()), e.field().empty() ? "plan" : "plan." + e.field()};
    }
    ValidateRequest v;
    // The robot is the service's, by the plan's kind: a request never names a file
    // on the server.
    v.robot_urdf = plan.robot == PlanRobot::kUgv ? options.robot_ugv : options.robot_uav;
    if (v.robot_urdf->empty()) v.robot_urdf = find_model(plan.robot == PlanRobot::kUgv ? "miniugv.urdf" : "m100.urdf");
    if (body.has("builtin_shapes")) {
      if (!body.at("builtin_shapes").is_boolean()) bad_request("builtin_shapes", "true or false");
      v.builtin_shapes = body.at("builtin_shapes").get<bool>();
    }
    v.mission = options.mission_path;
    v.bounds = body.bounds();
    v.tether_budget_m = body.optional_number("tether_budget_m", 1e-3, 1000.0, "metres in (0, 1000]");
    if (body.has("entry")) {
      const auto e = body.numbers("entry", 2, "[x, y] in metres");
      v.p_WE = Eigen::Vector2d(e[0], e[1]);
    }
    if (body.has("unknown")) {
      try {
        v.unknown = parse_unknown_policy(body.text("unknown"), "unknown");
      } catch (const InputError&) {
        bad_request("unknown", "free or occupied", body.text("unknown"));
      }
    }
    v.floor_z_m = body.optional_number("floor_z_m", -1e6, 1e6, "a height in metres");
    // A plan can ask for a million collision checks: the deadline bounds them too.
    const auto stop = cancel_flag(req);
    v.cancelled = [stop, deadline] { return Clock::now() >= deadline || stop(); };
    v.collision_map = [this, &map](const octomap::OcTree& tree, const CollisionMapOptions& o) {
      return cached_setup(map->validation, collision_map_options_key(o), [&] {
               metrics.record_setup_built("validation");
               return MapEntry::ValidationMap{CollisionMap::build(tree, o)};
             })->map;
    };
    with_worker(res, deadline, [&] {
      try {
        const ValidationReport report = validate_plan(std::move(plan), map->world, v, "plan");
        json out = json::parse(validation_report_to_json(report));
        out["planning_time_s"] = std::chrono::duration<double>(Clock::now() - arrived).count();
        send(res, 200, out);
      } catch (const InputError& e) {
        throw ApiError{400, "INVALID_REQUEST", printable(e.what()), e.field().empty() ? "plan" : e.field()};
      } catch (const ValidationCancelled&) {
        if (Clock::now() >= deadline)
          throw ApiError{422, "TIMEOUT", "the deadline passed before the plan was checked whole", "deadline_s"};
        throw ApiError{503, "CANCELLED", "the validation was stopped (the service is stopping)", ""};
      }
    });
  }

  void next_goal(const httplib::Request& req, httplib::Response& res) {
    const auto arrived = Clock::now();
    const Body body(req.body, {"grid", "object_probability", "object_confidence", "pose", "velocity", "method",
                               "ir_fov_rad", "ir_range_m", "camera_range_m", "seed", "deadline_s"});
    const auto deadline = deadline_of(body, arrived);
    NextGoalRequest r;
    r.mission = options.mission;
    if (!body.has("grid") || !body.at("grid").is_object())
      bad_request("grid", "an object: origin, resolution_m, width, height, occupancy");
    const json& grid = body.at("grid");
    for (const auto& [key, value] : grid.items())
      if (key != "origin" && key != "resolution_m" && key != "width" && key != "height" && key != "occupancy")
        bad_request("grid." + key, "one of the fields origin, resolution_m, width, height, occupancy", key);
    const auto dim = [&](const char* key) {
      if (!grid.contains(key) || !grid.at(key).is_number_integer() || grid.at(key).get<long long>() < 1 ||
          grid.at(key).get<long long>() > 4096)
        bad_request(std::string("grid.") + key, "an integer in [1, 4096]", grid.value(key, json()).dump());
      return static_cast<int>(grid.at(key).get<long long>());
    };
    r.geometry.width = dim("width");
    r.geometry.height = dim("height");
    if (!grid.contains("resolution_m")) bad_request("grid.resolution_m", "metres in [0.005, 10] (required)");
    r.geometry.resolution_m = Body::number_of(grid.at("resolution_m"), "grid.resolution_m", 0.005, 10.0, "metres in [0.005, 10]");
    if (!grid.contains("origin")) bad_request("grid.origin", "[x, y] in metres (required)");
    const auto o = Body::numbers_of(grid.at("origin"), "grid.origin", 2, "[x, y] in metres");
    r.geometry.origin_x_m = o[0];
    r.geometry.origin_y_m = o[1];
    const std::size_t n = r.geometry.size();
    if (!grid.contains("occupancy") || !grid.at("occupancy").is_array() || grid.at("occupancy").size() != n)
      bad_request("grid.occupancy", fmt::format("an array of width x height = {} cells, each -1 (unknown) or 0..100", n));
    r.occupancy.reserve(n);
    for (std::size_t k = 0; k < n; ++k) {
      const json& v = grid.at("occupancy")[k];
      if (!v.is_number_integer() || v.get<long long>() < -1 || v.get<long long>() > 100)
        bad_request(fmt::format("grid.occupancy[{}]", k), "-1 (unknown) or an integer 0..100 (percent occupied)", v.dump());
      const long long x = v.get<long long>();
      r.occupancy.push_back(x < 0 ? -1.0f : static_cast<float>(x) / 100.0f);
    }
    const auto per_cell = [&](const char* key, const char* what, std::vector<float>& out) {
      if (!body.has(key)) return;
      const json& q = body.at(key);
      if (!q.is_array() || q.size() != n) bad_request(key, fmt::format("an array of {} values, {} each", n, what));
      out.reserve(n);
      for (std::size_t k = 0; k < n; ++k)
        out.push_back(static_cast<float>(Body::number_of(q[k], fmt::format("{}[{}]", key, k), 0.0, 1.0, what)));
    };
    per_cell("object_probability", "a probability in [0, 1]", r.object_probability);
    per_cell("object_confidence", "a confidence in [0, 1]", r.object_confidence);
    const auto p = body.numbers("pose", 3, "[x, y, yaw] in metres and radians");
    r.pose = {p[0], p[1], p[2]};
    if (body.has("velocity")) {
      const auto v = body.numbers("velocity", 2, "[vx, vy] in m/s");
      r.velocity_W = {v[0], v[1]};
    }
    r.method = body.text("method", "cdos");
    if (auto v = body.optional_number("ir_fov_rad", 1e-3, 6.3, "radians in (0, 2 pi]")) r.ir_fov_rad = *v;
    if (auto v = body.optional_number("ir_range_m", 0.01, 100.0, "metres in (0, 100]")) r.ir_range_m = *v;
    if (auto v = body.optional_number("camera_range_m", 0.01, 100.0, "metres in (0, 100]")) r.camera_range_m = *v;
    r.seed = body.seed();
    with_worker(res, deadline, [&] {
      try {
        const auto goal = next_exploration_goal(r);
        const double wall_s = std::chrono::duration<double>(Clock::now() - arrived).count();
        if (!goal) {
          json out = error_body({422, "NO_FRONTIER", "no frontier is reachable: nothing left to explore from here", ""});
          out["planning_time_s"] = wall_s;
          send(res, 422, out);
          return;
        }
        json path = json::array();
        for (const Eigen::Vector2d& q : goal->path_W) path.push_back({q.x(), q.y()});
        json g{{"x_m", goal->p_W.x()}, {"y_m", goal->p_W.y()}, {"cell", {goal->cell.i, goal->cell.j}},
               {"score", goal->score}, {"reason", goal->reason}, {"path_m", path}};
        g["heading_rad"] = goal->heading_rad ? json(*goal->heading_rad) : json(nullptr);
        send(res, 200, json{{"goal", g}, {"method", r.method}, {"planning_time_s", wall_s}});
      } catch (const InputError& e) {
        throw from_input_error(e, {{"pose", "pose"}, {"method", "method"}, {"velocity", "velocity"}});
      }
    });
  }

  // -- routing ---------------------------------------------------------------------

  template <typename Handler>
  httplib::Server::Handler route(const std::string& label, Handler handler) {
    return [this, label, handler](const httplib::Request& req, httplib::Response& res) {
      const auto t0 = Clock::now();
      ++in_flight;
      try {
        handler(req, res);
      } catch (const ApiError& e) {
        send(res, e.http, error_body(e));
      } catch (const InputError& e) {
        send(res, 400, error_body({400, "INVALID_REQUEST", printable(e.what()), e.field()}));
      } catch (const std::bad_alloc&) {
        send(res, 507, error_body({507, "INSUFFICIENT_STORAGE", "the request needs more memory than the service has", ""}));
      } catch (const std::exception& e) {
        send(res, 500, error_body({500, "INTERNAL", printable(e.what()), ""}));
      }
      --in_flight;
      metrics.record(label, res.status, std::chrono::duration<double>(Clock::now() - t0).count());
    };
  }

  void install_routes() {
    auto& s = server;
    s.set_payload_max_length(options.max_body_bytes);
    s.set_keep_alive_max_count(1000);
    // Answers are small and clients wait for them: without TCP_NODELAY, Nagle's
    // algorithm and the client's delayed ACK hold each answer's last segment ~40 ms.
    s.set_tcp_nodelay(true);
    // A request's own wait for a worker is bounded by Admission; the HTTP threads must
    // outnumber workers + queue so that a request past the queue is answered 503 at
    // once instead of waiting unseen for a thread.
    const std::size_t threads = static_cast<std::size_t>(options.workers + options.queue + 8);
    s.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };

    s.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
      if (req.path == "/healthz") return httplib::Server::HandlerResponse::Unhandled;
      if (!options.token.empty()) {
        const std::string auth = req.get_header_value("Authorization");
        const std::string prefix = "Bearer ";
        if (auth.rfind(prefix, 0) != 0 || !same_token(auth.substr(prefix.size()), options.token)) {
          res.set_header("WWW-Authenticate", "Bearer realm=\"ferret-plannerd\"");
          send(res, 401, error_body({401, "UNAUTHORIZED", auth.empty() ? "Authorization: expected a bearer token" : "Authorization: the bearer token is not the service's", "Authorization"}));
          metrics.record("auth", 401, 0.0);
          return httplib::Server::HandlerResponse::Handled;
        }
      }
      if (draining && req.path != "/readyz" && req.path != "/metrics") {
        res.set_header("Retry-After", "5");
        send(res, 503, error_body({503, "DRAINING", "the service is shutting down", ""}));
        metrics.record("draining", 503, 0.0);
        return httplib::Server::HandlerResponse::Handled;
      }
      return httplib::Server::HandlerResponse::Unhandled;
    });
    // An exception that escapes a route (none should): a JSON 500, without cpp-httplib's
    // default EXCEPTION_WHAT header, which would hand the client the exception's text.
    s.set_exception_handler([this](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
      res.headers.clear();
      send(res, 500, error_body({500, "INTERNAL", "the service failed to answer this request", ""}));
      metrics.record("other", 500, 0.0);
    });
    s.set_error_handler([this](const httplib::Request& req, httplib::Response& res) {
      if (!res.body.empty()) return;  // a route's own error
      const int st = res.status;
      std::string code = "NOT_FOUND", msg = "no route " + printable(req.method + " " + req.path, 120);
      if (st == 413) {
        code = "PAYLOAD_TOO_LARGE";
        msg = fmt::format("body: expected at most {} bytes", options.max_body_bytes);
      } else if (st == 400) {
        code = "INVALID_REQUEST";
        msg = "a malformed HTTP request";
      } else if (st != 404) {
        code = "HTTP_" + std::to_string(st);
        msg = "the request could not be served";
      }
      send(res, st, error_body({st, code, msg, st == 413 ? "body" : ""}));
      metrics.record("other", st, 0.0);
    });

    s.Get("/healthz", route("/healthz", [](const httplib::Request&, httplib::Response& res) {
      send(res, 200, json{{"status", "ok"}});
    }));
    s.Get("/readyz", route("/readyz", [this](const httplib::Request&, httplib::Response& res) {
      if (draining) {
        send(res, 503, json{{"status", "draining"}});
        return;
      }
      send(res, 200, json{{"status", "ready"}, {"maps", map_count()}});
    }));
    s.Get("/metrics", route("/metrics", [this](const httplib::Request&, httplib::Response& res) {
      const auto [active, waiting] = admission.load();
      res.status = 200;
      res.set_content(metrics.text(waiting, active, map_count(), draining), "text/plain; version=0.0.4");
    }));

    const std::string name_re = "/v1/maps/([^/]+)";
    s.Put(name_re, route("/v1/maps/{name}", [this](const httplib::Request& req, httplib::Response& res) {
      const auto arrived = Clock::now();
      const std::string name = req.matches[1];
      if (!valid_map_name(name))
        bad_request("name", "1 to 64 letters, digits, '_', '-' or '.'", name);
      {
        const std::lock_guard lock(maps_mutex);
        if (!maps.count(name) && maps.size() >= options.max_maps)
          throw ApiError{507, "TOO_MANY_MAPS", fmt::format("maps: the service holds its limit of {} (DELETE one first)", options.max_maps), "name"};
      }
      // Loading a map is work like planning: it takes a worker, within the longest deadline.
      const auto deadline = arrived + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(options.max_deadline_s));
      with_worker(res, deadline, [&] {
        std::shared_ptr<MapEntry> entry;
        const MapUpload upload = map_upload(req);
        try {
          entry = map_builder.run_here([&] { return load_map(name, upload, "body"); });
        } catch (const InputError& e) {
          // A map_server map's errors name their part (yaml, image), a whole body's "body".
          const std::string part = upload.map_2d ? e.source() : "body";
          throw ApiError{400, "INVALID_MAP", printable(e.what()), e.field().empty() ? part : part + "." + e.field()};
        }
        bool replaced = false;
        {
          const std::lock_guard lock(maps_mutex);
          replaced = maps.count(name) > 0;
          if (!replaced && maps.size() >= options.max_maps)
            throw ApiError{507, "TOO_MANY_MAPS", fmt::format("maps: the service holds its limit of {}", options.max_maps), "name"};
          maps[name] = entry;
        }
        send(res, replaced ? 200 : 201, map_metadata(*entry));
      });
    }));
    s.Get(name_re, route("/v1/maps/{name}", [this](const httplib::Request& req, httplib::Response& res) {
      send(res, 200, map_metadata(*find_map(req.matches[1])));
    }));
    s.Delete(name_re, route("/v1/maps/{name}", [this](const httplib::Request& req, httplib::Response& res) {
      const std::string name = req.matches[1];
      const std::lock_guard lock(maps_mutex);
      if (maps.erase(name) == 0)
        throw ApiError{404, "UNKNOWN_MAP", fmt::format("map: no map called '{}'", printable(name, 64)), "name"};
      res.status = 204;
    }));
    s.Get("/v1/maps", route("/v1/maps", [this](const httplib::Request&, httplib::Response& res) {
      std::vector<std::shared_ptr<MapEntry>> all;
      {
        const std::lock_guard lock(maps_mutex);
        for (const auto& [name, m] : maps) all.push_back(m);
      }
      json list = json::array();
      for (const auto& m : all) list.push_back(map_metadata(*m));
      send(res, 200, json{{"maps", list}});
    }));
    s.Post("/v1/plan/ugv", route("/v1/plan/ugv", [this](const httplib::Request& req, httplib::Response& res) {
      plan_ugv(req, res, false);
    }));
    s.Post("/v1/plan/ugv/return", route("/v1/plan/ugv/return", [this](const httplib::Request& req, httplib::Response& res) {
      plan_ugv(req, res, true);
    }));
    s.Post("/v1/plan/uav", route("/v1/plan/uav", [this](const httplib::Request& req, httplib::Response& res) {
      plan_uav(req, res);
    }));
    s.Post("/v1/explore/next-goal", route("/v1/explore/next-goal", [this](const httplib::Request& req, httplib::Response& res) {
      next_goal(req, res);
    }));
    s.Post("/v1/validate", route("/v1/validate", [this](const httplib::Request& req, httplib::Response& res) {
      validate(req, res);
    }));

    if (options.json_log)
      s.set_logger([](const httplib::Request& req, const httplib::Response& res) {
        json line{{"ts", utc_now()}, {"method", req.method}, {"path", printable(req.path, 200)},
                  {"status", res.status}, {"remote", req.remote_addr}};
        if (res.status >= 400) {
          const auto body = json::parse(res.body, nullptr, false);
          if (body.is_object() && body.contains("error")) line["code"] = body["error"].value("code", "");
        }
        std::cerr << line.dump() << "\n";
      });
  }
};

PlannerService::PlannerService(PlannerServiceOptions options)
    : impl_(std::make_unique<Impl>(std::move(options))) {
  check_planner_service_options(impl_->options);
  impl_->install_routes();
}

PlannerService::~PlannerService() { stop(); }

int PlannerService::start() {
  Impl& m = *impl_;
  int port = m.options.port;
  if (port == 0) {
    port = m.server.bind_to_any_port(m.options.host);
    if (port < 0) throw std::runtime_error("ferret-plannerd: cannot bind " + m.options.host);
  } else if (!m.server.bind_to_port(m.options.host, port)) {
    throw std::runtime_error(fmt::format("ferret-plannerd: cannot bind {}:{} (in use, or not an address of this machine)", m.options.host, port));
  }
  m.thread = std::thread([&m] { m.server.listen_after_bind(); });
  return port;
}

void PlannerService::drain(double timeout_s) {
  Impl& m = *impl_;
  m.draining = true;
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(timeout_s));
  while (m.in_flight.load() > 0 && Clock::now() < until) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  stop();
}

void PlannerService::stop() {
  Impl& m = *impl_;
  m.cancel_all = true;  // searches still running end at their next check
  m.server.stop();
  if (m.thread.joinable()) m.thread.join();
}

bool PlannerService::draining() const { return impl_->draining; }

void PlannerService::put_map(const std::string& name, const std::string& bytes,
                             const std::string& source) {
  Impl& m = *impl_;
  if (!valid_map_name(name))
    throw InputError(source, "name", "1 to 64 letters, digits, '_', '-' or '.'", name);
  Impl::MapUpload upload;
  upload.body = bytes;
  auto entry = m.map_builder.run_here([&] { return m.load_map(name, upload, source); });
  const std::lock_guard lock(m.maps_mutex);
  if (!m.maps.count(name) && m.maps.size() >= m.options.max_maps)
    throw InputError(source, "", fmt::format("at most {} maps (--max-maps)", m.options.max_maps));
  m.maps[name] = std::move(entry);
}

void PlannerService::put_map_2d(const std::string& name, const std::string& yaml_text,
                                const std::string& image_bytes, const std::string& yaml_source,
                                const std::string& image_source) {
  Impl& m = *impl_;
  if (!valid_map_name(name))
    throw InputError(yaml_source, "name", "1 to 64 letters, digits, '_', '-' or '.'", name);
  Impl::MapUpload upload;
  upload.map_2d = Impl::Map2DUpload{yaml_text, image_bytes, yaml_source, image_source};
  auto entry = m.map_builder.run_here([&] { return m.load_map(name, upload, yaml_source); });
  const std::lock_guard lock(m.maps_mutex);
  if (!m.maps.count(name) && m.maps.size() >= m.options.max_maps)
    throw InputError(yaml_source, "", fmt::format("at most {} maps (--max-maps)", m.options.max_maps));
  m.maps[name] = std::move(entry);
}

}  // namespace ferret
