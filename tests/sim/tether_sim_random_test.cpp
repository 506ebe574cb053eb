// Randomized closed-loop tests of the winch controllers: the targets the shipped
// trajectories demonstrate (tether_sim_test.cpp) must also hold on trajectories
// nobody tuned against. Scenarios are drawn from std::mt19937_64 with fixed seeds,
// so every run sees the same ones and a failure names the scenario to replay
// (--gtest_filter='TetherSimRandom/RandomTetherScenario.*/<index>').
//
// Only scenarios the winch can physically serve are drawn: the miniUGV is slower
// than the spool (cruise <= 0.5 m/s, the servo does 0.6 m/s), the taut length stays
// a margin below L, the required length is continuous (no wrap point that unwraps
// "through" an obstacle) and its acceleration stays below the servo's, and a snag
// only pins the line while the miniUGV is not pulling away from the pinned corner
// (pulling away from a pinned line over-tensions it whatever the winch does).

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ferret/sim/tether_sim.hpp"
#include "ferret/tether_model/feedforward_pid.hpp"
#include "ferret/tether_model/required_length.hpp"
#include "ferret/tether_model/taut_mpc.hpp"

namespace ferret::sim {
namespace {

constexpr double kTotalLengthM = 15.0;  // L
constexpr double kEntryOffsetM = 1.0;   // l_0
// The taut length stays this far below L: the targets here are about tracking,
// reach_limit.csv covers driving against the end of the line.
constexpr double kLengthMarginM = 1.0;
// The miniUGV's path keeps this far from the entry and every wrap point: the line's
// direction then turns slowly enough that the required length's acceleration
// (a . u + v_perp^2 / r <= 1.5 + 0.25 m/s^2) stays within the servo's 2 m/s^2.
constexpr double kClearanceM = 1.0;
constexpr double kMaxRequiredAccelerationMps2 = 1.8;  // 90 % of the servo's profile acceleration
// What the waypoint spacing is drawn for: one sim takes 5-15 ms in Release.
constexpr double kPathTimeS = 28.0;
constexpr double kMaxDurationS = 40.0;
// Area the miniUGV drives in: 10 x 10 m beyond the entry at the origin.
constexpr double kAreaMinX = 0.0, kAreaMaxX = 10.0, kAreaMinY = -5.0, kAreaMaxY = 5.0;
// 200 (a third with snags): scenario 35 found the MPC holding a snagged line at
// 10.4 N before its predictions were clamped during a pull (taut_mpc.cpp).
constexpr int kScenarioCount = 200;
constexpr std::uint64_t kBaseSeed = 0x7e7'4e25'0000ULL;

struct RandomScenario {
  int index = 0;
  std::uint64_t generator_seed = 0;
  std::uint64_t sim_seed = 0;
  std::vector<Eigen::Vector2d> waypoints;
  double cruise_mps = 0.0, accel_mps2 = 0.0, dwell_s = 0.0;
  TetherScenario scenario;

  [[nodiscard]] bool has_snag() const { return !scenario.snags.empty(); }

