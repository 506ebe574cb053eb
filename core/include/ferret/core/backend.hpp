#pragma once
// Which implementation of a hardware interface runs: the simulator's or the robot's.
// Each interface (UgvBase, Winch, FlightController) has a section in the mission YAML
// whose `backend` key picks one, and a factory that builds it (docs/robots.md).

#include <initializer_list>
#include <string_view>

#include "ferret/core/yaml_config.hpp"

namespace ferret {

enum class Backend {
  kSim,  ///< the simulated world's implementation (the default everywhere)
  kHw,   ///< the real device
};

[[nodiscard]] std::string_view to_string(Backend backend);  ///< "sim" / "hw"

/// The `backend` key of an interface's section: `sim` (also when the key is left out) or
/// `hw`. Throws InputError naming the field for another value, a key without a value or
/// a value that is not a string.
[[nodiscard]] Backend read_backend(const yaml::MapReader& section);

/// True when the section holds more than its `backend` key and the keys in `common` (what
/// every backend reads): the real device's settings, which are checked whichever backend
/// runs (switching a file to the simulator is one line).
[[nodiscard]] bool has_device_settings(const yaml::MapReader& section,
                                       std::initializer_list<const char*> common = {});

}  // namespace ferret
