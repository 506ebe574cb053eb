// Marker detection: AprilTag 3 vs OpenCV ArUco on frames rendered by SensorSimulator
// from the default world, from poses the UAV would fly.
//
//   build/<preset>/bench/ferret_bench_marker_detection            Google Benchmark timings
//   ... --evaluate [--frames N] [--seed S] [--markers LIST]        detection/pose table
//   ... --false-positives N [--seed S] [--markers LIST]            frames with no marker
//
// LIST: the columns, family:dictionary separated by commas (default
// apriltag:tag36h11,aruco:DICT_4X4_50). The evaluation renders each pose once per
// column's dictionary (same ids, sizes, placement), with the same seed, blur, noise and
// exposure, so the detectors meet the same views; the families' cells differ in size
// (a tag36h11 marker is 8 cells across its black border, a 4x4 or tag16h5 one 6). Every number
// follows from the seed (core/random.hpp). docs/results/markers.md has the
// figures and the commands.

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "ferret/perception/colour.hpp"
#include "ferret/sim/sensor_sim.hpp"
#include "ferret/uav/marker_detector.hpp"
#include "ferret/uav/opening_locator.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace {
using namespace ferret;

const std::string kSource = FERRET_SOURCE_DIR;

CameraModel m100_marker_camera() {
  const std::string urdf = kSource + "/urdf/models/m100.urdf";
  return camera_model(load_robot(urdf).marker_camera(), urdf);
}

WorldSpec world_with(const MarkerDictionary& dictionary) {
  WorldSpec w = load_world(kSource + "/examples/worlds/default.yaml");
  for (auto& h : w.hidden_spaces) h.marker.dictionary = dictionary;
  return w;
}
WorldSpec world_with(MarkerFamily family) {
  MarkerDictionary d;
  d.family = family;
  d.name = default_marker_dictionary(family);
  return world_with(d);
}

// A camera looking from `p_W` towards `target_W`, rolled about its optical axis.
Pose3 look_at(const Eigen::Vector3d& p_W, const Eigen::Vector3d& target_W, double roll_rad) {
  const Eigen::Vector3d z = (target_W - p_W).normalized();
  Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ());
  if (x.norm() < 1e-6) x = Eigen::Vector3d::UnitX();
  x.normalize();
  const Eigen::Vector3d y = z.cross(x);
  Pose3 X = Pose3::Identity();
  X.linear().col(0) = x;
  X.linear().col(1) = y;
  X.linear().col(2) = z;
  X.linear() =
      X.linear() * Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = p_W;
  return X;
}

struct View {
  int hidden_space = 0;
  Pose3 X_WC;
  CameraFrameOptions frame;
  std::uint64_t seed = 0;
};

// A UAV's view of one of the world's markers: 1-10 m away, 0-75 deg off the marker's
// normal (any azimuth, the camera at least 0.4 m above the ground), the marker anywhere
// in the image, the camera rolled up to 30 deg; blur, noise and exposure as a real
// flight varies them.
View sample_view(const WorldSpec& world, const CameraModel& camera, Rng& rng) {
  View v;
  v.hidden_space = static_cast<int>(
      rng.uniform_int(0, static_cast<std::int64_t>(world.hidden_spaces.size()) - 1));
  const Pose3& X_WM = world.hidden_spaces[static_cast<std::size_t>(v.hidden_space)].marker.X_WM;
  const Eigen::Vector3d p_WM = X_WM.translation();
  Eigen::Vector3d p_W;
  double d = 0.0;
  do {
    d = rng.uniform(1.0, 10.0);
    const double theta = rng.uniform(0.0, deg_to_rad(75.0)), phi = rng.uniform(0.0, 2 * M_PI);
    const Eigen::Vector3d u = std::cos(theta) * X_WM.linear().col(2) +
                              std::sin(theta) * (std::cos(phi) * X_WM.linear().col(0) +
                                                 std::sin(phi) * X_WM.linear().col(1));
    p_W = p_WM + d * u;
  } while (p_W.z() < 0.4);
  // Aim off the marker by up to 80 % of the half field of view.
  const Pose3 X_aim = look_at(p_W, p_WM, 0.0);
  const double ax = rng.uniform(-0.8, 0.8) * std::tan(camera.horizontal_fov_rad() / 2);
  const double ay = rng.uniform(-0.8, 0.8) * std::tan(camera.vertical_fov_rad() / 2);
  const Eigen::Vector3d target = p_W + X_aim.linear() * Eigen::Vector3d(-ax, -ay, 1.0);
  v.X_WC = look_at(p_W, target, rng.uniform(-deg_to_rad(30.0), deg_to_rad(30.0)));
  v.frame.blur_sigma_px = rng.uniform(0.3, 1.5);
  v.frame.noise_sigma = rng.uniform(1.0, 5.0);
  v.frame.exposure_gain = rng.uniform(0.6, 1.4);
  v.seed = rng.next_u64();
  return v;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::min<double>(v.size() - 1, std::floor(q * v.size())))];
}

