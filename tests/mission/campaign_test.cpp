// A fault campaign's plan, classes, CSV and merge (mission/campaign.hpp).

#include "ferret/mission/campaign.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/sim/fault_schedule.hpp"

namespace ferret {
namespace {

CampaignOptions options(std::size_t runs = 12) {
  CampaignOptions o;
  o.runs = runs;
  o.seed = 7;
  o.worlds = {"a.yaml", "b.yaml", "c.yaml"};
  return o;
}

TEST(Campaign, EachRunIsTheSameWhateverElseIsPlanned) {
  const auto all = plan_campaign(options());
  ASSERT_EQ(all.size(), 12u);
  const CampaignRun alone = plan_campaign_run(options(), 5);
  EXPECT_EQ(alone.seed, all[5].seed);
  EXPECT_EQ(alone.world, all[5].world);
  EXPECT_EQ(alone.faults, all[5].faults);
  // Another campaign seed, other runs.
  CampaignOptions other = options();
  other.seed = 8;
  EXPECT_NE(plan_campaign_run(other, 5).seed, alone.seed);
}

TEST(Campaign, RunsDrawInjectedFaultsOnlyAndSpreadOverTheWorlds) {
  std::set<std::string> worlds;
  for (const CampaignRun& r : plan_campaign(options(60))) {
    worlds.insert(r.world);
    EXPECT_GE(r.faults.faults.size(), 1u) << r.index;
    EXPECT_LE(r.faults.faults.size(), 4u) << r.index;
    for (const Fault& f : r.faults.faults) EXPECT_TRUE(simulation_injects(f)) << describe(f);
  }
  EXPECT_EQ(worlds.size(), 3u);
}

TEST(Campaign, ShardsPartitionTheRuns) {
  std::set<std::size_t> seen;
  for (std::size_t s = 0; s < 3; ++s)
    for (const CampaignRun& r : plan_campaign(options(), s, 3)) {
      EXPECT_EQ(r.index % 3, s);
      EXPECT_TRUE(seen.insert(r.index).second) << r.index;
    }
  EXPECT_EQ(seen.size(), 12u);
}

nlohmann::json report(bool safe, const std::string& uav, int in_world, int retrieved,
                      const std::vector<std::string>& ugv) {
  nlohmann::json counts = nlohmann::json::object();
  for (std::size_t k = 0; k < kInvariantKinds; ++k)
    counts[std::string(to_string(static_cast<InvariantKind>(k)))] = 0;
  if (!safe) counts["tension_over_limit"] = 3;
  nlohmann::json deps = nlohmann::json::array();
  for (const auto& o : ugv) deps.push_back({{"outcome", o}});
  return {{"outcome", uav},
          {"time_s", 600.0},
          {"summary", {{"objects_in_world", in_world}, {"objects_retrieved", retrieved}}},
          {"safety", {{"safe", safe}, {"counts", counts}}},
          {"ugv_deployments", deps}};
}

TEST(Campaign, ClassesFromTheMostSevere) {
  const CampaignRun run = plan_campaign_run(options(), 0);
  const auto cls = [&](const nlohmann::json& j) {
    return classify_campaign_run(run, j, "r.json").outcome;
  };
  EXPECT_EQ(cls(report(false, "search_complete", 1, 1, {"object_retrieved"})),
            CampaignOutcome::kUnsafe);
  EXPECT_EQ(cls(report(true, "retract_failed", 1, 0, {"recalled"})), CampaignOutcome::kAbortedSafe);
  EXPECT_EQ(cls(report(true, "search_complete", 1, 1, {"no_object", "object_retrieved"})),
            CampaignOutcome::kRetrieved);
  EXPECT_EQ(cls(report(true, "flight_budget", 1, 0, {"battery_low"})), CampaignOutcome::kRecalled);
  EXPECT_EQ(cls(report(true, "search_complete", 1, 0, {"no_object"})),
            CampaignOutcome::kReturnedEmpty);
  EXPECT_EQ(cls(report(true, "search_complete", 1, 0, {})), CampaignOutcome::kReturnedEmpty);
  const CampaignResult r = classify_campaign_run(
      run, report(false, "search_complete", 1, 1, {"object_retrieved"}), "r.json");
  EXPECT_EQ(r.violations[static_cast<std::size_t>(InvariantKind::kTensionOverLimit)], 3);
  EXPECT_THROW((void)classify_campaign_run(run, nlohmann::json{{"outcome", "x"}}, "r.json"),
               InputError);
  EXPECT_EQ(failed_campaign_run(run, "hang: over 900 s").outcome, CampaignOutcome::kUnsafe);
}

TEST(Campaign, MergedShardsGiveTheUnshardedCsvAndVerdict) {
  std::vector<CampaignResult> results;
  const char* uav[] = {"search_complete", "flight_budget", "search_complete", "aborted"};
  for (std::size_t i = 0; i < 4; ++i)
    results.push_back(classify_campaign_run(
        plan_campaign_run(options(4), i),
        report(true, uav[i], 1, i == 0 ? 1 : 0, {i == 1 ? "battery_low" : "no_object"}), "r"));
  std::string whole = campaign_csv_header(), even = whole, odd = whole;
  for (const CampaignResult& r : results) {
    const std::string row = campaign_csv_row(r, campaign_replay_command(r.run, "f,1.yaml"));
    whole += row;
    (r.run.index % 2 ? odd : even) += row;
  }
  EXPECT_EQ(merge_campaign_csv({odd, even}, {"odd", "even"}), whole);
  EXPECT_EQ(campaign_verdict(whole),
            "campaign: 4 runs: 1 retrieved, 1 returned_empty, 1 recalled, 1 aborted_safe, 0 "
            "unsafe; 0 invariant violations; object retrieved in 1 of 4 runs with one; PASS (no "
            "run unsafe)");
  EXPECT_TRUE(campaign_passed(whole));
  EXPECT_THROW((void)merge_campaign_csv({whole, even}, {"a", "b"}), InputError);  // twice
  EXPECT_THROW((void)merge_campaign_csv({"run,x\n1,2\n"}, {"a"}), InputError);
  const std::string unsafe =
      whole +
      campaign_csv_row(failed_campaign_run(plan_campaign_run(options(), 9), "crash: exit 3"),
                       "ferret mission ...");
  EXPECT_FALSE(campaign_passed(unsafe));
}

}  // namespace
}  // namespace ferret
