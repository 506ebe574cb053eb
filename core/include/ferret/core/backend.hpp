#pragma once
// Which implementation of a hardware interface runs: the simulator's, the robot's device,
// or one added later. Each interface (UgvBase, Winch, FlightController) has a registry of
// its backends by name (ugv_base_backends(), winch_backends(), flight_controller_backends())
// and a section in the mission YAML whose `backend` key names one (docs/robots.md).
// Adding a backend is one class and one add() line in that interface's
// register_builtin_*_backends():
//
//   registry.add("hw", "Dynamixel servo on a serial port (DynamixelWinch)",
//                [](const WinchBackendSetup& s) { ... }, {}, BackendTraits{});

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/core/registry.hpp"
#include "ferret/core/yaml_config.hpp"

namespace ferret {

/// The simulator's backend, the default of every interface (a mission file written before
/// backends existed means the simulator).
inline constexpr std::string_view kSimBackend = "sim";

/// What a backend says about itself before it is built.
struct BackendTraits {
  /// Served by the simulated world (its owner builds it); otherwise a device, whose
  /// settings the interface's section must give.
  bool simulated = false;
};

/// A registry of one interface's backends, each built from `Setup` (the interface's
/// parsed section and what the caller brings).
template <class Interface, class Setup>
using BackendRegistry = Registry<Interface, Setup, BackendTraits>;

/// The `backend` key of an interface's section: one of `names` (the interface's
/// registry's, in its order), "sim" when the key is left out. Throws InputError naming the
/// field and listing `names` for another value, a key without a value or a value that is
/// not a string.
[[nodiscard]] std::string read_backend(const yaml::MapReader& section,
                                       const std::vector<std::string>& names);

/// True when the section holds more than its `backend` key and the keys in `common` (what
/// every backend reads): the real device's settings, which are checked whichever backend
/// runs (switching a file to the simulator is one line).
[[nodiscard]] bool has_device_settings(const yaml::MapReader& section,
                                       std::initializer_list<const char*> common = {});

}  // namespace ferret
