// Marker detection on frames the simulator renders from the default world (its real
// marker bitmaps, shading, occlusion, blur and noise), from seeded UAV-like views; the
// small version of bench/marker_detection_bench.cpp --evaluate.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "ferret/core/random.hpp"
#include "ferret/mapping/world_spec.hpp"
#include "ferret/perception/colour.hpp"
#include "ferret/sim/sensor_sim.hpp"
#include "ferret/uav/marker_detector.hpp"
#include "ferret/uav/opening_locator.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

const std::string kSource = FERRET_SOURCE_DIR;

CameraModel m100_marker_camera() {
  const std::string urdf = kSource + "/urdf/models/m100.urdf";
  return camera_model(load_robot(urdf).marker_camera(), urdf);
}

WorldSpec default_world(MarkerFamily family) {
  WorldSpec w = load_world(kSource + "/examples/worlds/default.yaml");
  for (auto& h : w.hidden_spaces) {
    h.marker.dictionary.family = family;
    h.marker.dictionary.name = default_marker_dictionary(family);
  }
  return w;
}

Pose3 look_at(const Eigen::Vector3d& p_W, const Eigen::Vector3d& target_W, double roll_rad) {
  const Eigen::Vector3d z = (target_W - p_W).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  Pose3 X = Pose3::Identity();
  X.linear() << x, z.cross(x), z;
  X.linear() =
      X.linear() * Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = p_W;
  return X;
}

struct Views {
  int seen = 0, found = 0, false_detections = 0;
  std::vector<double> entry_error_m;
};

// `frames` views of the world's markers from `d_lo`..`d_hi` m, up to 60 deg off their
// normal, the marker anywhere in the middle of the image, blur 0.3-1.2 px, noise 1-4
// grey levels, exposure 0.7-1.3. Counts the markers wholly in view whose black square
// spans at least `min_side_px`.
Views run(MarkerFamily family, int frames, double d_lo, double d_hi, double min_side_px,
          std::uint64_t seed) {
  const CameraModel camera = m100_marker_camera();
  const WorldSpec world = default_world(family);
  const SensorSimulator sim(world);
  MarkerDetectorOptions o = marker_detector_options(world.hidden_spaces[0].marker);
  const auto detector = make_marker_detector(o);
  Rng rng(seed);
  Views out;
  for (int f = 0; f < frames; ++f) {
    const auto hs = static_cast<std::size_t>(rng.uniform_int(0, 1));
    const HiddenSpace& h = world.hidden_spaces[hs];
    const Pose3& X_WM = h.marker.X_WM;
    Eigen::Vector3d p_W;
    do {
      const double d = rng.uniform(d_lo, d_hi), theta = rng.uniform(0.0, deg_to_rad(60.0)),
                   phi = rng.uniform(0.0, 2 * M_PI);
      p_W = X_WM.translation() + d * (std::cos(theta) * X_WM.linear().col(2) +
                                      std::sin(theta) * (std::cos(phi) * X_WM.linear().col(0) +
                                                         std::sin(phi) * X_WM.linear().col(1)));
    } while (p_W.z() < 0.4);
    const Pose3 aim = look_at(p_W, X_WM.translation(), 0.0);
    const Eigen::Vector3d target =
        p_W + aim.linear() * Eigen::Vector3d(rng.uniform(-0.4, 0.4), rng.uniform(-0.25, 0.25), 1.0);
    const Pose3 X_WC = look_at(p_W, target, rng.uniform(-0.5, 0.5));
    CameraFrameOptions frame;
    frame.blur_sigma_px = rng.uniform(0.3, 1.2);
    frame.noise_sigma = rng.uniform(1.0, 4.0);
    frame.exposure_gain = rng.uniform(0.7, 1.3);
    const auto found =
        detector->detect(to_gray(sim.render_camera(camera, X_WC, frame, rng.next_u64())), camera);
    const auto visible = sim.visible_markers(camera, X_WC);
    for (const auto& d : found) {
      bool matches = false;
      for (const auto& m : visible)
        matches = matches || (m.id == d.id && (m.corners_px[0] - d.corners_px[0]).norm() < 5.0);
      if (!matches) ++out.false_detections;
    }
    for (const auto& m : visible) {
      double side = 1e9;
      for (int k = 0; k < 4; ++k)
        side = std::min(side, (m.corners_px[k] - m.corners_px[(k + 1) % 4]).norm());
      if (m.visible_fraction < 0.999 || side < min_side_px || m.off_axis_rad > deg_to_rad(60.0))
        continue;
      ++out.seen;
      for (const auto& d : found)
        if (d.id == m.id && (m.corners_px[0] - d.corners_px[0]).norm() < 3.0) {
          ++out.found;
          const HiddenSpace& hm = world.hidden_spaces[static_cast<std::size_t>(m.hidden_space)];
          out.entry_error_m.push_back(
              (locate_opening(d, X_WC, opening_in_marker(hm)).p_WE - hm.p_WE).norm());
          break;
        }
    }
  }
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? std::nan("") : v[v.size() / 2];
}

class RenderedMarkers : public ::testing::TestWithParam<MarkerFamily> {};

// Markers of 30 px and more (about 5 m and nearer for the 0.2 m markers) are all found;
// no detection is anything but a marker in view.
TEST_P(RenderedMarkers, EveryMarkerOfAtLeast30PxIsFoundAndNothingElse) {
  const Views v = run(GetParam(), 60, 1.0, 5.0, 30.0, 21);
  ASSERT_GE(v.seen, 30);
  EXPECT_EQ(v.found, v.seen);
  EXPECT_EQ(v.false_detections, 0);
}

// The opening target: median position error of the entry point <= 3 cm at 3 m.
TEST_P(RenderedMarkers, OpeningWithin3CmAt3M) {
  const Views v = run(GetParam(), 30, 2.5, 3.5, 20.0, 22);
  ASSERT_GE(v.entry_error_m.size(), 15u);
  EXPECT_LE(median(v.entry_error_m), 0.03);
}

INSTANTIATE_TEST_SUITE_P(Families, RenderedMarkers,
                         ::testing::Values(MarkerFamily::kAprilTag, MarkerFamily::kAruco),
                         [](const auto& info) { return std::string(to_string(info.param)); });

}  // namespace
}  // namespace ferret