  // Everything needed to rebuild the scenario by hand (e.g. as a YAML for `ferret tether-sim`).
  [[nodiscard]] std::string describe() const {
    std::ostringstream out;
    out.precision(4);
    out << "random scenario " << index << " (generator seed " << generator_seed << ", sim seed "
        << sim_seed << "): script {waypoints_xy_m: [";
    for (std::size_t i = 0; i < waypoints.size(); ++i)
      out << (i ? ", " : "") << "[" << waypoints[i].x() << ", " << waypoints[i].y() << "]";
    out << "], cruise_mps: " << cruise_mps << ", accel_mps2: " << accel_mps2
        << ", dwell_s: " << dwell_s << "}, wrap_points: [";
    for (std::size_t i = 0; i < scenario.wrap_points.size(); ++i) {
      const auto& w = scenario.wrap_points[i];
      out << (i ? ", " : "") << "{xy_m: [" << w.p_W.x() << ", " << w.p_W.y() << "], side: "
          << (w.side > 0   ? "left"
              : w.side < 0 ? "right"
                           : "always")
          << "}";
    }
    out << "], snags: [";
    for (const auto& s : scenario.snags)
      out << "{wrap_point: " << s.wrap_point << ", start_s: " << s.start_s
          << ", duration_s: " << s.duration_s << "}";
    out << "], duration " << scenario.end_s() << " s";
    return out.str();
  }
};

double distance_to_segment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                           const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double t =
      ab.squaredNorm() > 0.0 ? std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

bool inside_area(const Eigen::Vector2d& p) {
  return p.x() >= kAreaMinX && p.x() <= kAreaMaxX && p.y() >= kAreaMinY && p.y() <= kAreaMaxY;
}

// Why a drawn scenario is unusable, or "" if it is fine. Checked on the sampled
// trajectory, so the checks hold for what the simulation actually drives.
std::string infeasibility(const TetherScenario& scn) {
  const tether::FixedWrapTether taut(kEntryOffsetM, scn.p_WE, scn.wrap_points);
  const auto& s = scn.samples;
  std::vector<double> required(s.size());
  std::vector<bool> bent(scn.wrap_points.size(), false);
  double max_bend_m = 0.0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    required[i] = taut.required_length_m(s[i].p_WG);
    if (required[i] > kTotalLengthM - kLengthMarginM) return "taut length too close to L";
    const std::size_t engaged = taut.engaged_count(s[i].p_WG);
    for (std::size_t k = 0; k < engaged; ++k) bent[k] = true;
    max_bend_m =
        std::max(max_bend_m, required[i] - (kEntryOffsetM + (s[i].p_WG - scn.p_WE).norm()));
    // Continuous: the taut length cannot change by more than the miniUGV moved.
    if (i > 0 &&
        std::abs(required[i] - required[i - 1]) > (s[i].p_WG - s[i - 1].p_WG).norm() + 1e-9)
      return "required length jumps";
  }
  if (std::find(bent.begin(), bent.end(), false) != bent.end()) return "a wrap point never bends";
  if (!scn.wrap_points.empty() && max_bend_m < 0.1) return "the tether barely bends";
  // Second differences over 0.1 s (the samples are 0.02 s apart).
  constexpr std::size_t kStride = 5;
  for (std::size_t i = kStride; i + kStride < s.size(); ++i) {
    const double h = s[i + kStride].t_s - s[i].t_s;
    const double acc =
        (required[i + kStride] - 2.0 * required[i] + required[i - kStride]) / (h * h);
    if (std::abs(acc) > kMaxRequiredAccelerationMps2) return "required length accelerates too fast";
  }
  return "";
}

// A snag on wrap point k over [start, start + duration]: the corner must be engaged
// when it starts (otherwise the simulation ignores it), and the miniUGV must not
// move away from the pinned corner while it lasts, but should approach it by a
// useful distance so the line beyond it goes slack and geometry alone says "reel in".
// Nor may it start while the winch reels in so fast that no winch could stop in
// time: pinned, the winch side (l_0 to the corner) stretches by at least what the
// spool reels in during a control period plus its braking distance at the servo's
// acceleration, v T + v^2 / (2 a), and that stretch must stay below the tension
// limit (0.4 m/s onto a 4.3 m winch side gives ~17 N whatever the controller does).
std::optional<TetherSnag> draw_snag(const TetherScenario& scn, std::mt19937_64& rng) {
  std::uniform_int_distribution<std::size_t> pick_wrap(0, scn.wrap_points.size() - 1);
  const std::size_t k = pick_wrap(rng);
  const double duration_s = std::uniform_real_distribution<double>(1.0, 4.0)(rng);
  const tether::FixedWrapTether taut(kEntryOffsetM, scn.p_WE, scn.wrap_points);
  const tether::FixedWrapTether beyond(
      0.0, scn.wrap_points[k].p_W,
      std::vector<tether::WrapPoint>(scn.wrap_points.begin() + static_cast<long>(k) + 1,
                                     scn.wrap_points.end()));
  const tether::TensionModel tension;
  const tether::WinchLimits winch;
  const double period_s = tether::TautControlOptions{}.control_period_s;
  const double winch_side_npm = tension.stiffness_npm(taut.length_to_wrap_point_m(k));
  const auto& s = scn.samples;
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i + 1 < s.size(); ++i) {
    if (taut.engaged_count(s[i].p_WG) <= k || taut.engaged_count(s[i + 1].p_WG) <= k) continue;
    const double reel_in_mps =
        std::max(0.0, (taut.required_length_m(s[i].p_WG) - taut.required_length_m(s[i + 1].p_WG)) /
                          (s[i + 1].t_s - s[i].t_s));
    const double stopping_stretch_m =
        reel_in_mps * period_s + reel_in_mps * reel_in_mps / (2.0 * winch.max_acceleration_mps2);
    if (winch_side_npm * stopping_stretch_m > tension.max_tension_n) continue;
    const double end_s = s[i].t_s + duration_s;
    if (end_s > scn.end_s()) break;
    double previous = beyond.required_length_m(s[i].p_WG);
    bool receding = false;
    std::size_t j = i + 1;
    for (; j < s.size() && s[j].t_s <= end_s + 0.02; ++j) {
      const double now = beyond.required_length_m(s[j].p_WG);
      if (now > previous + 1e-6) {
        receding = true;
        break;
      }
      previous = now;
    }
    if (!receding && beyond.required_length_m(s[i].p_WG) - previous >= 0.2) starts.push_back(i);
  }
  if (starts.empty()) return std::nullopt;
  const std::size_t i =
      starts[std::uniform_int_distribution<std::size_t>(0, starts.size() - 1)(rng)];
  // Half a physics step after the sample: engaged on both sides of the start.
  return TetherSnag{k, s[i].t_s + 0.0005, duration_s};
}

