#pragma once
// ferret's planners as a long-lived HTTP/JSON service (`ferret-plannerd`,
// docs/service.md): maps uploaded by name, UAV and tether-aware miniUGV plans, plan
// validation, health, readiness and Prometheus metrics. The planning is the library's
// (uav_approach.hpp, ugv_path.hpp, plan_validation.hpp), so the service answers what
// `ferret plan` and `ferret validate` answer. No HTTP, OMPL or FCL types here.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "ferret/planning/mission_config.hpp"

namespace ferret {

struct PlannerServiceOptions {
  std::string host = "127.0.0.1";          ///< loopback unless asked ("0.0.0.0": every interface)
  int port = 8642;                         ///< 0: any free port (start() returns it)
  int workers = 2;                         ///< requests planning (or loading a map) at once
  int queue = 32;                          ///< requests waiting for a worker; past it: 503
  std::size_t max_body_bytes = 64u << 20;  ///< larger bodies: 413
  double default_deadline_s = 1.0;         ///< a request's deadline when it names none
  double max_deadline_s = 30.0;            ///< the longest deadline a request may ask for
  std::size_t max_maps = 32;               ///< maps held at once; a PUT past it: 507
  /// A map built from a world YAML may have at most this many OctoMap nodes.
  std::size_t max_map_nodes = 8'000'000;
  std::string token;                ///< bearer token for every route but /healthz; empty: none
  bool json_log = false;            ///< one JSON line a request on stderr
  std::filesystem::path robot_uav;  ///< URDF of the UAV; empty: the shipped m100.urdf
  std::filesystem::path robot_ugv;  ///< URDF of the miniUGV; empty: the shipped miniugv.urdf
  MissionConfig mission;            ///< limits, tether L and l_0
  /// The file `mission` came from, if any: /v1/validate reads it as `ferret validate
  /// --mission` does.
  std::optional<std::filesystem::path> mission_path;
};

/// Checks options a user gave (`--check-config` runs it and loads both robots): one
/// InputError naming the option for a value out of range or a robot that does not load.
void check_planner_service_options(const PlannerServiceOptions& options);

class PlannerService {
 public:
  explicit PlannerService(PlannerServiceOptions options);
  ~PlannerService();
  PlannerService(const PlannerService&) = delete;
  PlannerService& operator=(const PlannerService&) = delete;

  /// Binds and serves on a background thread; returns the port. Throws
  /// std::runtime_error when the address cannot be bound.
  int start();
  /// Stops taking work (new requests get 503, /readyz says draining), waits for the
  /// requests in flight (each ends by its deadline) up to `timeout_s`, then stops.
  void drain(double timeout_s);
  /// Stops at once (requests in flight are cut off).
  void stop();
  [[nodiscard]] bool draining() const;
  /// Loads a map as PUT /v1/maps/{name} would (the bytes of a .bt/.ot file or a world
  /// YAML as the whole body): `ferret-plannerd --map NAME=FILE` preloads with it. InputError naming
  /// `source` when the bytes are not a map.
  void put_map(const std::string& name, const std::string& bytes, const std::string& source);
  /// Loads a map_server map as a multipart PUT would: its YAML's text and its image's
  /// bytes (the YAML's `image` key is not opened). InputError naming `yaml_source` or
  /// `image_source`.
  void put_map_2d(const std::string& name, const std::string& yaml_text,
                  const std::string& image_bytes, const std::string& yaml_source,
                  const std::string& image_source);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ferret
