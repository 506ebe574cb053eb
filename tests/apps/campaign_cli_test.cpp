// `ferret campaign` (docs/safety.md, "Campaigns"): bad options exit 2 before any run and
// write nothing; a small campaign classes its runs, and a run's replay command replays it.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/cli_runner.hpp"

namespace ferret {
namespace {

namespace fs = std::filesystem;

TEST(CampaignCli, BadOptionsExitTwoNamingTheOptionAndWriteNothing) {
  test::TempDir dir;
  const std::string out = dir / "c";
  for (const std::string& bad :
       {std::string("--runs 0"), std::string("--jobs 0"), std::string("--run-timeout-s 1"),
        std::string("--min-faults 3 --max-faults 2"), std::string("--shard 2/2"),
        std::string("--world nowhere.yaml")}) {
    const auto r = test::run_cli("campaign " + bad + " -o " + out);
    EXPECT_EQ(r.exit_code, 2) << bad << ": " << r.err;
    EXPECT_NE(r.err.find(bad.substr(0, bad.find(' '))), std::string::npos) << bad << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << bad;
  }
  const auto m = test::run_cli("campaign merge -o " + out + " " + (dir / "none"));
  EXPECT_EQ(m.exit_code, 2) << m.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(CampaignCli, ASmallCampaignClassesEachRunAndNamesItsReplay) {
  test::TempDir dir;
  const std::string out = dir / "c";
  const auto r =
      test::run_cli("campaign --runs 2 --seed 5 --world examples/worlds/small.yaml -q -o " + out);
  ASSERT_TRUE(r.exit_code == 0 || r.exit_code == 1) << r.err;  // 1: an unsafe run
  EXPECT_NE(r.out.find("campaign: 2 runs:"), std::string::npos) << r.out;
  std::ifstream csv(fs::path(out) / "campaign.csv");
  std::stringstream s;
  s << csv.rdbuf();
  const std::string text = s.str();
  EXPECT_EQ(text.rfind("run,world,seed,faults,outcome,", 0), 0u) << text;
  EXPECT_NE(text.find("ferret mission --world "), std::string::npos);
  EXPECT_NE(text.find("--faults runs/000001/faults.yaml"), std::string::npos);
  for (const char* run : {"000000", "000001"}) {
    EXPECT_TRUE(fs::exists(fs::path(out) / "runs" / run / "faults.yaml")) << run;
    EXPECT_TRUE(fs::exists(fs::path(out) / "runs" / run / "report.json")) << run;
  }
}

}  // namespace
}  // namespace ferret
