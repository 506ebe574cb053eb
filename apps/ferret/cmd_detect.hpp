#pragma once
// `ferret detect marker | landing | object`: one subcommand group shared by three
// files (cmd_detect.cpp, cmd_detect_landing.cpp, cmd_detect_object.cpp), each of
// which registers its own subcommand with a CommandRegistration and asks for the
// group here:
//
//   const CommandRegistration kDetectLanding{"detect landing", [](CLI::App& app) {
//     auto* sub = detect_group(app).add_subcommand("landing", "...");
//     ...
//   }};
//
// The group is created by whichever registration runs first, so the order of the
// registrations does not matter.

#include <CLI/CLI.hpp>

namespace ferret::cli {

/// The `detect` subcommand of `app`, created on first use (it requires one of its
/// subcommands).
[[nodiscard]] CLI::App& detect_group(CLI::App& app);

}  // namespace ferret::cli
