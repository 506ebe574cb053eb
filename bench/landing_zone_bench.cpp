// Landing zones: ms per depth frame of LandingZoneDetector and of the PX4 rule (Google
// Benchmark), and with --compare the evaluation on generated terrains with ground
// truth (docs/results/landing_zone.md):
//
//   ferret_bench_landing_zone --compare [--terrains N] [--seed S] [--verbose] [--set NAME=V]...
//
// --verbose lists the frames missed and the truth-safe candidates rejected there; --set
// changes a detector option for a study (margin_m, max_step_m, step_allowance_m,
// max_roughness_m, max_slope_deg, slope_sigmas, slope_allowance_deg, taller_than_m,
// taller_allowance_m, cell_size_m, min_clearance_m, hover_cell_size_m: 0 for one frame's cells,
// hover_min_frames) or the truth's footprint
// (truth_radius_m) or the view it asks for round a safe disc (view_radius_m) or the
// rendered frames' D415 model (depth_noise_per_m, depth_dropout) or their size
// (width_px, height_px: 640 x 480 unless set; the M100's URDF camera is 1280 x 720) or
// the frames a hover fuses (frames: 1 unless set; each further frame drifted by up to
// hover_drift_m = 0.03 and hover_drift_deg = 0.5 per axis) and how long it looks when
// they show no safe zone (frames_max: twice the frames, judged again, up to this many, as
// the mission's uav.survey_frames_max; the PX4 rule sees the first `frames`).
//
// Besides the truth's "safe zone in view", the table counts the frames with a zone that
// is safe with the detector's own limits and margin (by the exact solids, in view): what
// is left missed there is lost to sensing, not to the limits' distance from the truth's.
//
// Each terrain is seen from the M100's depth camera (role depth_camera; its field of
// view at 640 x 480) at 2, 3 and 4 m; SensorSimulator renders the D415-like frame.
#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <string>

#include "ferret/sim/landing_terrain.hpp"
#include "ferret/uav/landing_zone.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

struct Setup {
  RobotDescription robot;
  CameraSensor sensor;
  CameraModel camera;
  LandingZoneDetector::Options options;
};

Setup setup(int width, int height) {
  Setup s{load_robot_description(std::string(FERRET_SOURCE_DIR) + "/urdf/models/m100.urdf"),
          {},
          {},
          {}};
  s.sensor = s.robot.depth_camera();
  s.camera = CameraModel::from_fov(s.sensor.name, width, height, s.sensor.horizontal_fov_rad);
  s.options = LandingZoneDetector::Options::for_robot(s.robot);
  return s;
}

// What the detector must see around a zone to judge it: its disc, the margin, the
// clearance ring, and the cell the ring's edge falls in (a cell is judged whole).
LandingSceneOptions scene_options(const LandingZoneDetector::Options& o) {
  LandingSceneOptions so;
  so.footprint_radius_m = o.footprint_radius_m;
  so.view_radius_m =
      o.footprint_radius_m + o.margin_m + o.min_clearance_m + o.cell_size_m * std::sqrt(2.0);
  return so;
}

// One view 3 m over a terrain with rubble and steps (index 1 of the family): a hover's
// `frames` depth frames, posed, with the setup they were rendered by.
struct BenchHover {
  Setup s;
  LandingScene scene;
  std::vector<PosedDepthFrame> frames;  // into scene
  BenchHover(int width, int height, int n)
      : s(setup(width, height)), scene(landing_scene(1, 1, s.sensor, s.camera, options(s, n))) {
    const LandingFrame& f = view();
    frames.push_back({&f.depth, f.X_WC});
    for (std::size_t m = 0; m < f.more_depth.size(); ++m)
      frames.push_back({&f.more_depth[m], f.more_X_WC[m]});
    // The ray table is built once per camera, not in the first iteration.
    (void)LandingZoneDetector(s.options).detect(f.depth, s.camera, f.X_WC);
  }
  BenchHover(const BenchHover&) = delete;  // frames point into scene
  BenchHover& operator=(const BenchHover&) = delete;
  [[nodiscard]] const LandingFrame& view() const { return scene.frames.front(); }
  static LandingSceneOptions options(const Setup& s, int n) {
    auto so = scene_options(s.options);
    so.heights_m = {3.0};
    so.frames_per_view = n;
    return so;
  }
};

