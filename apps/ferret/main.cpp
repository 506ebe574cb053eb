#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <utility>
#include <vector>

#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/logging.hpp"

namespace ferret::cli {
namespace {
std::vector<std::pair<std::string, CommandSetup>>& registry() {
  static std::vector<std::pair<std::string, CommandSetup>> commands;
  return commands;
}
int g_exit_code = 0;
}  // namespace

CommandRegistration::CommandRegistration(std::string name, CommandSetup setup) {
  registry().emplace_back(std::move(name), std::move(setup));
}

void set_exit_code(int code) { g_exit_code = code; }

}  // namespace ferret::cli

int main(int argc, char** argv) {
  CLI::App app{"ferret: UAV-miniUGV planning and hidden-space object search"};
  app.set_version_flag("--version", std::string("ferret ") + FERRET_VERSION);
  std::string log_level = "info";
  app.add_option("--log-level", log_level, "trace, debug, info, warn, error or off")
      ->capture_default_str();
  app.require_subcommand(1);
  app.parse_complete_callback([&] { ferret::setup_logging(log_level); });

  auto& commands = ferret::cli::registry();
  std::sort(commands.begin(), commands.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [name, setup] : commands) setup(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0; real usage errors are bad input.
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "ferret: error: %s\n", e.what());
    std::fprintf(stderr, "Run with --help for usage.\n");
    return 2;
  } catch (const ferret::InputError& e) {
    std::fprintf(stderr, "ferret: error: %s\n", e.what());
    return 2;
  } catch (const ferret::CheckFailed& e) {
    std::fprintf(stderr, "ferret: check failed: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ferret: internal error: %s\n", e.what());
    return 3;
  }
  return ferret::cli::g_exit_code;
}