struct Column {
  std::string name;
  MarkerDictionary dictionary;  ///< the markers it reads, rendered for it
  std::unique_ptr<MarkerDetector> detector;
  std::unique_ptr<SensorSimulator> sim;
  // Eligible: the whole marker visible, >= 20 px, <= 60 deg off-axis.
  int eligible = 0, eligible_found = 0, false_detections = 0;
  int duplicates = 0;  ///< detections of an id already detected in the same frame
  std::map<std::pair<int, int>, std::pair<int, int>> bins;  ///< (d bin, angle bin) -> (found, seen)
  std::map<int, std::pair<int, int>> side_bins;  ///< side bin (<= 60 deg) -> (found, seen)
  std::vector<double> t_err_3m, r_err_3m_deg, entry_err_3m, entry_err_all, ms;
};

constexpr double kDistEdges[] = {1, 2, 3, 4, 6, 8, 10.01};
constexpr double kAngleEdges[] = {0, 20, 40, 60, 75.01};
constexpr double kSideEdges[] = {20, 24, 28, 32, 40, 60, 1e9};
int bin_of(double v, const double* edges, int n) {
  for (int i = 0; i + 1 < n; ++i)
    if (v < edges[i + 1]) return i;
  return n - 2;
}

bool matches(const MarkerDetection& d, const VisibleMarker& m, double tol_px) {
  if (d.id != m.id) return false;
  double sum = 0.0;
  for (int k = 0; k < 4; ++k) sum += (d.corners_px[k] - m.corners_px[k]).norm();
  return sum / 4 < tol_px;
}

// "family:dictionary,..." -> one column each; exits 2 naming the bad entry.
std::vector<Column> make_columns(const std::string& list) {
  std::vector<Column> c;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t end = std::min(list.find(',', start), list.size());
    const std::string item = list.substr(start, end - start);
    start = end + 1;
    const std::size_t colon = item.find(':');
    try {
      if (colon == std::string::npos) throw InputError("--markers", item, "family:dictionary");
      MarkerDetectorOptions o;
      o.dictionary.family = parse_marker_family(item.substr(0, colon), "--markers", item);
      o.dictionary.name = item.substr(colon + 1);
      o.marker_size_m = 0.2;  // the default world's markers
      Column col;
      col.name = fmt::format("{} {}", to_string(o.dictionary.family), o.dictionary.name);
      col.dictionary = o.dictionary;
      col.detector = make_marker_detector(o);
      col.sim = std::make_unique<SensorSimulator>(world_with(o.dictionary));
      c.push_back(std::move(col));
    } catch (const InputError& e) {
      std::fprintf(stderr, "ferret_bench_marker_detection: %s\n", e.what());
      std::exit(2);
    }
  }
  return c;
}

// A Markdown table's first two lines: `corner`, then one column a detector.
std::string table_header(const std::string& corner, const std::vector<Column>& columns) {
  std::string head = fmt::format("| {} |", corner), sep = "|---|";
  for (const Column& c : columns) {
    head += fmt::format(" {} |", c.name);
    sep += "---|";
  }
  return head + "\n" + sep + "\n";
}

template <typename F>
std::vector<MarkerDetection> timed(const MarkerDetector& det, const GrayImage& g,
                                   const CameraModel& cam, std::vector<double>& ms, F&&) {
  const auto t0 = std::chrono::steady_clock::now();
  auto out = det.detect(g, cam);
  ms.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  return out;
}

