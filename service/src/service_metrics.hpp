#pragma once
// The counters behind GET /metrics, in Prometheus' text exposition format (version
// 0.0.4). Routes are labelled by their pattern ("/v1/maps/{name}"), never by the raw
// path, so the number of series stays bounded whatever clients send.

#include <array>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <utility>

namespace ferret::internal {

/// How a plan request ended, as GET /metrics counts it.
enum class PlanOutcome { kSolved, kFailed, kCancelled };

class ServiceMetrics {
 public:
  static constexpr std::array<double, 13> kBuckets_s{0.001, 0.0025, 0.005, 0.01, 0.025, 0.05, 0.1,
                                                     0.25,  0.5,    1.0,   2.5,  5.0,   10.0};
  /// One request answered: its route pattern, HTTP status and wall time.
  void record(const std::string& route, int status, double seconds);
  /// A plan answered: solved, failed, or cancelled (its client went away, a shutdown).
  void record_plan(PlanOutcome outcome);
  /// A map's setup built (a cache miss): "uav", "ugv" or "validation".
  void record_setup_built(const char* kind);
  /// The whole exposition; gauges passed in as they are now.
  [[nodiscard]] std::string text(int queue_depth, int active, std::size_t maps_loaded,
                                 bool draining) const;

 private:
  struct Histogram {
    std::array<std::uint64_t, kBuckets_s.size()> counts{};
    std::uint64_t count = 0;
    double sum_s = 0.0;
  };
  mutable std::mutex mutex_;
  std::map<std::pair<std::string, int>, std::uint64_t> requests_;
  std::map<std::string, Histogram> latency_;
  std::uint64_t plans_solved_ = 0, plans_failed_ = 0, plans_cancelled_ = 0;
  std::map<std::string, std::uint64_t> setups_built_{{"uav", 0}, {"ugv", 0}, {"validation", 0}};
};

/// The process's resident memory in bytes (/proc/self/statm), 0 where unknown.
[[nodiscard]] std::uint64_t resident_memory_bytes();

}  // namespace ferret::internal