// Whether the tether wraps round a corner and comes off it again during the drive
// (the required length's kink the controllers must follow).
bool wraps_and_unwraps(const TetherScenario& scn) {
  const tether::FixedWrapTether taut(kEntryOffsetM, scn.p_WE, scn.wrap_points);
  std::size_t least = scn.wrap_points.size(), most = 0;
  for (const auto& s : scn.samples) {
    least = std::min(least, taut.engaged_count(s.p_WG));
    most = std::max(most, taut.engaged_count(s.p_WG));
  }
  return least < most;
}

std::optional<RandomScenario> try_draw(std::mt19937_64& rng, int index, int wrap_count,
                                       bool with_snag, bool must_unwrap) {
  auto uniform = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  auto integer = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  RandomScenario r;
  r.index = index;
  r.cruise_mps = uniform(0.1, 0.5);
  r.accel_mps2 = uniform(0.3, 1.5);
  r.dwell_s = uniform(0.0, 1.0);
  const int waypoint_count = integer(3, 6);
  auto& scn = r.scenario;
  scn.name = "random_" + std::to_string(index);
  scn.p_WE = Eigen::Vector2d::Zero();
  // Segments sized so the drive takes about kPathTimeS at the drawn cruise speed.
  const double segment_m = std::clamp(r.cruise_mps * kPathTimeS / (waypoint_count - 1), 0.6, 4.0);
  r.waypoints.push_back({uniform(kAreaMinX, kAreaMaxX), uniform(kAreaMinY, kAreaMaxY)});
  while (static_cast<int>(r.waypoints.size()) < waypoint_count) {
    const double heading = uniform(-std::numbers::pi, std::numbers::pi);
    const Eigen::Vector2d next =
        r.waypoints.back() +
        uniform(0.5, 1.0) * segment_m * Eigen::Vector2d(std::cos(heading), std::sin(heading));
    if (!inside_area(next)) return std::nullopt;
    r.waypoints.push_back(next);
  }
  // Obstacle corners near the line from the previous anchor to a waypoint, so that the
  // path passes on both sides of them and a corner with a side wraps and unwraps.
  Eigen::Vector2d anchor = scn.p_WE;
  for (int k = 0; k < wrap_count; ++k) {
    const Eigen::Vector2d to =
        r.waypoints[static_cast<std::size_t>(integer(0, waypoint_count - 1))] - anchor;
    const Eigen::Vector2d normal = Eigen::Vector2d(-to.y(), to.x()).normalized();
    const Eigen::Vector2d corner =
        anchor + uniform(0.3, 0.8) * to + (integer(0, 1) ? 1.0 : -1.0) * uniform(0.2, 1.5) * normal;
    if (!inside_area(corner)) return std::nullopt;
    scn.wrap_points.push_back({corner, integer(-1, 1)});
    anchor = corner;
  }
  std::vector<Eigen::Vector2d> anchors{scn.p_WE};
  for (const auto& w : scn.wrap_points) anchors.push_back(w.p_W);
  for (std::size_t i = 0; i + 1 < r.waypoints.size(); ++i)
    for (const auto& a : anchors)
      if (distance_to_segment(a, r.waypoints[i], r.waypoints[i + 1]) < kClearanceM)
        return std::nullopt;
  scn.samples = scripted_trajectory(r.waypoints, r.cruise_mps, r.accel_mps2, r.dwell_s);
  if (scn.end_s() > kMaxDurationS || !infeasibility(scn).empty()) return std::nullopt;
  if (must_unwrap && !wraps_and_unwraps(scn)) return std::nullopt;
  if (with_snag) {
    const auto snag = draw_snag(scn, rng);
    if (!snag) return std::nullopt;
    scn.snags.push_back(*snag);
  }
  return r;
}