int evaluate(int frames, std::uint64_t seed, const std::string& markers) {
  const CameraModel camera = m100_marker_camera();
  const WorldSpec aruco_world = world_with(MarkerFamily::kAruco);
  std::vector<Column> columns = make_columns(markers);
  Rng rng(seed);
  int ineligible = 0;
  for (int f = 0; f < frames; ++f) {
    const View v = sample_view(aruco_world, camera, rng);
    for (Column& c : columns) {
      const auto visible = c.sim->visible_markers(camera, v.X_WC);
      const GrayImage frame = to_gray(c.sim->render_camera(camera, v.X_WC, v.frame, v.seed));
      const auto found = timed(*c.detector, frame, camera, c.ms, 0);
      for (std::size_t i = 0; i < found.size(); ++i)
        for (std::size_t j = 0; j < i; ++j)
          if (found[j].id == found[i].id) {
            ++c.duplicates;
            break;
          }
      for (const auto& d : found) {
        bool ok = false;
        for (const auto& m : visible) ok = ok || matches(d, m, 10.0);
        if (!ok) ++c.false_detections;
      }
      for (const auto& m : visible) {
        if (m.visible_fraction < 0.999) continue;  // partly hidden: not the target's set
        double shortest = 1e9;
        for (int k = 0; k < 4; ++k)
          shortest = std::min(shortest, (m.corners_px[k] - m.corners_px[(k + 1) % 4]).norm());
        const double angle_deg = rad_to_deg(m.off_axis_rad);
        const MarkerDetection* hit = nullptr;
        for (const auto& d : found)
          if (matches(d, m, 3.0)) hit = &d;
        if (shortest >= 20.0) {
          auto& b =
              c.bins[{bin_of(m.distance_m, kDistEdges, 7), bin_of(angle_deg, kAngleEdges, 5)}];
          ++b.second;
          if (hit) ++b.first;
        }
        const bool eligible = shortest >= 20.0 && angle_deg <= 60.0;
        if (eligible) {
          auto& b = c.side_bins[bin_of(shortest, kSideEdges, 7)];
          ++b.second;
          if (hit) ++b.first;
          ++c.eligible;
          if (hit) ++c.eligible_found;
          if (!hit && std::getenv("FERRET_BENCH_MISSES"))
            std::fprintf(stderr,
                         "miss %s frame %d: d %.2f m, %.0f deg, side %.1f px, blur %.2f, noise "
                         "%.1f, gain %.2f, found %zu\n",
                         c.name.c_str(), f, m.distance_m, angle_deg, shortest,
                         v.frame.blur_sigma_px, v.frame.noise_sigma, v.frame.exposure_gain,
                         found.size());
        } else if (&c == &columns[0]) {
          ++ineligible;
        }
        if (!hit) continue;
        const HiddenSpace& h = aruco_world.hidden_spaces[static_cast<std::size_t>(m.hidden_space)];
        const OpeningEstimate e = locate_opening(*hit, v.X_WC, opening_in_marker(h));
        const double entry_err = (e.p_WE - h.p_WE).norm();
        c.entry_err_all.push_back(entry_err);
        if (m.distance_m >= 2.5 && m.distance_m < 3.5) {
          c.entry_err_3m.push_back(entry_err);
          c.t_err_3m.push_back((hit->X_CM.translation() - m.X_CM.translation()).norm());
          c.r_err_3m_deg.push_back(rad_to_deg(
              Eigen::AngleAxisd(hit->X_CM.linear().transpose() * m.X_CM.linear()).angle()));
        }
      }
    }
    if ((f + 1) % 100 == 0) std::fprintf(stderr, "\r%d / %d frames", f + 1, frames);
  }
  std::fprintf(stderr, "\n");
  fmt::print("frames: {} (seed {}), camera {} {}x{} hfov {:.1f} deg\n\n", frames, seed, camera.name,
             camera.width_px, camera.height_px, rad_to_deg(camera.horizontal_fov_rad()));
  fmt::print("{}", table_header("", columns));
  auto row = [&](const std::string& label, auto cell) {
    std::string line = fmt::format("| {} |", label);
    for (auto& c : columns) line += fmt::format(" {} |", cell(c));
    fmt::print("{}\n", line);
  };
  row("detected (>= 20 px, <= 60 deg, whole marker in view)", [](Column& c) {
    return fmt::format("{}/{} = {:.2f} %", c.eligible_found, c.eligible,
                       100.0 * c.eligible_found / std::max(1, c.eligible));
  });
  row("false detections", [](Column& c) { return std::to_string(c.false_detections); });
  row("duplicate detections (an id twice in a frame)",
      [](Column& c) { return std::to_string(c.duplicates); });
  row("opening p_WE error median at 2.5-3.5 m", [](Column& c) {
    return fmt::format("{:.1f} mm (n {})", 1e3 * percentile(c.entry_err_3m, 0.5),
                       c.entry_err_3m.size());
  });
  row("opening p_WE error p95 at 2.5-3.5 m",
      [](Column& c) { return fmt::format("{:.1f} mm", 1e3 * percentile(c.entry_err_3m, 0.95)); });
  row("t_CM error median / p95 at 2.5-3.5 m", [](Column& c) {
    return fmt::format("{:.1f} / {:.1f} mm", 1e3 * percentile(c.t_err_3m, 0.5),
                       1e3 * percentile(c.t_err_3m, 0.95));
  });
  row("R_CM error median / p95 at 2.5-3.5 m", [](Column& c) {
    return fmt::format("{:.2f} / {:.2f} deg", percentile(c.r_err_3m_deg, 0.5),
                       percentile(c.r_err_3m_deg, 0.95));
  });
  row("opening p_WE error median, all distances",
      [](Column& c) { return fmt::format("{:.1f} mm", 1e3 * percentile(c.entry_err_all, 0.5)); });
  row("detect time median / p95 (1280x720, one core)", [](Column& c) {
    return fmt::format("{:.2f} / {:.2f} ms", percentile(c.ms, 0.5), percentile(c.ms, 0.95));
  });
  fmt::print(
      "\nDetection rate by distance (rows, m) and off-axis angle (columns, deg), markers "
      ">= 20 px wholly in view (found/seen):\n");
  for (auto& c : columns) {
    fmt::print("\n{}\n\n| d \\ angle | 0-20 | 20-40 | 40-60 | 60-75 |\n|---|---|---|---|---|\n",
               c.name);
    for (int di = 0; di < 6; ++di) {
      std::string line =
          fmt::format("| {:g}-{:g} |", kDistEdges[di], std::floor(kDistEdges[di + 1]));
      for (int ai = 0; ai < 4; ++ai) {
        const auto it = c.bins.find({di, ai});
        line +=
            it == c.bins.end() || it->second.second == 0
                ? " - |"
                : fmt::format(" {:.1f} % ({}/{}) |", 100.0 * it->second.first / it->second.second,
                              it->second.first, it->second.second);
      }
      fmt::print("{}\n", line);
    }
  }
  fmt::print(
      "\nDetection rate by the marker's shortest side in the image (px), <= 60 deg off-axis, "
      "wholly in view (found/seen):\n\n{}",
      table_header("side \\ markers", columns));
  for (int si = 0; si < 6; ++si) {
    std::string line = si == 5 ? fmt::format("| >= {:g} |", kSideEdges[si])
                               : fmt::format("| {:g}-{:g} |", kSideEdges[si], kSideEdges[si + 1]);
    for (auto& c : columns) {
      const auto it = c.side_bins.find(si);
      line += it == c.side_bins.end() || it->second.second == 0
                  ? " - |"
                  : fmt::format(" {:.1f} % ({}/{}) |", 100.0 * it->second.first / it->second.second,
                                it->second.first, it->second.second);
    }
    fmt::print("{}\n", line);
  }
  fmt::print("\n(markers seen but not in the target's set: {} in the first column's frames)\n",
             ineligible);
  return 0;
}

