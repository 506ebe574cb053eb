#pragma once
// The robot and mission files as every command names them: a shipped model's name or a
// URDF path, a mission YAML or the built-in defaults (docs/cli.md).

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/mission/mission_document.hpp"
#include "ferret/planning/mission_config.hpp"

namespace ferret {

/// The names of the models shipped with ferret (m100, miniugv).
[[nodiscard]] const std::vector<std::string>& shipped_model_names();
/// --robot's value as a file: "" gives `default_model` (a shipped file name such as
/// "miniugv.urdf"); a shipped model's name gives its file; anything else is a path,
/// which must exist. InputError listing the shipped names otherwise.
[[nodiscard]] std::filesystem::path resolve_robot(const std::string& robot,
                                                  std::string_view default_model);

/// The mission YAML parsed once (mission_document.hpp), or the built-in defaults when
/// `path` is empty.
[[nodiscard]] MissionDocument load_mission_document_or_defaults(const std::string& path);
/// Its common sections: for commands that build no robot backend. The backend sections
/// and the UAV mission's keys are checked as well.
[[nodiscard]] MissionConfig load_mission_or_defaults(const std::string& path);

}  // namespace ferret
