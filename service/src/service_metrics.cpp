#include "service_metrics.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <fstream>

namespace ferret::internal {

void ServiceMetrics::record(const std::string& route, int status, double seconds) {
  const std::lock_guard lock(mutex_);
  ++requests_[{route, status}];
  Histogram& h = latency_[route];
  for (std::size_t k = 0; k < kBuckets_s.size(); ++k)
    if (seconds <= kBuckets_s[k]) ++h.counts[k];  // cumulative, as Prometheus wants
  ++h.count;
  h.sum_s += seconds;
}

void ServiceMetrics::record_plan(PlanOutcome outcome) {
  const std::lock_guard lock(mutex_);
  switch (outcome) {
    case PlanOutcome::kSolved:
      ++plans_solved_;
      break;
    case PlanOutcome::kCancelled:
      ++plans_cancelled_;
      break;
    case PlanOutcome::kFailed:
      ++plans_failed_;
      break;
  }
}

void ServiceMetrics::record_setup_built(const char* kind) {
  const std::lock_guard lock(mutex_);
  ++setups_built_[kind];
}

std::string ServiceMetrics::text(int queue_depth, int active, std::size_t maps_loaded,
                                 bool draining) const {
  const std::lock_guard lock(mutex_);
  std::string out;
  out += "# HELP ferret_requests_total Requests answered, by route pattern and HTTP status.\n";
  out += "# TYPE ferret_requests_total counter\n";
  for (const auto& [key, n] : requests_)
    out += fmt::format("ferret_requests_total{{route=\"{}\",code=\"{}\"}} {}\n", key.first,
                       key.second, n);
  out += "# HELP ferret_request_duration_seconds Wall time from request to response.\n";
  out += "# TYPE ferret_request_duration_seconds histogram\n";
  for (const auto& [route, h] : latency_) {
    for (std::size_t k = 0; k < kBuckets_s.size(); ++k)
      out += fmt::format("ferret_request_duration_seconds_bucket{{route=\"{}\",le=\"{:g}\"}} {}\n",
                         route, kBuckets_s[k], h.counts[k]);
    out += fmt::format("ferret_request_duration_seconds_bucket{{route=\"{}\",le=\"+Inf\"}} {}\n",
                       route, h.count);
    out +=
        fmt::format("ferret_request_duration_seconds_sum{{route=\"{}\"}} {:.6f}\n", route, h.sum_s);
    out +=
        fmt::format("ferret_request_duration_seconds_count{{route=\"{}\"}} {}\n", route, h.count);
  }
  out +=
      "# HELP ferret_plans_total Plans answered: solved, failed, or cancelled (client gone, "
      "shutdown).\n";
  out += "# TYPE ferret_plans_total counter\n";
  out += fmt::format("ferret_plans_total{{result=\"solved\"}} {}\n", plans_solved_);
  out += fmt::format("ferret_plans_total{{result=\"failed\"}} {}\n", plans_failed_);
  out += fmt::format("ferret_plans_total{{result=\"cancelled\"}} {}\n", plans_cancelled_);
  out +=
      "# HELP ferret_setups_built_total What the maps' plans and validations share, built (cache "
      "misses).\n";
  out += "# TYPE ferret_setups_built_total counter\n";
  for (const auto& [kind, n] : setups_built_)
    out += fmt::format("ferret_setups_built_total{{kind=\"{}\"}} {}\n", kind, n);
  out += "# HELP ferret_queue_depth Requests waiting for a worker.\n";
  out += "# TYPE ferret_queue_depth gauge\n";
  out += fmt::format("ferret_queue_depth {}\n", queue_depth);
  out += "# HELP ferret_active_requests Requests holding a worker.\n";
  out += "# TYPE ferret_active_requests gauge\n";
  out += fmt::format("ferret_active_requests {}\n", active);
  out += "# HELP ferret_maps_loaded Maps held by the service.\n";
  out += "# TYPE ferret_maps_loaded gauge\n";
  out += fmt::format("ferret_maps_loaded {}\n", maps_loaded);
  out += "# HELP ferret_draining 1 while the service drains before it stops.\n";
  out += "# TYPE ferret_draining gauge\n";
  out += fmt::format("ferret_draining {}\n", draining ? 1 : 0);
  out += "# HELP process_resident_memory_bytes Resident memory of the service.\n";
  out += "# TYPE process_resident_memory_bytes gauge\n";
  out += fmt::format("process_resident_memory_bytes {}\n", resident_memory_bytes());
  return out;
}

std::uint64_t resident_memory_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t size_pages = 0, resident_pages = 0;
  if (!(statm >> size_pages >> resident_pages)) return 0;
  return resident_pages * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE));
}

}  // namespace ferret::internal
