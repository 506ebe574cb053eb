#pragma once
// The miniUGV's base chosen by configuration: `ugv.base.backend` in the mission YAML
// names one of ugv_base_backends(), `sim` (the default) or `hw` (HwUgvBase, with the rest
// of the section as its HwUgvConfig; docs/robots.md, "Backends"). A new backend is one
// class and one add() line in register_builtin_ugv_base_backends().
//
//   ugv:
//     base:
//       backend: hw
//       serial: {port: /dev/ttyAMA0}
//       camera: {device: /dev/video0}

#include <yaml-cpp/yaml.h>

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "ferret/core/backend.hpp"
#include "ferret/core/pose.hpp"
#include "ferret/mapping/object_search_params.hpp"
#include "ferret/ugv/hw_ugv_config.hpp"
#include "ferret/ugv/ugv_base.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret::ugv {

struct UgvBaseConfig {
  std::string backend = std::string(kSimBackend);  ///< a name of ugv_base_backends()
  /// How long the base may stand still when told to drive forwards before the mission
  /// takes it to be held by something (a bump, UgvMissionOptions::bump_time_s): longer
  /// than the base takes from a command to motion on its odometry, from rest. Any backend.
  double stall_time_s = 0.3;
  /// The hardware settings: required with `backend: hw`; with `sim`, checked when the
  /// section has them (switching a robot's file to the simulator is one line), unused.
  std::optional<HwUgvConfig> hw;

  /// True when the simulated world serves the backend (ugv_base_backends()' traits).
  [[nodiscard]] bool simulated() const;
};

/// Reads `ugv.base` (`node` may be undefined or null: all defaults, `sim`). Throws
/// InputError naming the file and the field: a backend not registered (listing them), `hw`
/// without serial.port or camera.device, a stall_time_s outside [0.05, 10] s, and every
/// error of hw_ugv_config_from_yaml.
[[nodiscard]] UgvBaseConfig ugv_base_config_from_yaml(const YAML::Node& node,
                                                      const std::string& source);
/// The section as a mapping (backend first) that ugv_base_config_from_yaml reads back.
void emit_ugv_base_config(YAML::Emitter& e, const UgvBaseConfig& config);

/// What every backend is built from besides its own settings.
struct UgvBaseContext {
  const RobotDescription& robot;  ///< the miniUGV's URDF
  ObjectSearchParams object_search;
  Pose2 X_WG_start;  ///< where its odometry starts, in the hidden space's frame
};

/// Builds one backend. The simulated base needs the simulated world, which only the
/// simulator has: its owner passes a factory for `sim`.
using UgvBaseFactory =
    std::function<std::unique_ptr<UgvBase>(const UgvBaseConfig&, const UgvBaseContext&)>;

/// What a backend is built from.
struct UgvBaseSetup {
  const UgvBaseConfig& config;
  const UgvBaseContext& context;
  const UgvBaseFactory& sim;  ///< builds the `sim` backend (may be empty elsewhere)
};

using UgvBaseBackendRegistry = BackendRegistry<UgvBase, UgvBaseSetup>;

/// Adds "sim" and "hw".
void register_builtin_ugv_base_backends(UgvBaseBackendRegistry& registry);
/// The miniUGV base's backends, registered on first use.
[[nodiscard]] const UgvBaseBackendRegistry& ugv_base_backends();

/// The backend `config` names, from ugv_base_backends(): `hw` builds HwUgvBase (bringing the robot
/// up, so it throws what HwUgvBase throws); `sim` calls `sim`.
/// @throws std::invalid_argument for `sim` without a sim factory (a caller's bug).
[[nodiscard]] std::unique_ptr<UgvBase> make_ugv_base(const UgvBaseConfig& config,
                                                     const UgvBaseContext& context,
                                                     const UgvBaseFactory& sim = {});

}  // namespace ferret::ugv
