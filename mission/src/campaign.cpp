#include "ferret/mission/campaign.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"
#include "ferret/mission/mission_document.hpp"
#include "ferret/sim/fault_schedule.hpp"

namespace ferret {
namespace {

constexpr std::array<std::string_view, kCampaignOutcomes> kOutcomeNames{
    "retrieved", "returned_empty", "recalled", "aborted_safe", "unsafe"};

// A draw keeps only what the simulation injects; a draw left empty is drawn again.
FaultPlan draw_injectable(std::uint64_t seed, const FaultDrawOptions& options) {
  for (std::uint64_t attempt = 0; attempt < 16; ++attempt) {
    FaultPlan plan = draw_fault_plan(derive_seed(seed, {attempt}), options, mission_fault_states());
    std::erase_if(plan.faults, [](const Fault& f) { return !simulation_injects(f); });
    if (!plan.empty() || options.max_faults == 0) return plan;
  }
  return {};
}

// CSV fields: quoted when they hold a comma or a quote.
std::string field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string q(1, '"');
  for (const char c : text) {
    q.push_back(c);
    if (c == '"') q.push_back('"');
  }
  q.push_back('"');
  return q;
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        out.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

int column(const std::vector<std::string>& header, std::string_view name) {
  const auto it = std::find(header.begin(), header.end(), name);
  return it == header.end() ? -1 : static_cast<int>(it - header.begin());
}

}  // namespace

std::string_view to_string(CampaignOutcome outcome) {
  const auto i = static_cast<std::size_t>(outcome);
  return i < kOutcomeNames.size() ? kOutcomeNames[i] : "?";
}

CampaignRun plan_campaign_run(const CampaignOptions& options, std::size_t index) {
  if (options.worlds.empty()) throw InputError("campaign", "worlds", "at least one world", "none");
  CampaignRun run;
  run.index = index;
  Rng rng(derive_seed(options.seed, {stable_hash("campaign"), index}));
  // A mission seed a user can type, far from the small seeds the tests pin.
  run.seed = 1000 + static_cast<std::uint64_t>(rng.uniform_int(0, 999'999'999));
  run.world = options.worlds[static_cast<std::size_t>(
      rng.uniform_int(0, static_cast<std::int64_t>(options.worlds.size()) - 1))];
  run.faults = draw_injectable(rng.next_u64(), options.draw);
  return run;
}

std::vector<CampaignRun> plan_campaign(const CampaignOptions& options, std::size_t shard_index,
                                       std::size_t shard_count) {
  std::vector<CampaignRun> runs;
  for (std::size_t i = shard_index; i < options.runs; i += std::max<std::size_t>(shard_count, 1))
    runs.push_back(plan_campaign_run(options, i));
  return runs;
}

CampaignResult classify_campaign_run(const CampaignRun& run, const nlohmann::json& report,
                                     const std::string& source) {
  CampaignResult r;
  r.run = run;
  try {
    r.uav_outcome = report.at("outcome").get<std::string>();
    r.time_s = report.at("time_s").get<double>();
    const nlohmann::json& summary = report.at("summary");
    r.objects_in_world = summary.at("objects_in_world").get<int>();
    r.objects_retrieved = summary.at("objects_retrieved").get<int>();
    const nlohmann::json& safety = report.at("safety");
    for (std::size_t k = 0; k < kInvariantKinds; ++k)
      r.violations[k] =
          safety.at("counts").at(std::string(to_string(static_cast<InvariantKind>(k)))).get<int>();
    const bool safe = safety.at("safe").get<bool>();
    bool called_back = false;
    for (const nlohmann::json& d : report.at("ugv_deployments")) {
      const std::string o = d.at("outcome").get<std::string>();
      if (o != "object_retrieved" && o != "no_object") called_back = true;
    }
    const bool normal_end = r.uav_outcome == "search_complete" || r.uav_outcome == "flight_budget";
    if (!safe)
      r.outcome = CampaignOutcome::kUnsafe;
    else if (!normal_end)
      r.outcome = CampaignOutcome::kAbortedSafe;
    else if (r.objects_retrieved > 0)
      r.outcome = CampaignOutcome::kRetrieved;
    else if (called_back)
      r.outcome = CampaignOutcome::kRecalled;
    else
      r.outcome = CampaignOutcome::kReturnedEmpty;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(
        source, "", "a mission report with outcome, summary, safety and ugv_deployments", e.what());
  }
  return r;
}

CampaignResult failed_campaign_run(const CampaignRun& run, std::string note) {
  CampaignResult r;
  r.run = run;
  r.outcome = CampaignOutcome::kUnsafe;
  r.note = std::move(note);
  return r;
}

std::string campaign_replay_command(const CampaignRun& run, const std::string& faults_path) {
  return fmt::format("ferret mission --world {} --seed {} --faults {}", run.world, run.seed,
                     faults_path);
}

std::string campaign_csv_header() {
  std::string h =
      "run,world,seed,faults,outcome,uav_outcome,objects_in_world,objects_retrieved,time_s";
  for (std::size_t k = 0; k < kInvariantKinds; ++k) {
    h.push_back(',');
    h.append(to_string(static_cast<InvariantKind>(k)));
  }
  h.append(",note,fault_list,replay\n");
  return h;
}

std::string campaign_csv_row(const CampaignResult& r, const std::string& replay) {
  std::string faults;
  for (const Fault& f : r.run.faults.faults) {
    if (!faults.empty()) faults.append("; ");
    faults.append(describe(f));
  }
  std::string row = fmt::format("{},{},{},{},{},{},{},{},{:.2f}", r.run.index, field(r.run.world),
                                r.run.seed, r.run.faults.faults.size(), to_string(r.outcome),
                                r.uav_outcome, r.objects_in_world, r.objects_retrieved, r.time_s);
  for (const int v : r.violations) row.append(fmt::format(",{}", v));
  row.append(fmt::format(",{},{},{}\n", field(r.note), field(faults), field(replay)));
  return row;
}

std::string merge_campaign_csv(const std::vector<std::string>& texts,
                               const std::vector<std::string>& sources) {
  const std::string header = campaign_csv_header();
  std::map<std::size_t, std::string> rows;
  for (std::size_t s = 0; s < texts.size(); ++s) {
    const std::vector<std::string> lines = lines_of(texts[s]);
    const std::string source = s < sources.size() ? sources[s] : "shard";
    if (lines.empty() || lines[0] + "\n" != header)
      throw InputError(source, "", "a campaign.csv (its header: " + header.substr(0, 40) + "...)",
                       lines.empty() ? "an empty file" : lines[0].substr(0, 60));
    for (std::size_t i = 1; i < lines.size(); ++i) {
      const std::string run = split_csv_line(lines[i]).front();
      std::size_t index = 0;
      try {
        std::size_t used = 0;
        index = std::stoull(run, &used);
        if (used != run.size()) throw std::invalid_argument(run);
      } catch (const std::exception&) {
        throw InputError(source, "line " + std::to_string(i + 1), "a run number", run);
      }
      if (!rows.emplace(index, lines[i] + "\n").second)
        throw InputError(source, "line " + std::to_string(i + 1), "each run in one shard only",
                         "run " + run + " again");
    }
  }
  std::string out = header;
  for (const auto& [index, row] : rows) out += row;
  return out;
}

namespace {
struct Tally {
  std::array<int, kCampaignOutcomes> outcomes{};
  int runs = 0, violations = 0, with_object = 0, retrieved = 0;
};
Tally tally(const std::string& csv) {
  Tally t;
  const std::vector<std::string> lines = lines_of(csv);
  if (lines.empty()) return t;
  const std::vector<std::string> header = split_csv_line(lines[0]);
  const int outcome = column(header, "outcome"), in_world = column(header, "objects_in_world"),
            retrieved = column(header, "objects_retrieved");
  std::vector<int> kinds;
  for (std::size_t k = 0; k < kInvariantKinds; ++k)
    kinds.push_back(column(header, to_string(static_cast<InvariantKind>(k))));
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const std::vector<std::string> f = split_csv_line(lines[i]);
    const auto at = [&](int c) { return c >= 0 && c < static_cast<int>(f.size()) ? f[c] : ""; };
    ++t.runs;
    for (std::size_t o = 0; o < kCampaignOutcomes; ++o)
      if (at(outcome) == kOutcomeNames[o]) ++t.outcomes[o];
    for (const int c : kinds) t.violations += std::atoi(at(c).c_str());
    if (std::atoi(at(in_world).c_str()) > 0) {
      ++t.with_object;
      if (std::atoi(at(retrieved).c_str()) > 0) ++t.retrieved;
    }
  }
  return t;
}
}  // namespace

std::string campaign_verdict(const std::string& csv) {
  const Tally t = tally(csv);
  std::string classes;
  for (std::size_t o = 0; o < kCampaignOutcomes; ++o)
    classes += fmt::format("{}{} {}", o == 0 ? "" : ", ", t.outcomes[o], kOutcomeNames[o]);
  return fmt::format(
      "campaign: {} runs: {}; {} invariant violations; object retrieved in {} of {} runs with "
      "one; {}",
      t.runs, classes, t.violations, t.retrieved, t.with_object,
      campaign_passed(csv) ? "PASS (no run unsafe)" : "FAIL (unsafe runs)");
}

bool campaign_passed(const std::string& csv) {
  const Tally t = tally(csv);
  return t.outcomes[static_cast<std::size_t>(CampaignOutcome::kUnsafe)] == 0;
}

}  // namespace ferret
