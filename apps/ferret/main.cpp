#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <utility>
#include <vector>

#include "command.hpp"
#include "ferret/core/error.hpp"
#include "ferret/core/logging.hpp"
#include "ferret/core/number.hpp"

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

namespace {
// Every numeric option of every command goes through ferret's number parser, whoever
// declared it: CLI11 alone takes "nan", "inf" and wraps "-1" into a huge unsigned
// seed. Ranges beyond "finite" are the commands' own (NumberRange in their checks).
bool starts_with_type(const std::string& type, const std::string& name) {
  return type.rfind(name, 0) == 0 &&
         (type.size() == name.size() || type[name.size()] == ':' || type[name.size()] == ' ');
}

void check_numbers(CLI::App* app) {
  for (CLI::Option* opt : app->get_options()) {
    const std::string type = opt->get_type_name();
    if (starts_with_type(type, "FLOAT"))
      opt->check([](const std::string& text) { return number_error(text, NumberRange::finite()); },
                 "", "finite");
    else if (starts_with_type(type, "UINT"))
      opt->check([](const std::string& text) { return integer_error(text, true); }, "", "whole");
    else if (starts_with_type(type, "INT"))
      opt->check([](const std::string& text) { return integer_error(text, false); }, "", "integer");
  }
  for (CLI::App* sub : app->get_subcommands([](CLI::App*) { return true; })) check_numbers(sub);
}

// CLI11's messages may span lines; ferret's errors are one line.
std::string one_line(std::string text) {
  for (auto pos = text.find('\n'); pos != std::string::npos; pos = text.find('\n', pos))
    text.replace(pos, 1, "; ");
  return printable(text);
}
}  // namespace

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
  ferret::cli::check_numbers(&app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version are "errors" with exit code 0; real usage errors are bad input.
    if (e.get_exit_code() == 0) return app.exit(e);
    std::fprintf(stderr, "ferret: error: %s (run with --help for usage)\n",
                 ferret::cli::one_line(e.what()).c_str());
    return 2;
  } catch (const ferret::InputError& e) {
    std::fprintf(stderr, "ferret: error: %s\n", ferret::cli::one_line(e.what()).c_str());
    return 2;
  } catch (const ferret::CheckFailed& e) {
    std::fprintf(stderr, "ferret: check failed: %s\n", ferret::cli::one_line(e.what()).c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ferret: internal error: %s\n", ferret::cli::one_line(e.what()).c_str());
    return 3;
  }
  return ferret::cli::g_exit_code;
}
