#pragma once
// PlannerService::Impl, shared by the service's files: planner_service.cpp (the service:
// options, start, drain, stop), routes.cpp (the HTTP handlers), map_store.cpp (maps),
// with request_parsing.cpp and service_metrics.cpp beside them. cpp-httplib is included
// here, never in the public header.

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "ferret/service/planner_service.hpp"
#include "map_store.hpp"
#include "request_parsing.hpp"
#include "service_metrics.hpp"

// After every header that includes Eigen: httplib pulls in <resolv.h>, whose `_res`
// macro breaks Eigen's templates that name a parameter _res.
// clang-format off: httplib after every header that includes Eigen
#include <httplib.h>
// clang-format on

namespace ferret {
namespace internal {

using Clock = std::chrono::steady_clock;

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

}  // namespace internal

struct PlannerService::Impl {
  explicit Impl(PlannerServiceOptions o)
      : options(std::move(o)), admission(options.workers, options.queue) {}

  PlannerServiceOptions options;
  internal::MapBuilder map_builder;  // before the server: its thread's arena comes first
  httplib::Server server;
  std::thread thread;
  internal::Admission admission;
  internal::ServiceMetrics metrics;
  std::atomic<bool> draining{false}, cancel_all{false};
  std::atomic<int> in_flight{0};

  mutable std::mutex maps_mutex;
  std::map<std::string, std::shared_ptr<internal::MapEntry>> maps;

  using Map2DUpload = internal::Map2DUpload;
  using MapUpload = internal::MapUpload;
  using Clock = internal::Clock;

  // -- maps (map_store.cpp) ---------------------------------------------------------

  /// The map called `name`, or a 404 UNKNOWN_MAP.
  std::shared_ptr<internal::MapEntry> find_map(const std::string& name) const;
  std::size_t map_count() const;
  /// The map in `upload` (map_store.hpp says what it may be), its hidden spaces' setups
  /// built; InputError naming `source` when the bytes are not a map.
  std::shared_ptr<internal::MapEntry> load_map(const std::string& name, const MapUpload& upload,
                                               const std::string& source);
  /// GET /v1/maps/{name}'s answer.
  internal::json map_metadata(const internal::MapEntry& m) const;

  // -- helpers (routes.cpp) ---------------------------------------------------------

  static void send(httplib::Response& res, int status, const internal::json& body);
  Clock::time_point deadline_of(const internal::Body& body, Clock::time_point arrived) const;
  template <typename Work>
  void with_worker(httplib::Response& res, Clock::time_point deadline, Work work);
  static double seconds_left(Clock::time_point deadline);
  std::function<bool()> cancel_flag(const httplib::Request& req);
  internal::json plan_response(const PlanResult& r, double wall_s, httplib::Response& res);
  static MapUpload map_upload(const httplib::Request& req);

  // -- plans (routes.cpp) -----------------------------------------------------------

  UgvPathRequest ugv_defaults() const;
  static std::string ugv_key(const HiddenSpaceFrame& s);
  void plan_ugv(const httplib::Request& req, httplib::Response& res, bool return_path);
  static std::string uav_key(const UavApproachRequest& r);
  void plan_uav(const httplib::Request& req, httplib::Response& res);
  void validate(const httplib::Request& req, httplib::Response& res);
  void next_goal(const httplib::Request& req, httplib::Response& res);

  // -- routing (routes.cpp) ---------------------------------------------------------

  template <typename Handler>
  httplib::Server::Handler route(const std::string& label, Handler handler);
  void install_routes();
};

}  // namespace ferret