void BM_Detector(benchmark::State& state, int width, int height, bool px4, int frames = 1) {
  const BenchHover h(width, height, frames);
  const LandingFrame& f = h.view();
  const LandingZoneDetector det(h.s.options);
  const Px4LandingBaseline base(Px4LandingBaseline::Options{});
  for (auto _ : state) {
    if (px4)
      benchmark::DoNotOptimize(base.detect(f.depth, h.s.camera, f.X_WC, f.X_WB.translation()));
    else if (frames > 1)
      benchmark::DoNotOptimize(det.detect(h.frames, h.s.camera));  // fused, then judged
    else
      benchmark::DoNotOptimize(det.detect(f.depth, h.s.camera, f.X_WC));
  }
}

// A survey view that finds nothing (the mission's 8, 16, 32 and 64 frames judged, one
// frame a control step): its frames fused again from the first at every judgment, as
// fuse_depth_frames does, or fused as they come (DepthFrameFusion, the mission's). The
// counter worst_step_ms is the longest control step's share: the frame it adds, and the
// judgment when there is one.
void BM_SurveyThatMisses(benchmark::State& state, bool as_they_come) {
  const BenchHover h(640, 480, kMaxHoverFrames);
  const LandingZoneDetector det(h.s.options);
  using Clock = std::chrono::steady_clock;
  double worst_step_ms = 0.0;
  for (auto _ : state) {
    DepthFrameFusion fusion(h.s.camera);
    int judged_at = 8;  // the mission's uav.survey_frames
    for (int n = 1; n <= kMaxHoverFrames; ++n) {
      const auto began = Clock::now();
      const bool judge = n == judged_at;
      if (judge) judged_at = hover_frames_after_miss(n, kMaxHoverFrames);
      if (as_they_come) {
        fusion.add(*h.frames[n - 1].depth, h.frames[n - 1].X_WC);
        if (judge) benchmark::DoNotOptimize(det.detect(fusion));
      } else if (judge) {
        const std::vector<PosedDepthFrame> taken(h.frames.begin(), h.frames.begin() + n);
        benchmark::DoNotOptimize(det.detect(taken, h.s.camera));
      }
      worst_step_ms = std::max(
          worst_step_ms, std::chrono::duration<double, std::milli>(Clock::now() - began).count());
    }
  }
  state.counters["worst_step_ms"] = worst_step_ms;
}

struct Tally {
  int frames = 0, with_zone = 0, found_where_exists = 0, chose = 0, chose_unsafe = 0, listed = 0,
      listed_unsafe = 0, found_where_none = 0, with_clear_zone = 0, found_where_clear = 0;
  double ms = 0.0;
  void add(const LandingResult& r, const LandingFrame& f, bool clear_zone,
           const TerrainGroundTruth& truth, double radius, const LandingCriteria& crit,
           double elapsed_ms) {
    ++frames;
    ms += elapsed_ms;
    with_zone += f.safe_zone_in_view;
    with_clear_zone += clear_zone;
    found_where_clear += clear_zone && !r.zones.empty();
    if (r.zones.empty()) return;
    found_where_exists += f.safe_zone_in_view;
    found_where_none += !f.safe_zone_in_view;
    ++chose;
    chose_unsafe += !truth.is_safe(r.zones.front().center_m.head<2>(), radius, crit);
    for (const auto& z : r.zones) {
      ++listed;
      listed_unsafe += !truth.is_safe(z.center_m.head<2>(), radius, crit);
    }
  }
};

