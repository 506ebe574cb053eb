#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "support/cli_runner.hpp"

namespace ferret::test {
namespace {

TEST(Cli, HelpExitsZero) {
  const auto r = run_cli("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("Usage"), std::string::npos);
}

TEST(Cli, UnknownSubcommandIsBadInput) {
  const auto r = run_cli("no-such-command");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("ferret: error:"), std::string::npos);
}

/// The subcommands a help text lists under "Subcommands:".
std::vector<std::string> subcommands(const std::string& help) {
  std::vector<std::string> names;
  std::istringstream in(help);
  bool listing = false;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("Subcommands:", 0) == 0) {
      listing = true;
      continue;
    }
    std::smatch m;
    if (listing && std::regex_match(line, m, std::regex(R"(\s+([a-z][a-z0-9-]*)\s.*)")))
      names.push_back(m[1]);
    else if (listing && !line.empty() && line[0] != ' ')
      listing = false;
  }
  return names;
}

/// docs/cli.md, checked on every command's --help, so a command added later cannot
/// drift from it: no old spelling is advertised, -o is always -o,--out, and every
/// option that is neither required nor a flag says what its absence means.
TEST(Cli, EveryCommandFollowsTheConvention) {
  const std::set<std::string> old_spellings{"--output",     "--output-dir",    "--tether",
                                            "--tether-max", "--tether-length", "--geofence",
                                            "--altitude",   "--config"};
  std::vector<std::string> todo;
  for (const auto& c : subcommands(run_cli("--help").out)) todo.push_back(c);
  ASSERT_GE(todo.size(), 10u);  // config, experiment, explore, plan, render, validate, ...
  std::size_t options_checked = 0;
  while (!todo.empty()) {
    const std::string command = todo.back();
    todo.pop_back();
    const auto r = run_cli(command + " --help");
    ASSERT_EQ(r.exit_code, 0) << command;
    for (const auto& sub : subcommands(r.out)) todo.push_back(command + " " + sub);
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) {
      std::smatch m;
      // "  -o,--out TEXT REQUIRED   what" / "  --seed UINT=1   what" / "  --all   what"
      if (!std::regex_match(
              line, m, std::regex(R"(\s+(-\w,)?(--[a-z0-9-]+)( [A-Z:]+[^ ]*)?( REQUIRED)?(.*))")))
        continue;
      const std::string name = m[2], type = m[3], required = m[4], text = m[5];
      if (name == "--help" || name == "--version") continue;
      ++options_checked;
      EXPECT_EQ(old_spellings.count(name), 0u) << command << ": advertises " << name;
      if (m[1].matched) {
        EXPECT_TRUE(m[1] != "-o," || name == "--out") << command << ": -o is " << name;
      }
      const bool flag = type.empty();
      const bool has_default = type.find('=') != std::string::npos;
      std::string lower = text;
      for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (!flag && required.empty() && !has_default) {
        EXPECT_TRUE(lower.find("default") != std::string::npos ||
                    lower.find("required") != std::string::npos)
            << command << ": " << name << " does not say what its absence means: " << line;
      }
    }
  }
  EXPECT_GE(options_checked, 60u);
}

}  // namespace
}  // namespace ferret::test