// Scenario `index`: its own generator seed, so each one is reproducible alone and
// adding scenarios does not change the others. Every third one has a snag, and in
// every fourth the tether wraps round a corner and comes off it again. The number of
// wrap points is drawn once, before the rejection loop: redrawing it with the rest
// would favour the straight tethers that are rejected least.
RandomScenario random_scenario(int index) {
  const std::uint64_t seed = kBaseSeed + static_cast<std::uint64_t>(index);
  std::mt19937_64 rng(seed);
  const bool with_snag = index % 3 == 2, must_unwrap = index % 4 == 1;
  const int wrap_count =
      std::uniform_int_distribution<int>(with_snag || must_unwrap ? 1 : 0, 2)(rng);
  for (int attempt = 0; attempt < 200000; ++attempt) {
    if (auto r = try_draw(rng, index, wrap_count, with_snag, must_unwrap)) {
      r->generator_seed = seed;
      r->sim_seed = 1000 + static_cast<std::uint64_t>(index);
      return *r;
    }
  }
  throw std::runtime_error("no feasible random tether scenario for index " + std::to_string(index));
}

std::shared_ptr<const tether::FixedWrapTether> taut_model(const TetherScenario& scn) {
  return std::make_shared<tether::FixedWrapTether>(kEntryOffsetM, scn.p_WE, scn.wrap_points);
}

// The generator itself: it must deliver what the closed-loop test relies on, and
// really vary the things it claims to vary.
TEST(TetherSimRandomGenerator, DrawsFeasibleVariedScenarios) {
  int bent = 0, two_wraps = 0, snags = 0, unwraps = 0;
  double min_cruise = 1.0, max_cruise = 0.0;
  for (int i = 0; i < kScenarioCount; ++i) {
    const auto r = random_scenario(i);
    SCOPED_TRACE(r.describe());
    const auto& scn = r.scenario;
    EXPECT_EQ(infeasibility(scn), "");
    EXPECT_LE(scn.end_s(), kMaxDurationS);
    EXPECT_EQ(scn.p_WE, Eigen::Vector2d::Zero());
    ASSERT_GE(r.waypoints.size(), 3u);
    ASSERT_LE(r.waypoints.size(), 6u);
    for (const auto& w : r.waypoints) EXPECT_TRUE(inside_area(w)) << w.transpose();
    EXPECT_GE(r.cruise_mps, 0.1);
    EXPECT_LE(r.cruise_mps, 0.5);
    // The drawn trajectory is the script: it starts and ends at the waypoints.
    // (the last sample is within a sampling step's rounding, < 0.1 mm, of the last waypoint.)
    EXPECT_NEAR((scn.samples.front().p_WG - r.waypoints.front()).norm(), 0.0, 1e-9);
    EXPECT_NEAR((scn.samples.back().p_WG - r.waypoints.back()).norm(), 0.0, 1e-3);
    bent += scn.wrap_points.empty() ? 0 : 1;
    two_wraps += scn.wrap_points.size() == 2 ? 1 : 0;
    unwraps += wraps_and_unwraps(scn) ? 1 : 0;
    min_cruise = std::min(min_cruise, r.cruise_mps);
    max_cruise = std::max(max_cruise, r.cruise_mps);
    if (r.has_snag()) {
      ++snags;
      // The snag pins a corner the tether is bent round when it starts.
      const auto& snag = scn.snags.front();
      const tether::FixedWrapTether taut(kEntryOffsetM, scn.p_WE, scn.wrap_points);
      EXPECT_GT(taut.engaged_count(scn.at(snag.start_s).p_WG), snag.wrap_point);
    }
    // Same index, same scenario.
    const auto again = random_scenario(i);
    ASSERT_EQ(again.scenario.samples.size(), scn.samples.size());
    EXPECT_EQ(again.scenario.samples.back().p_WG, scn.samples.back().p_WG);
  }
  EXPECT_GE(bent, kScenarioCount / 2);
  EXPECT_GE(two_wraps, 2);
  EXPECT_GE(unwraps, kScenarioCount / 4);
  EXPECT_EQ(snags, kScenarioCount / 3);
  EXPECT_GT(max_cruise - min_cruise, 0.2);
}

