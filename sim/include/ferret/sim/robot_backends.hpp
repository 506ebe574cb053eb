#pragma once
// Which backend each hardware interface runs on, from a mission YAML's `ugv` and `uav`
// sections (docs/robots.md, "Backends"):
//
//   ugv:
//     base: {backend: sim}                   # UgvBase: sim | hw (HwUgvBase)
//   uav:
//     winch: {backend: sim}                  # Winch: sim | hw (DynamixelWinch)
//     flight_controller: {backend: sim}      # FlightController: sim | hw (address)
//
// Each `backend` names an entry of that interface's registry (ugv_base_backends(),
// winch_backends(), flight_controller_backends()); another name is an InputError listing
// them.
//
// Every section and key is optional; the default is `sim` everywhere, so every mission
// file written before backends existed still means the simulator.

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <string>

#include "ferret/tether_model/winch_factory.hpp"
#include "ferret/uav/flight_controller_config.hpp"
#include "ferret/ugv/ugv_base_factory.hpp"

namespace ferret {

struct RobotBackends {
  ugv::UgvBaseConfig ugv_base;
  tether::WinchConfig winch;
  FlightControllerConfig flight_controller;

  /// One line for a run's first log lines: "ugv.base: sim, uav.winch: hw (/dev/ttyUSB0),
  /// uav.flight_controller: sim".
  [[nodiscard]] std::string summary() const;
  /// True when the simulated world serves every interface.
  [[nodiscard]] bool all_sim() const;
};

/// Reads the `ugv` and `uav` sections of a parsed mission YAML (`root`: the document; an
/// empty document means all defaults). Throws InputError naming `source` and the field:
/// unknown keys in `ugv` (only `base`) or `uav` (only `winch`, `flight_controller`), and
/// every error of the three sections' readers.
[[nodiscard]] RobotBackends robot_backends_from_yaml(const YAML::Node& root,
                                                     const std::string& source);
/// The same from a mission YAML file (load_mission_config reads the rest of it).
[[nodiscard]] RobotBackends load_robot_backends(const std::filesystem::path& path);
/// YAML text, `ugv:` and `uav:` with every backend and its settings, that
/// robot_backends_from_yaml reads back to the same values.
[[nodiscard]] std::string robot_backends_to_yaml(const RobotBackends& backends);

/// Throws InputError(source, FIELD.backend, "sim (" + why + ")", "'<backend>'") for the
/// first interface that is not simulated: for commands that run only the simulator.
void require_all_sim(const RobotBackends& backends, const std::string& source,
                     const std::string& why);

}  // namespace ferret
