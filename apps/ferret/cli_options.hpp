#pragma once
// The options that mean the same thing in every command, spelt, typed and checked in
// one place so the commands cannot drift apart again. docs/cli.md is the convention;
// every command adds these through the functions below instead of by hand.
//
// Old spellings are kept as hidden aliases (an option in CLI11's empty group, bound to
// the same variable) for one release; docs/cli.md lists them.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "ferret/mission/mission_files.hpp"
#include "ferret/perception/camera_model.hpp"
#include "ferret/planning/collision_map.hpp"
#include "ferret/planning/mission_config.hpp"

namespace ferret {
struct MissionSetupOptions;
}  // namespace ferret

namespace ferret::cli {

/// `--world FILE`: a world YAML, or an OctoMap .bt/.ot.
CLI::Option* add_world_option(CLI::App* cmd, std::string& world, bool required = true,
                              std::string_view what = "world YAML, .bt or .ot");

/// `--robot URDF|NAME`: a URDF path or a shipped model's name (docs/cli.md).
/// `default_text` says what an absent --robot means for this command.
CLI::Option* add_robot_option(CLI::App* cmd, std::string& robot, std::string_view default_text);

/// `--mission YAML`: the mission configuration (config/mission.yaml's format).
/// `config_alias` keeps the old `--config` spelling as a hidden alias; commands where
/// `--config` means something else pass false.
CLI::Option* add_mission_option(CLI::App* cmd, std::string& mission, bool config_alias = true);

/// `-o,--out PATH` (hidden aliases: --output, --output-dir). Not marked required in
/// CLI11 (an alias may carry the value): call require_out() in the callback.
CLI::Option* add_out_option(CLI::App* cmd, std::string& out, std::string_view what);
/// Throws InputError("--out", ...) when `out` is empty.
void require_out(const std::string& out, std::string_view what);
/// The output file `out`, required (require_out) and checked before any work is done
/// (check_output_target): InputError for a directory, a FIFO, a device, a path under
/// a regular file or an unwritable directory.
[[nodiscard]] std::filesystem::path checked_out_file(const std::string& out, std::string_view what);
/// The output directory `out`, required and checked the same way (not an existing
/// non-directory).
[[nodiscard]] std::filesystem::path checked_out_dir(const std::string& out, std::string_view what);
/// For an optional -o: InputError when -o/--out (or an alias) was given an empty value,
/// which would otherwise mean "no output" (or the working directory).
void refuse_empty_out(const CLI::App* cmd, const std::string& out);

/// `--shard I/N` (0 <= I < N): InputError naming the option otherwise. Not `given` on
/// the command line, a Slurm job array's task is the shard (SLURM_ARRAY_TASK_ID less
/// SLURM_ARRAY_TASK_MIN, of SLURM_ARRAY_TASK_COUNT); outside one, `text` (0/1).
[[nodiscard]] std::pair<int, int> parse_shard(const std::string& text, bool given);

/// `--tether-budget M`: the taut tether length the miniUGV may use on the floor,
/// L - l_0 (hidden aliases: --tether, --tether-max).
CLI::Option* add_tether_budget_option(CLI::App* cmd, std::optional<double>& budget_m,
                                      std::string_view default_text);
/// The budget checked: finite, in (0, 1000] m.
[[nodiscard]] std::optional<double> checked_tether_budget(const std::optional<double>& budget_m);

/// `--bounds x0,y0,z0,x1,y1,z1` (metres), one format in every command.
CLI::Option* add_bounds_option(CLI::App* cmd, std::string& bounds, std::string_view meaning);
/// nullopt for "", the box otherwise; InputError unless six finite numbers with
/// x0 < x1, y0 < y1, z0 < z1.
[[nodiscard]] std::optional<Aabb3> parse_bounds(const std::string& text,
                                                const std::string& option = "--bounds");

/// `--seed N`: the run's seed (every simulated or sampled result follows from it).
CLI::Option* add_seed_option(CLI::App* cmd, std::uint64_t& seed, std::string_view what);

/// A hidden alias `name` for an option bound to `value` (same type, same variable).
template <typename T>
CLI::Option* add_hidden_alias(CLI::App* cmd, const std::string& name, T& value) {
  return cmd->add_option(name, value, "")->group("");
}

/// `--camera CAM.yaml`: a ROS camera_info calibration file; the alternative to taking
/// the camera from --robot's URDF by its role.
CLI::Option* add_camera_option(CLI::App* cmd, std::string& camera_yaml, std::string_view role);
/// The camera a command works with: the camera_info file `camera_yaml`, or the camera
/// with `role` (kRoleMarkerCamera, kRoleDepthCamera, kRoleObjectCamera) of the URDF
/// `robot` (a path or a shipped model's name). Exactly one of the two must be given:
/// InputError naming --camera and --robot otherwise, and for a robot without a camera
/// of that role. `mission` may assign the roles (its `roles:` section) when the URDF
/// has no <ferret role> markers.
[[nodiscard]] CameraModel resolve_camera(const std::string& camera_yaml, const std::string& robot,
                                         std::string_view role, const MissionConfig& mission = {});

/// --world, --robot-uav, --robot-ugv, --mission, --method, --planner, --no-landing-zone:
/// the files and choices of one mission (`ferret mission`, `sim-world`, `uav`, `ugv`).
void add_mission_setup_options(CLI::App* sub, MissionSetupOptions& o);
/// `--faults FILE`: the faults a simulated world injects (ferret mission, sim-world).
void add_faults_option(CLI::App* sub, MissionSetupOptions& o);

/// "one of a, b, c": the expectation of an option with a fixed set of values.
[[nodiscard]] std::string one_of(const std::vector<std::string>& choices);
/// Throws InputError(option, "", one_of(choices), value) unless value is a choice.
void check_choice(const std::string& option, const std::string& value,
                  const std::vector<std::string>& choices);

}  // namespace ferret::cli
