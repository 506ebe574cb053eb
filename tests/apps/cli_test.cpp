#include <gtest/gtest.h>

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


}  // namespace
}  // namespace ferret::test