// Views over the whole site (any position inside the bounds, 0.5-8 m up, looking
// 0-80 deg below the horizon) that show no marker: every detection is a false one.
int false_positives(int frames, std::uint64_t seed, const std::string& markers) {
  const CameraModel camera = m100_marker_camera();
  const WorldSpec aruco_world = world_with(MarkerFamily::kAruco);
  const SensorSimulator aruco_sim(aruco_world);
  std::vector<Column> columns = make_columns(markers);
  Rng rng(seed);
  int done = 0, skipped = 0;
  while (done < frames) {
    const Eigen::Vector3d lo = aruco_world.bounds_min_m, hi = aruco_world.bounds_max_m;
    const Eigen::Vector3d p{rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()),
                            rng.uniform(0.5, 8.0)};
    const double yaw = rng.uniform(-M_PI, M_PI), down = rng.uniform(0.0, deg_to_rad(80.0));
    const Eigen::Vector3d dir{std::cos(yaw) * std::cos(down), std::sin(yaw) * std::cos(down),
                              -std::sin(down)};
    const Pose3 X_WC = look_at(p, p + dir, rng.uniform(-0.3, 0.3));
    CameraFrameOptions o;
    o.blur_sigma_px = rng.uniform(0.3, 1.5);
    o.noise_sigma = rng.uniform(1.0, 5.0);
    o.exposure_gain = rng.uniform(0.6, 1.4);
    const std::uint64_t s = rng.next_u64();
    if (!aruco_sim.visible_markers(camera, X_WC).empty()) {
      ++skipped;
      continue;
    }
    // No marker in view: the frame is the same whatever the markers' family.
    const GrayImage frame = to_gray(aruco_sim.render_camera(camera, X_WC, o, s));
    for (Column& c : columns) {
      const auto found = timed(*c.detector, frame, camera, c.ms, 0);
      c.false_detections += static_cast<int>(found.size());
    }
    if (++done % 100 == 0) std::fprintf(stderr, "\r%d / %d frames", done, frames);
  }
  std::fprintf(stderr, "\n");
  fmt::print(
      "frames without a marker in view: {} (seed {}; {} sampled views showed one and were "
      "skipped)\n\n| detector | false detections | detect time median / p95 |\n|---|---|---|\n",
      frames, seed, skipped);
  for (auto& c : columns)
    fmt::print("| {} | {} | {:.2f} / {:.2f} ms |\n", c.name, c.false_detections,
               percentile(c.ms, 0.5), percentile(c.ms, 0.95));
  return 0;
}