class RandomTetherScenario : public ::testing::TestWithParam<int> {};

// The MPC's targets (docs/tether.md) on a trajectory it was not tuned on: never
// over-tension the line, never pay out past L, never fall back to braking; without
// a snag, keep the line taut (slack RMS of millimetres, slack below s_max) and do
// at least about as well as the baseline. The baseline is held to L only: it may
// over-tension on fast direction changes (docs/results.md).
TEST_P(RandomTetherScenario, TheMpcMeetsItsTargetsAndKeepsUpWithTheBaseline) {
  const auto r = random_scenario(GetParam());
  SCOPED_TRACE(r.describe());
  const auto& scn = r.scenario;
  auto config = TetherRunConfig::for_tether(kTotalLengthM, kEntryOffsetM);
  config.sim.seed = r.sim_seed;
  const auto model = taut_model(scn);

  tether::TautTetherMpc mpc(config.mpc, model);
  const auto m = run_tether_sim(scn, config.sim, mpc).metrics;
  tether::FeedForwardPid pid(config.baseline, model);
  const auto b = run_tether_sim(scn, config.sim, pid).metrics;
  RecordProperty("mpc_slack_rms_mm", std::to_string(1e3 * m.slack_rms_m));
  RecordProperty("baseline_slack_rms_mm", std::to_string(1e3 * b.slack_rms_m));
  RecordProperty("has_snag", r.has_snag() ? 1 : 0);
  SCOPED_TRACE(
      "mpc: slack rms " + std::to_string(1e3 * m.slack_rms_m) + " mm, max " +
      std::to_string(1e3 * m.max_slack_m) + " mm, min " + std::to_string(1e3 * m.min_slack_m) +
      " mm, max tension " + std::to_string(m.max_tension_n) + " N; baseline: slack rms " +
      std::to_string(1e3 * b.slack_rms_m) + " mm, max tension " + std::to_string(b.max_tension_n) +
      " N, over-tension events " + std::to_string(b.over_tension_events));

  EXPECT_EQ(m.over_tension_events, 0);
  EXPECT_EQ(m.released_over_limit, 0);
  EXPECT_LE(m.max_released_m, kTotalLengthM + 1e-3);
  EXPECT_EQ(mpc.fallback_count(), 0);
  EXPECT_EQ(b.released_over_limit, 0);
  if (r.has_snag()) return;  // a snag leaves slack beyond the corner: no slack targets
  // Generous against the ~1-3 mm the MPC achieves here, but a winch that does not
  // follow the miniUGV misses them by orders of magnitude.
  EXPECT_LT(m.slack_rms_m, 0.005);
  EXPECT_LT(m.max_slack_m, config.mpc.control.max_slack_m);
  EXPECT_LE(m.slack_rms_m, 1.5 * b.slack_rms_m);
}

INSTANTIATE_TEST_SUITE_P(TetherSimRandom, RandomTetherScenario,
                         ::testing::Range(0, kScenarioCount));

}  // namespace
}  // namespace ferret::sim
