#pragma once
// The winch controllers by name: "mpc" (TautTetherMpc) and "baseline" (FeedForwardPid),
// on core's Registry, filled by register_builtin_tether_controllers() the first time
// tether_controllers() is asked. Each controller has its own options beside the common
// TautControlOptions, read and emitted here (the mission YAML's `uav.winch_control`,
// tether-sim's --sim-config sections `mpc` and `baseline`):
//
//   uav:
//     winch_controller: mpc
//     winch_control:
//       mpc: {horizon: 20, weight_slack: 100}
//       baseline: {kp_per_s: 16}
//
// A new controller is one class and one add() line in
// register_builtin_tether_controllers() (with its options, a member of
// WinchControllerOptions and its reader).

#include <yaml-cpp/yaml.h>

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/core/registry.hpp"
#include "ferret/core/yaml_config.hpp"
#include "ferret/tether_model/feedforward_pid.hpp"
#include "ferret/tether_model/taut_mpc.hpp"

namespace ferret::tether {

/// Each controller's own options. Their `control` members are not used: the
/// controller gets WinchControllerSetup::control.
struct WinchControllerOptions {
  TautTetherMpc::Options mpc;
  FeedForwardPid::Options baseline;

  /// The options make_tether_controller() gives: the defaults, the MPC's estimation of
  /// the miniUGV (velocity error, response identification) as `control` has it.
  [[nodiscard]] static WinchControllerOptions following(const TautControlOptions& control);
};

/// What a winch controller is built from.
struct WinchControllerSetup {
  TautControlOptions control;
  WinchControllerOptions own;
  std::shared_ptr<const RequiredLengthModel> model;
};

using TetherControllerRegistry = Registry<TetherController, WinchControllerSetup>;

/// A controller of tether_controllers() (winch_controllers.hpp), "mpc" or "baseline",
/// with WinchControllerOptions::following(options): the MPC gets
/// options.ugv_velocity_error (default off), not TautTetherMpc's default.
/// @throws InputError listing the names for another name.
[[nodiscard]] std::unique_ptr<TetherController> make_tether_controller(
    std::string_view name, const TautControlOptions& options,
    std::shared_ptr<const RequiredLengthModel> model);

/// The names of tether_controllers(), in the order registered.
[[nodiscard]] std::vector<std::string> tether_controller_names();

/// Adds "mpc" and "baseline".
void register_builtin_tether_controllers(TetherControllerRegistry& registry);
/// The winch controllers, registered on first use.
[[nodiscard]] const TetherControllerRegistry& tether_controllers();

/// Reads the `mpc` and `baseline` sections of `r` (a mapping; each optional) over `o`.
/// Unknown keys, values out of range and keys without values are InputErrors naming
/// the file and the field.
void read_winch_controller_options(const yaml::MapReader& r, WinchControllerOptions& o);
/// The same keys, each controller's section a mapping, for read_winch_controller_options.
void emit_winch_controller_options(YAML::Emitter& e, const WinchControllerOptions& o);
/// One controller's section (`r` is the section itself).
void read_mpc_options(const yaml::MapReader& r, TautTetherMpc::Options& o);
void read_baseline_options(const yaml::MapReader& r, FeedForwardPid::Options& o);

}  // namespace ferret::tether
