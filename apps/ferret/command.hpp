#pragma once
// The `ferret` CLI is one executable with subcommands. Each subcommand lives in its
// own apps/ferret/cmd_<name>.cpp and registers itself with a static
// CommandRegistration, so adding one is one new file:
//
//   const ferret::cli::CommandRegistration kWorld{"world", [](CLI::App& app) {
//     auto* sub = app.add_subcommand("world", "Build and slice 3D worlds");
//     ...
//     sub->callback([=] { ...; });  // throw InputError for bad input
//   }};
//
// Exit codes: 0 success, 1 a failed check (throw CheckFailed or call
// set_exit_code(1)), 2 bad input (throw InputError), 3 an internal error.

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace ferret::cli {

using CommandSetup = std::function<void(CLI::App& app)>;

struct CommandRegistration {
  CommandRegistration(std::string name, CommandSetup setup);
};

/// Lets a command report a non-zero exit status without throwing.
void set_exit_code(int code);

}  // namespace ferret::cli
