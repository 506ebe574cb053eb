#include <gmock/gmock.h>
#include <gtest/gtest.h>

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
    if (!listing) continue;
    if (!line.empty() && line[0] != ' ') {
      listing = false;
      continue;
    }
    std::istringstream words(line);
    std::string name;
    if (words >> name && std::islower(static_cast<unsigned char>(name[0]))) names.push_back(name);
  }
  return names;
}

/// One option line of CLI11's help: "  -o,--out TEXT REQUIRED   what",
/// "  --seed UINT=1   what", "  --all   what" (the columns are two or more spaces apart).
struct HelpOption {
  std::string short_name, long_name, text;
  bool flag = true, required = false, has_default = false;
};

HelpOption parse_help_option(const std::string& line) {
  HelpOption o;
  const std::size_t start = line.find_first_not_of(' ');
  if (start == std::string::npos || start == 0 || line[start] != '-') return o;
  const std::size_t gap = line.find("  ", start);
  const std::string left = line.substr(start, gap == std::string::npos ? gap : gap - start);
  o.text = gap == std::string::npos ? "" : line.substr(gap);
  std::istringstream tokens(left);
  std::string names, token;
  tokens >> names;
  std::istringstream name_list(names);
  for (std::string n; std::getline(name_list, n, ',');)
    (n.rfind("--", 0) == 0 ? o.long_name : o.short_name) = n;
  while (tokens >> token) {
    if (token == "REQUIRED") {
      o.required = true;
    } else {
      o.flag = false;  // a value's type: TEXT, UINT=1, FLOAT x 4
      o.has_default = o.has_default || token.find('=') != std::string::npos;
    }
  }
  return o;
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
      const HelpOption o = parse_help_option(line);
      if (o.long_name.empty() || o.long_name == "--help" || o.long_name == "--version") continue;
      ++options_checked;
      EXPECT_EQ(old_spellings.count(o.long_name), 0u) << command << ": advertises " << o.long_name;
      EXPECT_TRUE(o.short_name != "-o" || o.long_name == "--out")
          << command << ": -o is " << o.long_name;
      std::string lower = o.text;
      for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (!o.flag && !o.required && !o.has_default) {
        EXPECT_TRUE(lower.find("default") != std::string::npos ||
                    lower.find("required") != std::string::npos)
            << command << ": " << o.long_name << " does not say what its absence means: " << line;
      }
    }
  }
  EXPECT_GE(options_checked, 60u);
}

}  // namespace
}  // namespace ferret::test