// Google Benchmark: one detector on one rendered 1280x720 frame (the marker at 3 m, or
// no marker).
void BM_Detect(benchmark::State& state, MarkerFamily family, bool with_marker,
               double quad_decimate = 2.0, const char* dictionary = nullptr) {
  const CameraModel camera = m100_marker_camera();
  MarkerDictionary dict;
  dict.family = family;
  dict.name = dictionary ? dictionary : default_marker_dictionary(family);
  const WorldSpec world = world_with(dict);
  const SensorSimulator sim(world);
  Rng rng(7);
  GrayImage frame;
  for (int tries = 0; tries < 1000; ++tries) {
    View v = sample_view(world, camera, rng);
    if (!with_marker) v.X_WC = look_at({0, 0, 6}, {20, 20, 0}, 0.0);
    const auto vis = sim.visible_markers(camera, v.X_WC);
    if (with_marker && (vis.empty() || std::abs(vis[0].distance_m - 3.0) > 0.5)) continue;
    frame = to_gray(sim.render_camera(camera, v.X_WC, v.frame, v.seed));
    break;
  }
  MarkerDetectorOptions o;
  o.dictionary = dict;
  o.marker_size_m = 0.2;
  o.quad_decimate = quad_decimate;
  const auto det = make_marker_detector(o);
  std::size_t n = 0;
  for (auto _ : state) {
    n = det->detect(frame, camera).size();
    benchmark::DoNotOptimize(n);
  }
  state.counters["markers"] = static_cast<double>(n);
}
BENCHMARK_CAPTURE(BM_Detect, apriltag_marker_at_3m, MarkerFamily::kAprilTag, true)
    ->Unit(benchmark::kMillisecond);
// The trade-off behind the default quad_decimate = 2.
BENCHMARK_CAPTURE(BM_Detect, apriltag_decimate1_marker_at_3m, MarkerFamily::kAprilTag, true, 1.0)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Detect, apriltag_decimate1_no_marker, MarkerFamily::kAprilTag, false, 1.0)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Detect, aruco_marker_at_3m, MarkerFamily::kAruco, true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Detect, apriltag_no_marker, MarkerFamily::kAprilTag, false)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Detect, aruco_no_marker, MarkerFamily::kAruco, false)
    ->Unit(benchmark::kMillisecond);
// AprilTag families with larger cells (docs/results/markers.md, by family).
BENCHMARK_CAPTURE(BM_Detect, apriltag_tag25h9_marker_at_3m, MarkerFamily::kAprilTag, true, 2.0,
                  "tag25h9")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Detect, apriltag_tag25h9_no_marker, MarkerFamily::kAprilTag, false, 2.0,
                  "tag25h9")
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  int frames = 2000, fp = 0;
  bool eval = false;
  std::uint64_t seed = 11;
  std::string markers = "apriltag:tag36h11,aruco:DICT_4X4_50";
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--evaluate")
      eval = true;
    else if (a == "--frames" && i + 1 < argc)
      frames = std::atoi(argv[++i]);
    else if (a == "--false-positives" && i + 1 < argc)
      fp = std::atoi(argv[++i]);
    else if (a == "--seed" && i + 1 < argc)
      seed = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--markers" && i + 1 < argc)
      markers = argv[++i];
    else
      rest.push_back(argv[i]);
  }
  if (fp > 0) return false_positives(fp, seed, markers);
  if (eval) return evaluate(frames, seed, markers);
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
