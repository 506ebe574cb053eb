#pragma once
// A fault campaign (docs/safety.md, "Campaigns"): many simulated missions, each on a
// world and a seed drawn from the campaign's seed, each with a random mix of the faults
// the simulation injects, each run in a process of its own (`ferret campaign`), and
// each classed by how it ended. The plan of runs, the classes and the CSV are here; the
// command runs the processes.

#include <array>
#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "ferret/sim/fault_plan.hpp"
#include "ferret/sim/invariant_monitor.hpp"

namespace ferret {

struct CampaignOptions {
  std::size_t runs = 100;
  std::uint64_t seed = 1;
  /// The worlds drawn from (paths as the replay command names them).
  std::vector<std::string> worlds;
  /// The faults: kinds the simulation injects only (others are dropped from a draw).
  FaultDrawOptions draw;
};

struct CampaignRun {
  std::size_t index = 0;
  std::uint64_t seed = 1;  ///< the mission's --seed
  std::string world;
  FaultPlan faults;
};

/// Run `index` of a campaign: the same for the same options on every machine, whatever
/// other runs there are (a shard plans only its own).
[[nodiscard]] CampaignRun plan_campaign_run(const CampaignOptions& options, std::size_t index);
/// The runs of shard `shard_index` of `shard_count` (index % count == shard index).
[[nodiscard]] std::vector<CampaignRun> plan_campaign(const CampaignOptions& options,
                                                     std::size_t shard_index = 0,
                                                     std::size_t shard_count = 1);

/// How a run ended, from the most severe: a violated invariant, a crash or a hang is
/// `unsafe`; a UAV mission that did not end normally but safely is `aborted_safe`; then
/// the object retrieved; the miniUGV called back without it (recalled, battery, timeouts,
/// a failed grasp); or back without one to find (none in the world, none found, the
/// spaces searched empty).
enum class CampaignOutcome : std::uint8_t {
  kRetrieved,
  kReturnedEmpty,
  kRecalled,
  kAbortedSafe,
  kUnsafe,
};
inline constexpr std::size_t kCampaignOutcomes = 5;
[[nodiscard]] std::string_view to_string(CampaignOutcome outcome);

struct CampaignResult {
  CampaignRun run;
  CampaignOutcome outcome = CampaignOutcome::kUnsafe;
  std::string uav_outcome;  ///< the mission's ("" after a crash or a hang)
  int objects_in_world = 0, objects_retrieved = 0;
  double time_s = 0.0;  ///< simulated
  std::array<int, kInvariantKinds> violations{};
  std::string note;  ///< why unsafe without a violation: "crash: ...", "hang: ..."
};

/// Classes a run from its report.json (schema ferret.mission_report/1 with `safety`).
/// Throws InputError naming `source` for a report without the fields it needs.
[[nodiscard]] CampaignResult classify_campaign_run(const CampaignRun& run,
                                                   const nlohmann::json& report,
                                                   const std::string& source);
/// A run whose process crashed or hung: unsafe, with `note` saying how.
[[nodiscard]] CampaignResult failed_campaign_run(const CampaignRun& run, std::string note);

/// The command that replays a run, with its faults in `faults_path` (run in the
/// campaign's directory when the path is relative).
[[nodiscard]] std::string campaign_replay_command(const CampaignRun& run,
                                                  const std::string& faults_path);

/// campaign.csv: one row a run, in run order; the same bytes for the same runs however
/// they were sharded (nothing of the machine or the wall clock).
[[nodiscard]] std::string campaign_csv_header();
[[nodiscard]] std::string campaign_csv_row(const CampaignResult& r, const std::string& replay);
/// Merges shards' campaign.csv texts into the unsharded one's: rows sorted by run.
/// Throws InputError naming the source for a file that is not a campaign CSV, or a run
/// in two shards.
[[nodiscard]] std::string merge_campaign_csv(const std::vector<std::string>& texts,
                                             const std::vector<std::string>& sources);

/// The verdict on one line, from the CSV's rows: how many runs ended in each class,
/// the invariant violations, the share of runs with an object that retrieved it, and
/// PASS when no run is unsafe.
[[nodiscard]] std::string campaign_verdict(const std::string& csv);
[[nodiscard]] bool campaign_passed(const std::string& csv);

}  // namespace ferret
