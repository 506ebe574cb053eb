// The object detector on rendered frames: ms per frame (Google Benchmark), and with
// --table its conf(d) curve next to the paper's eta / d and the geometric detector.
//
//   build/release/bench/ferret_bench_object_detection            # timings
//   build/release/bench/ferret_bench_object_detection --table [--csv FILE] [--views N]
//
// The scene (tests/ugv/object_scene.hpp): the miniUGV's object camera (640 x 480,
// 90 deg, D_cam = 4 m from its URDF) on flat ground, the 8 x 8 x 5 cm object at
// distances 0.2 ... 8 m and bearings across the fov, N views each with a seeded
// random heading (so the object's yaw to the line of sight varies), exposure gain in
// [0.7, 1.3], the renderer's blur (0.8 px) and noise (2 grey levels).

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "ferret/core/random.hpp"
#include "ferret/mapping/object_map.hpp"
#include "ferret/ugv/object_detector.hpp"
#include "ferret/urdf/robot_description.hpp"
#include "ugv/object_scene.hpp"

namespace ferret {
namespace {

const RobotDescription& miniugv() {
  static const RobotDescription r =
      load_robot_description(std::string(FERRET_SOURCE_DIR) + "/urdf/models/miniugv.urdf");
  return r;
}

const test::ObjectScene& scene() {
  static const test::ObjectScene s(miniugv(), ObjectSearchParams{});
  return s;
}

void BM_ColourDetector_640x480(benchmark::State& state) {
  const test::ObjectView view{static_cast<double>(state.range(0)) / 10.0, 0.2, 0.3};
  const RgbImage img = scene().frame(view, {}, 7);
  const ugv::ColourObjectDetector det;
  for (auto _ : state) benchmark::DoNotOptimize(det.detect(img, scene().camera()));
  state.SetLabel("object at " + std::to_string(view.distance_m).substr(0, 3) + " m");
}
BENCHMARK(BM_ColourDetector_640x480)->Arg(5)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);

void BM_ColourDetector_1280x720(benchmark::State& state) {
  // The same scene through a 1280 x 720, 90 deg camera at the miniUGV camera's pose.
  const CameraModel cam = CameraModel::from_fov("hd", 1280, 720, std::numbers::pi / 2);
  const test::ObjectView view{1.5, 0.2, 0.3};
  const SensorSimulator sim(test::object_world({}));
  const RgbImage img = sim.render_camera(cam, scene().X_WC(view), {}, 7);
  const ugv::ColourObjectDetector det;
  for (auto _ : state) benchmark::DoNotOptimize(det.detect(img, cam));
}
BENCHMARK(BM_ColourDetector_1280x720)->Unit(benchmark::kMillisecond);

void BM_GeometricDetector(benchmark::State& state) {
  // HiddenSpaceSim's camera frame: the range-finder beams plus the detection.
  const test::ObjectView view{1.5, 0.2, 0.3};
  for (auto _ : state) benchmark::DoNotOptimize(scene().geometric(view));
}
BENCHMARK(BM_GeometricDetector)->Unit(benchmark::kMillisecond);

void BM_RenderObjectFrame_640x480(benchmark::State& state) {
  const test::ObjectView view{1.5, 0.2, 0.3};
  std::uint64_t seed = 1;
  for (auto _ : state) benchmark::DoNotOptimize(scene().frame(view, {}, seed++));
}
BENCHMARK(BM_RenderObjectFrame_640x480)->Unit(benchmark::kMillisecond);

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The detection nearest the object's true bearing (a frame shows one object).
const ugv::ObjectDetection* best(const std::vector<ugv::ObjectDetection>& dets) {
  return dets.empty() ? nullptr : &dets.front();
}

int table(const std::string& csv_path, int views) {
  const test::ObjectScene& s = scene();
  const ObjectSearchParams search;
  const ugv::ColourObjectDetector det(s.detector_options(search));
  const std::vector<double> bearings_deg = {0, 15, -15, 30, -30, 40, -40};
  std::ofstream csv;
  if (!csv_path.empty()) {
    csv.open(csv_path);
    csv << "distance_m,bearing_deg,view,detected,distance_est_m,confidence,geometric_detected,"
           "geometric_confidence,true_range_m\n";
  }
  std::printf(
      "| d (m) | frames | detected | geometric detected | median abs(d_est - d)/d | "
      "conf (mean) | geometric clip(eta/d) | paper eta/d | median abs(conf - geometric) |\n"
      "|---|---|---|---|---|---|---|---|---|\n");
  Rng rng(20261202);
  std::vector<double> all_conf_gap;
  for (int k = 1; k <= 40; ++k) {
    const double d = 0.2 * k;
    int frames = 0, found = 0, geo_found = 0;
    std::vector<double> rel_err, conf, geo_conf, conf_gap;
    for (const double b_deg : bearings_deg) {
      for (int n = 0; n < views; ++n) {
        const double heading = rng.uniform(-std::numbers::pi, std::numbers::pi);
        CameraFrameOptions fo;
        fo.exposure_gain = rng.uniform(0.7, 1.3);
        const std::uint64_t seed = rng.next_u64();
        const test::ObjectView view{d, deg_to_rad(b_deg), heading};
        const auto dets = det.detect(s.frame(view, fo, seed), s.camera());
        const auto geo = s.geometric(view);
        ++frames;
        const double truth = s.true_range_m(view);
        const ugv::ObjectDetection* o = best(dets);
        if (o) {
          ++found;
          rel_err.push_back(std::abs(o->distance_m - truth) / truth);
          conf.push_back(o->confidence);
        }
        double g = 0.0;
        if (geo) {
          ++geo_found;
          g = clip_confidence(geo->confidence, search.conf_floor, search.conf_cap);
          geo_conf.push_back(g);
        }
        if (o && geo) {
          conf_gap.push_back(std::abs(o->confidence - g));
          all_conf_gap.push_back(conf_gap.back());
        }
        if (csv.is_open())
          csv << fmt::format("{:.2f},{:.0f},{},{},{:.4f},{:.4f},{},{:.4f},{:.4f}\n", d, b_deg, n,
                             o ? 1 : 0, o ? o->distance_m : 0.0, o ? o->confidence : 0.0,
                             geo ? 1 : 0, g, truth);
      }
    }
    const auto mean = [](const std::vector<double>& v) {
      double sum = 0;
      for (double x : v) sum += x;
      return v.empty() ? std::nan("") : sum / v.size();
    };
    std::printf("| %.1f%s | %d | %.1f %% | %.1f %% | %.3f | %.3f | %.3f | %.3f | %.3f |\n", d,
                d > s.range_m() + 1e-9 ? " (> D_cam)" : "", frames, 100.0 * found / frames,
                100.0 * geo_found / frames, median(rel_err), mean(conf), mean(geo_conf),
                distance_confidence(search.eta_m, d), median(conf_gap));
  }
  std::sort(all_conf_gap.begin(), all_conf_gap.end());
  if (!all_conf_gap.empty())
    std::printf(
        "\n|conf - geometric| over all frames both detect: median %.4f, 95th %.4f, max %.4f\n",
        median(all_conf_gap),
        all_conf_gap[static_cast<std::size_t>(0.95 * (all_conf_gap.size() - 1))],
        all_conf_gap.back());
  return 0;
}

}  // namespace
}  // namespace ferret

int main(int argc, char** argv) {
  bool want_table = false;
  std::string csv;
  int views = 8;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--table") == 0) want_table = true;
    if (std::strcmp(argv[i], "--csv") == 0 && i + 1 < argc) csv = argv[++i];
    if (std::strcmp(argv[i], "--views") == 0 && i + 1 < argc) views = std::atoi(argv[++i]);
  }
  if (want_table) return ferret::table(csv, std::clamp(views, 1, 1000));
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