int compare(int terrains, std::uint64_t seed, bool verbose,
            const std::map<std::string, double>& set) {
  // The frames' size (the camera's field of view kept): 640 x 480 unless set.
  const auto size = [&](const char* key, int fallback) {
    const auto it = set.find(key);
    return it == set.end() ? fallback : static_cast<int>(it->second);
  };
  Setup s = setup(size("width_px", 640), size("height_px", 480));
  // Option overrides for studies (--set name=value), reported with the table.
  using Field = double LandingZoneDetector::Options::*;
  static const std::map<std::string, Field> kDetectorFields = {
      {"margin_m", &LandingZoneDetector::Options::margin_m},
      {"max_step_m", &LandingZoneDetector::Options::max_step_m},
      {"max_roughness_m", &LandingZoneDetector::Options::max_roughness_m},
      {"max_slope_deg", &LandingZoneDetector::Options::max_slope_deg},
      {"slope_sigmas", &LandingZoneDetector::Options::slope_sigmas},
      {"slope_allowance_deg", &LandingZoneDetector::Options::slope_allowance_deg},
      {"step_allowance_m", &LandingZoneDetector::Options::step_allowance_m},
      {"taller_than_m", &LandingZoneDetector::Options::taller_than_m},
      {"taller_allowance_m", &LandingZoneDetector::Options::taller_allowance_m},
      {"hover_cell_size_m", &LandingZoneDetector::Options::hover_cell_size_m},
      {"cell_size_m", &LandingZoneDetector::Options::cell_size_m},
      {"min_clearance_m", &LandingZoneDetector::Options::min_clearance_m}};
  // The scene's keys, read below.
  static const std::set<std::string> kSceneKeys = {
      "truth_radius_m", "view_radius_m", "depth_noise_per_m", "depth_dropout",   "width_px",
      "height_px",      "frames",        "hover_drift_m",     "hover_drift_deg", "frames_max"};
  for (const auto& [k, v] : set) {
    if (const auto f = kDetectorFields.find(k); f != kDetectorFields.end()) {
      s.options.*(f->second) = v;
    } else if (k == "hover_min_frames") {
      s.options.hover_min_frames = static_cast<int>(v);
    } else if (!kSceneKeys.contains(k)) {
      std::fprintf(stderr, "unknown option %s\n", k.c_str());
      return 2;
    }
    std::printf("set %s = %g\n", k.c_str(), v);
  }
  LandingSceneOptions so = scene_options(s.options);
  if (const auto r = set.find("truth_radius_m"); r != set.end()) so.footprint_radius_m = r->second;
  // The view the truth asks for round a safe disc (to compare detectors whose margins
  // need different views on the same frames).
  if (const auto r = set.find("view_radius_m"); r != set.end()) so.view_radius_m = r->second;
  // The D415 model the frames are rendered with (its noise coefficient and dropout).
  if (const auto r = set.find("depth_noise_per_m"); r != set.end())
    so.depth.noise_coefficient_per_m = r->second;
  if (const auto r = set.find("depth_dropout"); r != set.end())
    so.depth.dropout_fraction = r->second;
  if (const auto r = set.find("frames"); r != set.end())
    so.frames_per_view = std::max(1, static_cast<int>(r->second));
  // A hover that finds nothing in `frames` looks longer, as the mission's survey does
  // (uav.survey_frames_max): twice the frames each time, up to frames_max.
  const int first_frames = so.frames_per_view;
  if (const auto r = set.find("frames_max"); r != set.end())
    so.frames_per_view = std::clamp(static_cast<int>(r->second), first_frames, kMaxHoverFrames);
  const int most_frames = so.frames_per_view;
  long frames_judged = 0;
  if (const auto r = set.find("hover_drift_m"); r != set.end()) so.hover_drift_m = r->second;
  if (const auto r = set.find("hover_drift_deg"); r != set.end())
    so.hover_drift_rad = deg_to_rad(r->second);
  const LandingZoneDetector det(s.options);
  // The "clearly safe" count: the limits one frame is judged by, whatever the hover (the
  // one-frame cells' slope, step and taller-than allowances under the UAV's limits),
  // with the hover's own margin and clearance.
  // The truth's view round a safe disc stays the one-frame detector's, so that the
  // frames with a safe zone in view are the same whatever the hover.
  const LandingZoneDetector::Options& judged =
      det.options_for_frames(static_cast<std::size_t>(first_frames));
  LandingCriteria own;
  own.max_slope_deg = s.options.max_slope_deg - s.options.slope_allowance_deg;
  own.max_step_m = s.options.max_step_m - s.options.step_allowance_m;
  own.min_clearance_m = judged.min_clearance_m;
  own.taller_than_m = s.options.taller_than_m - s.options.taller_allowance_m;
  const double own_radius_m = judged.footprint_radius_m + judged.margin_m;
  const Px4LandingBaseline base(Px4LandingBaseline::Options{});
  std::map<std::string, Tally> ours, px4;  // by height, and "all"
  for (int i = 0; i < terrains; ++i) {
    const LandingScene scene = landing_scene(seed, i, s.sensor, s.camera, so);
    for (const auto& f : scene.frames) {
      const std::string key = fmt::format("{:.0f} m", f.height_m);
      std::vector<PosedDepthFrame> all{{&f.depth, f.X_WC}};
      for (std::size_t m = 0; m < f.more_depth.size(); ++m)
        all.push_back({&f.more_depth[m], f.more_X_WC[m]});
      const auto first = [&all](int n) {
        return std::vector<PosedDepthFrame>(
            all.begin(), all.begin() + std::min(static_cast<std::ptrdiff_t>(n),
                                                static_cast<std::ptrdiff_t>(all.size())));
      };
      const std::vector<PosedDepthFrame> hover = first(first_frames);
      const bool clear =
          scene.truth.safe_zone_in_view(own_radius_m, so.view_radius_m, own, s.camera, f.X_WC);
      auto t0 = std::chrono::steady_clock::now();
      LandingResult a = det.detect(hover, s.camera);
      int taken = first_frames;
      for (int next = hover_frames_after_miss(taken, most_frames); a.zones.empty() && next > taken;
           next = hover_frames_after_miss(taken, most_frames)) {
        taken = next;
        a = det.detect(first(taken), s.camera);
      }
      frames_judged += taken;
      auto t1 = std::chrono::steady_clock::now();
      const LandingResult b = base.detect(hover, s.camera, f.X_WB.translation());
      auto t2 = std::chrono::steady_clock::now();
      const double ma = std::chrono::duration<double, std::milli>(t1 - t0).count();
      const double mb = std::chrono::duration<double, std::milli>(t2 - t1).count();
      for (const std::string& k : {key, std::string("all")}) {
        ours[k].add(a, f, clear, scene.truth, so.footprint_radius_m, so.criteria, ma);
        px4[k].add(b, f, clear, scene.truth, so.footprint_radius_m, so.criteria, mb);
      }
      if (!a.zones.empty() && !scene.truth.is_safe(a.zones.front().center_m.head<2>(),
                                                   so.footprint_radius_m, so.criteria)) {
        const auto& z = a.zones.front();
        // Which criterion the truth holds against it (each relaxed alone).
        LandingCriteria slope = so.criteria, step = so.criteria, clear = so.criteria;
        slope.max_slope_deg = 90;
        step.max_step_m = 100;
        clear.min_clearance_m = 0;
        const Eigen::Vector2d c = z.center_m.head<2>();
        std::fprintf(stderr,
                     "ferret chose an unsafe zone: terrain %d (%s), %s, zone %.2f %.2f (slope "
                     "%.1f step %.3f clearance %.2f); safe without the slope test %d, the step "
                     "test %d, the clearance test %d\n",
                     i, scene.terrain.kind.c_str(), key.c_str(), c.x(), c.y(), z.slope_deg,
                     z.step_m, z.clearance_m, scene.truth.is_safe(c, so.footprint_radius_m, slope),
                     scene.truth.is_safe(c, so.footprint_radius_m, step),
                     scene.truth.is_safe(c, so.footprint_radius_m, clear));
      }
      if (verbose && a.zones.empty() && f.safe_zone_in_view) {
        std::fprintf(stderr, "missed: terrain %d (%s), %s: %s\n", i, scene.terrain.kind.c_str(),
                     key.c_str(), a.reason.c_str());
        // The rejected candidates of the result's sample (every third cell) that the
        // truth calls safe and sees whole: which test rejected them, with its values.
        for (const auto& z : a.rejected) {
          const Eigen::Vector2d c = z.center_m.head<2>();
          if (!scene.truth.is_safe(c, so.footprint_radius_m, so.criteria) ||
              !scene.truth.in_view(c, so.view_radius_m, s.camera, f.X_WC))
            continue;
          std::fprintf(stderr,
                       "  truth-safe candidate %.2f %.2f rejected (%s): slope %.1f rough %.3f "
                       "step %.3f clearance %.2f\n",
                       c.x(), c.y(), to_string(z.reject), z.slope_deg, z.roughness_m, z.step_m,
                       z.clearance_m);
        }
      }
    }
  }
  std::printf(
      "terrains: %d (seed %llu), views: %d of %d frame(s) (up to %d; %.2f judged a view), camera "
      "%s %dx%d, footprint %.3f m\n\n",
      terrains, static_cast<unsigned long long>(seed), ours["all"].frames, first_frames,
      most_frames, static_cast<double>(frames_judged) / std::max(1, ours["all"].frames),
      s.sensor.name.c_str(), s.camera.width_px, s.camera.height_px, so.footprint_radius_m);
  std::printf(
      "| detector | height | views | safe zone in view (truth) | zone found there | "
      "clearly safe zone in view | found there | found where none | chosen zones unsafe | "
      "listed zones unsafe | ms/view |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  const auto pct = [](int a, int b) { return b ? 100.0 * a / b : 0.0; };
  for (const auto& [name, table] : {std::pair{"ferret", &ours}, std::pair{"PX4 rule", &px4}})
    for (const auto& [k, t] : *table)
      std::printf(
          "| %s | %s | %d | %d | %d (%.1f %%) | %d | %d (%.1f %%) | %d | %d of %d | %d of %d | "
          "%.2f |\n",
          name, k.c_str(), t.frames, t.with_zone, t.found_where_exists,
          pct(t.found_where_exists, t.with_zone), t.with_clear_zone, t.found_where_clear,
          pct(t.found_where_clear, t.with_clear_zone), t.found_where_none, t.chose_unsafe, t.chose,
          t.listed_unsafe, t.listed, t.ms / std::max(1, t.frames));
  return 0;
}

}  // namespace
}  // namespace ferret

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--compare") == 0) {
      int terrains = 200;
      std::uint64_t seed = 1;
      bool verbose = false;
      std::map<std::string, double> set;
      for (int k = 1; k + 1 < argc; ++k) {
        if (std::strcmp(argv[k], "--terrains") == 0) terrains = std::atoi(argv[k + 1]);
        if (std::strcmp(argv[k + 1], "--verbose") == 0 || std::strcmp(argv[k], "--verbose") == 0)
          verbose = true;
        if (std::strcmp(argv[k], "--set") == 0) {
          const std::string kv = argv[k + 1];
          const auto eq = kv.find('=');
          set[kv.substr(0, eq)] = std::atof(kv.c_str() + eq + 1);
        }
        if (std::strcmp(argv[k], "--seed") == 0) seed = std::strtoull(argv[k + 1], nullptr, 10);
      }
      return ferret::compare(terrains, seed, verbose, set);
    }
  benchmark::RegisterBenchmark("landing_zone/ferret/640x480", ferret::BM_Detector, 640, 480, false,
                               1)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("landing_zone/px4_rule/640x480", ferret::BM_Detector, 640, 480, true,
                               1)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("landing_zone/ferret/1280x720", ferret::BM_Detector, 1280, 720,
                               false, 1)
      ->Unit(benchmark::kMillisecond);
  // A hover's 8 frames (the mission's uav.survey_frames): fused, then judged once.
  benchmark::RegisterBenchmark("landing_zone/ferret_hover8/640x480", ferret::BM_Detector, 640, 480,
                               false, 8)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("landing_zone/ferret_hover8/1280x720", ferret::BM_Detector, 1280,
                               720, false, 8)
      ->Unit(benchmark::kMillisecond);
  // The most a survey hover judges (uav.survey_frames_max), fused and judged once.
  benchmark::RegisterBenchmark("landing_zone/ferret_hover64/640x480", ferret::BM_Detector, 640, 480,
                               false, ferret::kMaxHoverFrames)
      ->Unit(benchmark::kMillisecond);
  // A survey view that finds nothing in 8, 16, 32 or 64 frames: re-fused at every
  // judgment, and fused as the frames come (the mission's).
  benchmark::RegisterBenchmark("landing_zone/survey_miss_fused_again/640x480",
                               ferret::BM_SurveyThatMisses, false)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("landing_zone/survey_miss_as_they_come/640x480",
                               ferret::BM_SurveyThatMisses, true)
      ->Unit(benchmark::kMillisecond);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
