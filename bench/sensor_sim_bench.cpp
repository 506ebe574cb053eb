// Simulated sensor frames (sim/sensor_sim.hpp) in the default world: the M100 1.85 m in
// front of house_void's marker, its marker camera (1280 x 720) and a D415-like depth
// camera (640 x 480, 65 deg) looking at it; the miniUGV's IR at the opening.
//   build/<preset>/bench/ferret_bench_sensor_sim

#include <benchmark/benchmark.h>

#include <numbers>

#include "ferret/mapping/world_spec.hpp"
#include "ferret/perception/colour.hpp"
#include "ferret/sim/sensor_sim.hpp"

namespace {
using namespace ferret;

const std::string kWorld = std::string(FERRET_SOURCE_DIR) + "/examples/worlds/default.yaml";

struct Setup {
  WorldSpec world = load_world(kWorld);
  SensorSimulator sim{world};
  RobotDescription uav = load_robot("m100"), ugv = load_robot("miniugv");
  // house_void's marker faces +x; the UAV hovers in front of it, facing -x.
  Pose3 X_WB = [this] {
    const Eigen::Vector3d p_M = world.hidden_spaces[0].marker.X_WM.translation();
    return pose_from_xyz_rpy(p_M + Eigen::Vector3d(1.85, 0, 0.9), 0, 0, std::numbers::pi);
  }();
};
const Setup& setup() {
  static const Setup s;
  return s;
}

void BM_CameraFrame1280x720(benchmark::State& state) {
  const Setup& s = setup();
  const CameraSensor& cam = s.uav.marker_camera();
  const CameraModel model = camera_model(cam, s.uav.source);
  const Pose3 X_WC = optical_pose(s.X_WB, cam);
  std::uint64_t seed = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(s.sim.render_camera(model, X_WC, {}, ++seed).data.data());
  state.counters["px"] = model.width_px * model.height_px;
}
BENCHMARK(BM_CameraFrame1280x720)->Unit(benchmark::kMillisecond);

// The grey frame the marker detectors read: rendered grey, against grey from the colour
// frame (what the mission did before render_gray).
void BM_GrayFrame1280x720(benchmark::State& state) {
  const Setup& s = setup();
  const CameraSensor& cam = s.uav.marker_camera();
  const CameraModel model = camera_model(cam, s.uav.source);
  const Pose3 X_WC = optical_pose(s.X_WB, cam);
  std::uint64_t seed = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(s.sim.render_gray(model, X_WC, {}, ++seed).data.data());
}
BENCHMARK(BM_GrayFrame1280x720)->Unit(benchmark::kMillisecond);

void BM_GrayFromColourFrame1280x720(benchmark::State& state) {
  const Setup& s = setup();
  const CameraSensor& cam = s.uav.marker_camera();
  const CameraModel model = camera_model(cam, s.uav.source);
  const Pose3 X_WC = optical_pose(s.X_WB, cam);
  std::uint64_t seed = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(to_gray(s.sim.render_camera(model, X_WC, {}, ++seed)).data.data());
}
BENCHMARK(BM_GrayFromColourFrame1280x720)->Unit(benchmark::kMillisecond);

// What the aerial search sees most of the time: 4 m up over the site, the ruins, the
// rubble and the ground ahead, no marker.
void BM_GrayFrameSearchView(benchmark::State& state) {
  const Setup& s = setup();
  const CameraSensor& cam = s.uav.marker_camera();
  const CameraModel model = camera_model(cam, s.uav.source);
  const Pose3 X_WC = optical_pose(pose_from_xyz_rpy({-25.0, 8.0, 4.0}, 0, 0, 0), cam);
  std::uint64_t seed = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(s.sim.render_gray(model, X_WC, {}, ++seed).data.data());
}
BENCHMARK(BM_GrayFrameSearchView)->Unit(benchmark::kMillisecond);

void BM_CameraFrameNoBlurNoNoise(benchmark::State& state) {
  const Setup& s = setup();
  const CameraSensor& cam = s.uav.marker_camera();
  const CameraModel model = camera_model(cam, s.uav.source);
  const Pose3 X_WC = optical_pose(s.X_WB, cam);
  CameraFrameOptions o;
  o.blur_sigma_px = o.noise_sigma = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s.sim.render_camera(model, X_WC, o, 1).data.data());
}
BENCHMARK(BM_CameraFrameNoBlurNoNoise)->Unit(benchmark::kMillisecond);

void BM_CameraFrameBlurOnly(benchmark::State& state) {
  const Setup& s = setup();
  const CameraSensor& cam = s.uav.marker_camera();
  const CameraModel model = camera_model(cam, s.uav.source);
  const Pose3 X_WC = optical_pose(s.X_WB, cam);
  CameraFrameOptions o;
  o.noise_sigma = 0;
  for (auto _ : state) benchmark::DoNotOptimize(s.sim.render_camera(model, X_WC, o, 1).data.data());
}
BENCHMARK(BM_CameraFrameBlurOnly)->Unit(benchmark::kMillisecond);

void BM_DepthFrame640x480(benchmark::State& state) {
  const Setup& s = setup();
  // The D415's depth stream at 640 x 480, where the M100's depth camera sits.
  const CameraModel model = CameraModel::from_fov("d415", 640, 480, 65.0 * std::numbers::pi / 180);
  const Pose3 X_WC = optical_pose(s.X_WB, s.uav.marker_camera());
  std::uint64_t seed = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(s.sim.render_depth(model, X_WC, {}, ++seed).data.data());
}
BENCHMARK(BM_DepthFrame640x480)->Unit(benchmark::kMillisecond);

void BM_DepthFrameM100DownLooking(benchmark::State& state) {
  const Setup& s = setup();
  const CameraSensor& cam = s.uav.depth_camera();  // 1280 x 720 as the URDF says
  const CameraModel model = camera_model(cam, s.uav.source);
  const Pose3 X_WC = optical_pose(s.X_WB, cam);
  for (auto _ : state) benchmark::DoNotOptimize(s.sim.render_depth(model, X_WC, {}, 1).data.data());
  state.counters["px"] = model.width_px * model.height_px;
}
BENCHMARK(BM_DepthFrameM100DownLooking)->Unit(benchmark::kMillisecond);

void BM_VisibleMarkers(benchmark::State& state) {
  const Setup& s = setup();
  const CameraSensor& cam = s.uav.marker_camera();
  const CameraModel model = camera_model(cam, s.uav.source);
  const Pose3 X_WC = optical_pose(s.X_WB, cam);
  for (auto _ : state) benchmark::DoNotOptimize(s.sim.visible_markers(model, X_WC).size());
}
BENCHMARK(BM_VisibleMarkers)->Unit(benchmark::kMicrosecond);

void BM_IrScan(benchmark::State& state) {
  const Setup& s = setup();
  const HiddenSpace& h = s.world.hidden_spaces[0];
  const Pose3 X_WB =
      pose_from_xyz_rpy(h.p_WE + Eigen::Vector3d(0.3, 0.1, 0), 0, 0, h.entry_yaw_rad);
  std::uint64_t seed = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(s.sim.ir_ranges(s.ugv, X_WB, SensorOptions{}, ++seed).size());
}
BENCHMARK(BM_IrScan)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
