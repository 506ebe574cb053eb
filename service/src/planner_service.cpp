// The planner service: its options checked, its HTTP server started on a thread,
// drained and stopped; maps preloaded. The rest of PlannerService::Impl is in
// routes.cpp (HTTP handlers), map_store.cpp (maps), request_parsing.cpp (request
// bodies) and service_metrics.cpp (Prometheus).

#include "ferret/service/planner_service.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "ferret/core/error.hpp"
#include "ferret/planning/plan_file.hpp"
#include "planner_service_impl.hpp"

namespace ferret {
namespace {

using internal::valid_map_name;
using Clock = internal::Clock;

}  // namespace

// ---------------------------------------------------------------------------------

void check_planner_service_options(const PlannerServiceOptions& o) {
  if (o.port < 0 || o.port > 65535)
    throw InputError("--listen", "port", "a port in [0, 65535]", std::to_string(o.port));
  if (o.workers < 1 || o.workers > 256)
    throw InputError("--workers", "", "an integer in [1, 256]", std::to_string(o.workers));
  if (o.queue < 0 || o.queue > 10000)
    throw InputError("--queue", "", "an integer in [0, 10000]", std::to_string(o.queue));
  if (o.max_body_bytes < 1024 || o.max_body_bytes > (std::size_t{4} << 30))
    throw InputError("--max-body-bytes", "", "bytes in [1024, 4 GiB]",
                     std::to_string(o.max_body_bytes));
  if (!(std::isfinite(o.max_deadline_s) && o.max_deadline_s > 0 && o.max_deadline_s <= 3600))
    throw InputError("--max-deadline", "", "seconds in (0, 3600]",
                     fmt::format("{}", o.max_deadline_s));
  if (!(std::isfinite(o.default_deadline_s) && o.default_deadline_s > 0 &&
        o.default_deadline_s <= o.max_deadline_s))
    throw InputError("--deadline", "", "seconds in (0, --max-deadline]",
                     fmt::format("{}", o.default_deadline_s));
  if (o.max_maps < 1 || o.max_maps > 4096)
    throw InputError("--max-maps", "", "an integer in [1, 4096]", std::to_string(o.max_maps));
  // Both robots must load: a service that cannot plan should not start.
  (void)load_plan_robot(PlanRobot::kUav, {o.robot_uav, false}, o.mission, 0.0, "--robot-uav", "");
  (void)load_plan_robot(PlanRobot::kUgv, {o.robot_ugv, false}, o.mission, 0.0, "--robot-ugv", "");
}

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
    throw std::runtime_error(fmt::format(
        "ferret-plannerd: cannot bind {}:{} (in use, or not an address of this machine)",
        m.options.host, port));
  }
  m.thread = std::thread([&m] { m.server.listen_after_bind(); });
  return port;
}

void PlannerService::drain(double timeout_s) {
  Impl& m = *impl_;
  m.draining = true;
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(timeout_s));
  while (m.in_flight.load() > 0 && Clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
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
    throw InputError(yaml_source, "",
                     fmt::format("at most {} maps (--max-maps)", m.options.max_maps));
  m.maps[name] = std::move(entry);
}

}  // namespace ferret
