#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
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
  std::string type;  ///< the value's type as help prints it: FLOAT, UINT, INT, TEXT, ...
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
      if (o.type.empty()) o.type = token.substr(0, token.find_first_of("=:"));
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

/// Every command's help, depth first: (command, options).
std::vector<std::pair<std::string, std::vector<HelpOption>>> every_command() {
  std::vector<std::pair<std::string, std::vector<HelpOption>>> out;
  std::vector<std::string> todo = subcommands(run_cli("--help").out);
  while (!todo.empty()) {
    const std::string command = todo.back();
    todo.pop_back();
    const auto r = run_cli(command + " --help");
    for (const auto& sub : subcommands(r.out)) todo.push_back(command + " " + sub);
    std::vector<HelpOption> options;
    std::istringstream in(r.out);
    for (std::string line; std::getline(in, line);) {
      const HelpOption o = parse_help_option(line);
      if (!o.long_name.empty() && !o.flag) options.push_back(o);
    }
    out.emplace_back(command, options);
  }
  return out;
}

/// One number parser behind every numeric option, whoever declared it: NaN, infinities,
/// overflow, hex, garbage and empty values are bad input (exit 2) with one line naming
/// the option, for every FLOAT, INT and UINT option of every command; a negative or
/// 20-digit value for an unsigned option (a seed) is refused instead of wrapped.
TEST(Cli, EveryNumericOptionRejectsNonNumbers) {
  std::size_t checked = 0;
  for (const auto& [command, options] : every_command()) {
    for (const auto& o : options) {
      std::vector<std::string> bad;
      // The parser's cases are in Number.*; here one of each kind per option, to prove
      // that every option goes through it.
      if (o.type == "FLOAT")
        bad = {"nan", "-inf", "1e400", "''"};
      else if (o.type == "UINT")
        bad = {"-1", "99999999999999999999"};
      else if (o.type == "INT")
        bad = {"1.5"};
      for (const auto& value : bad) {
        const auto r = run_cli(command + " " + o.long_name + "=" + value);
        ++checked;
        EXPECT_EQ(r.exit_code, 2) << command << " " << o.long_name << "=" << value << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1)
            << command << " " << o.long_name << "=" << value << ": " << r.err;
        EXPECT_NE(r.err.find("ferret: error: " + o.long_name), std::string::npos)
            << command << " " << o.long_name << "=" << value << ": " << r.err;
      }
    }
  }
  EXPECT_GE(checked, 100u);  // about 40 numeric options over the commands
}

TEST(Cli, ParseErrorsAreOneLine) {
  for (const char* args : {"explore --no-such-option", "validate", "plan ugv --start 1,2"}) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("ferret: error: ", 0), 0u) << r.err;
  }
}

}  // namespace
}  // namespace ferret::test
