// Marker detection on frames with a marker at a known pose (marker_test_frames.hpp):
// ids, corners and poses against the exact ground truth, for both detectors.

#include "ferret/uav/marker_detector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"
#include "uav/marker_test_frames.hpp"

namespace ferret {
namespace {

using test::MarkerScene;

constexpr double kDeg = M_PI / 180.0;

// The M100's marker camera (urdf/models/m100.urdf): 1280 x 720, 78 deg.
CameraModel marker_camera() {
  return CameraModel::from_fov("marker", 1280, 720, 1.3613568165555772);
}

MarkerDictionary apriltag36h11() { return test::dictionary(MarkerFamily::kAprilTag, "tag36h11"); }
MarkerDictionary aruco4x4() { return test::dictionary(MarkerFamily::kAruco, "DICT_4X4_50"); }

std::unique_ptr<MarkerDetector> detector(const MarkerDictionary& dict, double size_m = 0.2) {
  MarkerDetectorOptions o;
  o.dictionary = dict;
  o.marker_size_m = size_m;
  return make_marker_detector(o);
}

double rotation_error_rad(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

// How well a square's tilt is known from its corners: tilting it by theta makes its
// near and far edges differ in length by about L s sin(theta) / z (L = f s / z, its
// side in pixels), so a corner error delta hides tilts up to asin(delta z^2 / (f s^2)).
// With delta = 0.5 px (half this test's corner bound) plus 1 deg: 1.9 deg at 1 m, 8 deg
// at 3 m for a 0.2 m marker in the M100's camera (fronto-parallel views are the worst).
double tilt_tolerance_rad(const CameraModel& camera, double size_m, double z_m) {
  return std::asin(std::min(1.0, 0.5 * z_m * z_m / (camera.fx_px * size_m * size_m))) + kDeg;
}

// Views of a random marker (id 0-49) as a flight meets them: distance, off-axis angle
// either way, any roll, anywhere in the middle of the image; blur, noise, exposure.
struct RandomViews {
  std::pair<double, double> distance_m;
  double max_off_axis_deg = 60.0;
  std::pair<double, double> blur_px, noise, exposure_gain;
};

MarkerScene random_scene(Rng& rng, const MarkerDictionary& dictionary, const RandomViews& v) {
  MarkerScene s;
  s.dictionary = dictionary;
  s.id = static_cast<int>(rng.uniform_int(0, 49));
  const double d = rng.uniform(v.distance_m.first, v.distance_m.second);
  const double off_axis = rng.uniform(0.0, v.max_off_axis_deg) * kDeg;
  s.X_CM = test::marker_ahead(d, (rng.bernoulli(0.5) ? 1 : -1) * off_axis, rng.uniform(-M_PI, M_PI),
                              {rng.uniform(-0.4, 0.4) * d, rng.uniform(-0.2, 0.2) * d});
  s.blur_sigma_px = rng.uniform(v.blur_px.first, v.blur_px.second);
  s.noise_sigma = rng.uniform(v.noise.first, v.noise.second);
  s.exposure_gain = rng.uniform(v.exposure_gain.first, v.exposure_gain.second);
  s.seed = rng.next_u64();
  return s;
}

double shortest_side_px(const std::array<Eigen::Vector2d, 4>& corners) {
  double shortest = 1e9;
  for (int k = 0; k < 4; ++k)
    shortest = std::min(shortest, (corners[k] - corners[(k + 1) % 4]).norm());
  return shortest;
}

class BothDetectors : public ::testing::TestWithParam<MarkerDictionary> {};

// Several distances and off-axis angles, rolled in the image so that a corner order
// that is right only for an upright marker fails.
TEST_P(BothDetectors, FindsTheMarkerWithItsIdCornersAndPose) {
  const CameraModel camera = marker_camera();
  const auto det = detector(GetParam());
  int frames = 0;
  for (double d : {0.6, 1.0, 2.0, 3.0})
    for (double yaw_deg : {0.0, 30.0, -50.0})
      for (double roll_deg : {0.0, 100.0}) {
        MarkerScene s;
        s.dictionary = GetParam();
        s.id = 7;
        s.X_CM = test::marker_ahead(d, yaw_deg * kDeg, roll_deg * kDeg, {0.1 * d, -0.05 * d});
        s.seed = static_cast<std::uint64_t>(++frames);
        const auto found = det->detect(test::render_marker_frame(camera, s), camera);
        SCOPED_TRACE(::testing::Message()
                     << "d " << d << " yaw " << yaw_deg << " roll " << roll_deg);
        ASSERT_EQ(found.size(), 1u);
        EXPECT_EQ(found[0].id, 7);
        const auto truth = test::true_corners_px(camera, s);
        for (int k = 0; k < 4; ++k) EXPECT_LT((found[0].corners_px[k] - truth[k]).norm(), 1.0) << k;
        EXPECT_LT(found[0].reprojection_error_px, 1.0);
        // Pose: a few mm a metre (the corner error over the focal length, times d^2/s).
        const double t_err = (found[0].X_CM.translation() - s.X_CM.translation()).norm();
        EXPECT_LT(t_err, 0.005 * d * d + 0.002);
        EXPECT_LT(rotation_error_rad(found[0].X_CM.linear(), s.X_CM.linear()),
                  tilt_tolerance_rad(camera, s.size_m, d));
      }
}

// A barrel-distorted lens: the pose goes through K and D, the corners stay distorted.
TEST_P(BothDetectors, PoseThroughADistortedLens) {
  CameraModel camera = marker_camera();
  camera.distortion = DistortionModel::kPlumbBob;
  camera.distortion_coefficients = {-0.28, 0.07, 0.0005, -0.0003, 0.0};
  const auto det = detector(GetParam());
  MarkerScene s;
  s.dictionary = GetParam();
  s.id = 3;
  s.X_CM = test::marker_ahead(1.0, 20 * kDeg, 0.0, {0.35, 0.2});
  const auto found = det->detect(test::render_marker_frame(camera, s), camera);
  ASSERT_EQ(found.size(), 1u);
  const auto truth = test::true_corners_px(camera, s);
  // AprilTag fits straight lines to edges the lens bends: its corners may be off by
  // the edges' sag (about a pixel here); ArUco refines each corner locally.
  const double corner_tol_px = GetParam().family == MarkerFamily::kAprilTag ? 1.5 : 1.0;
  for (int k = 0; k < 4; ++k)
    EXPECT_LT((found[0].corners_px[k] - truth[k]).norm(), corner_tol_px) << k;
  EXPECT_LT((found[0].X_CM.translation() - s.X_CM.translation()).norm(), 0.007);
  EXPECT_LT(rotation_error_rad(found[0].X_CM.linear(), s.X_CM.linear()), 2 * kDeg);
}

TEST_P(BothDetectors, HalfCoveredMarkerIsNotReported) {
  const CameraModel camera = marker_camera();
  const auto det = detector(GetParam());
  for (double d : {0.8, 1.5}) {
    MarkerScene s;
    s.dictionary = GetParam();
    s.id = 5;
    s.X_CM = test::marker_ahead(d, 10 * kDeg);
    ASSERT_EQ(det->detect(test::render_marker_frame(camera, s), camera).size(), 1u);
    s.occluded_fraction = 0.5;
    EXPECT_TRUE(det->detect(test::render_marker_frame(camera, s), camera).empty()) << d;
  }
}

TEST_P(BothDetectors, FramesWithoutAMarkerGiveNone) {
  const CameraModel camera = marker_camera();
  const auto det = detector(GetParam());
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    MarkerScene s;
    s.dictionary = GetParam();
    s.draw_marker = false;
    s.noise_sigma = 4.0;
    s.seed = seed;
    EXPECT_TRUE(det->detect(test::render_marker_frame(camera, s), camera).empty()) << seed;
  }
}

TEST_P(BothDetectors, SameFrameSameDetections) {
  const CameraModel camera = marker_camera();
  MarkerScene s;
  s.dictionary = GetParam();
  s.id = 9;
  s.X_CM = test::marker_ahead(2.0, 40 * kDeg);
  s.noise_sigma = 3.0;
  s.blur_sigma_px = 0.8;
  const GrayImage frame = test::render_marker_frame(camera, s);
  const auto a = detector(GetParam())->detect(frame, camera);
  const auto b = detector(GetParam())->detect(frame, camera);
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(a[0].corners_px[k], b[0].corners_px[k]);
  EXPECT_TRUE(a[0].X_CM.isApprox(b[0].X_CM, 0.0));
}

// Two markers in one frame come out sorted by id, whatever order the library found.
TEST_P(BothDetectors, TwoMarkersSortedById) {
  const CameraModel camera = marker_camera();
  MarkerScene left, right;
  left.dictionary = right.dictionary = GetParam();
  left.id = 12;
  right.id = 4;
  left.X_CM = test::marker_ahead(1.5, 0.0, 0.0, {-0.5, 0.0});
  right.X_CM = test::marker_ahead(1.5, 0.0, 0.0, {0.5, 0.0});
  GrayImage frame = test::render_marker_frame(camera, left);
  const GrayImage other = test::render_marker_frame(camera, right);
  for (int y = 0; y < frame.height_px; ++y)
    for (int x = camera.width_px / 2; x < frame.width_px; ++x) frame.at(x, y) = other.at(x, y);
  const auto found = detector(GetParam())->detect(frame, camera);
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].id, 4);
  EXPECT_EQ(found[1].id, 12);
  EXPECT_GT(found[0].X_CM.translation().x(), 0.3);
}

INSTANTIATE_TEST_SUITE_P(Families, BothDetectors, ::testing::Values(apriltag36h11(), aruco4x4()),
                         [](const auto& info) {
                           return std::string(to_string(info.param.family));
                         });

// A marker of another dictionary is not reported as one of ours.
TEST(MarkerDetector, MarkerOfAnotherDictionaryIsNotReported) {
  const CameraModel camera = marker_camera();
  struct Case {
    MarkerDictionary shown, searched;
  };
  std::vector<Case> cases;
  cases.push_back({test::dictionary(MarkerFamily::kAprilTag, "tag25h9"), apriltag36h11()});
  cases.push_back({test::dictionary(MarkerFamily::kAprilTag, "tag16h5"), apriltag36h11()});
  cases.push_back({test::dictionary(MarkerFamily::kAruco, "DICT_5X5_50"), aruco4x4()});
  cases.push_back({test::dictionary(MarkerFamily::kAruco, "DICT_6X6_250"), aruco4x4()});
  cases.push_back({apriltag36h11(), aruco4x4()});
  for (const Case& c : cases) {
    const auto det = detector(c.searched);
    for (int id : {0, 1, 2, 3, 4, 5}) {
      MarkerScene s;
      s.dictionary = c.shown;
      s.id = id;
      s.X_CM = test::marker_ahead(1.0, 15 * kDeg);
      EXPECT_TRUE(det->detect(test::render_marker_frame(camera, s), camera).empty())
          << c.shown.name << " #" << id << " searched as " << c.searched.name;
    }
  }
}

TEST(MarkerDetector, EveryKnownDictionaryMakesADetector) {
  for (MarkerFamily f : {MarkerFamily::kAprilTag, MarkerFamily::kAruco})
    for (const auto& name : marker_dictionary_names(f))
      EXPECT_NO_THROW((void)detector(test::dictionary(f, name))) << name;
}

TEST(MarkerDetector, EachFamilysDetectorIsARegistryEntry) {
  EXPECT_EQ(marker_detectors().names(), (std::vector<std::string>{"apriltag", "aruco"}));
  EXPECT_EQ(marker_detectors().label("apriltag"), "AprilTag");
  MarkerDetectorOptions o;
  o.dictionary = test::dictionary(MarkerFamily::kAprilTag, "tag36h11");
  const auto april = marker_detectors().make("apriltag", o, "test");
  EXPECT_EQ(april->options().dictionary.family, MarkerFamily::kAprilTag);
  try {
    (void)marker_detectors().make("chilitags", o, "test", "dictionary.family");
    FAIL() << "an unregistered detector was built";
  } catch (const InputError& e) {
    EXPECT_EQ(e.expected(), "one of apriltag, aruco");
  }
}

TEST(MarkerDetector, BadOptionsAreInputErrors) {
  auto expect_field = [](MarkerDetectorOptions o, const std::string& field) {
    try {
      (void)make_marker_detector(o);
      ADD_FAILURE() << "accepted " << field;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), field);
    }
  };
  MarkerDetectorOptions o;
  for (double bad : {0.0, -0.2, std::nan(""), std::numeric_limits<double>::infinity(), 1e9}) {
    o.marker_size_m = bad;
    expect_field(o, "marker_size_m");
  }
  o = {};
  o.dictionary = test::dictionary(MarkerFamily::kAprilTag, "DICT_4X4_50");
  expect_field(o, "dictionary");
  o = {};
  o.dictionary = test::dictionary(MarkerFamily::kAruco, "tag36h11");
  expect_field(o, "dictionary");
  o = {};
  o.max_hamming = 9;
  expect_field(o, "max_hamming");
  o = {};
  o.quad_decimate = 0.0;
  expect_field(o, "quad_decimate");
  o = {};
  o.aruco_candidate_blur_px = -1.0;
  expect_field(o, "aruco_candidate_blur_px");
  o = {};
  o.aruco_threshold_constant = std::nan("");
  expect_field(o, "aruco_threshold_constant");
}

TEST(MarkerDetector, FrameOfAnotherSizeThanTheCameraIsAnInputError) {
  const auto det = detector(aruco4x4());
  EXPECT_THROW((void)det->detect(GrayImage(640, 480), marker_camera()), InputError);
  EXPECT_THROW((void)det->detect(GrayImage(), marker_camera()), InputError);
}

// The issue's target as a property on a small seeded sample: every marker that spans
// at least 20 px and is at most 60 deg off-axis is found, with blur, noise and an
// exposure change. (The bench's --evaluate runs the large version on rendered frames.)
TEST_P(BothDetectors, DetectsEveryMarkerOfAtLeast20PxAndAtMost60DegOffAxis) {
  const CameraModel camera = CameraModel::from_fov("small", 640, 360, 1.3613568165555772);
  // AprilTag at its full-resolution quad search: the default quad_decimate = 2 (3 ms a
  // frame instead of 7) misses some markers of 20-30 px (docs/perception.md, Markers).
  MarkerDetectorOptions o;
  o.dictionary = GetParam();
  o.marker_size_m = 0.2;
  o.quad_decimate = 1.0;
  const auto det = make_marker_detector(o);
  Rng rng(derive_seed(11, {static_cast<std::uint64_t>(GetParam().family)}));
  const RandomViews views{.distance_m = {0.5, 6.0},
                          .blur_px = {0.0, 1.0},
                          .noise = {0.0, 4.0},
                          .exposure_gain = {0.7, 1.2}};
  int tried = 0, found = 0;
  while (tried < 60) {
    const MarkerScene s = random_scene(rng, GetParam(), views);
    // Spans >= 20 px: the shortest side of the projected black square.
    const auto c = test::true_corners_px(camera, s);
    bool inside = true;
    for (int k = 0; k < 4; ++k) inside = inside && camera.in_image(c[k], 4.0);
    if (shortest_side_px(c) < 20.0 || !inside) continue;
    ++tried;
    const auto out = det->detect(test::render_marker_frame(camera, s), camera);
    if (out.size() == 1 && out[0].id == s.id) ++found;
  }
  EXPECT_EQ(found, tried);
}

// A marker of 8 or more cells across (6x6, 7x7, AprilTag 36h11 in OpenCV) with its
// one-cell white margin in front of something darker: the margin's outline is a second
// square one cell outside the black one. OpenCV merges candidates closer than
// minMarkerDistanceRate of the perimeter and keeps the outer one, so with its 0.05 the
// marker was lost (1 of 16 large 6x6 markers, 5 of 16 7x7 ones on the bench's frames).
TEST(MarkerDetector, ArucoFindsMarkersOfManyCellsInsideTheirWhiteMargin) {
  const CameraModel camera = marker_camera();
  for (const char* name : {"DICT_6X6_250", "DICT_7X7_50", "DICT_APRILTAG_36h11"}) {
    const MarkerDictionary dict = test::dictionary(MarkerFamily::kAruco, name);
    const auto det = detector(dict);
    int frames = 0;
    for (double d : {0.7, 1.2, 2.0})
      for (double yaw_deg : {0.0, 35.0}) {
        MarkerScene s;
        s.dictionary = dict;
        s.id = 11;
        s.X_CM = test::marker_ahead(d, yaw_deg * kDeg, 0.3, {0.05 * d, 0.05 * d});
        s.seed = static_cast<std::uint64_t>(++frames);
        s.blur_sigma_px = 0.7;
        s.noise_sigma = 2.0;
        const auto found = det->detect(test::render_marker_frame(camera, s), camera);
        SCOPED_TRACE(::testing::Message() << name << " d " << d << " yaw " << yaw_deg);
        ASSERT_EQ(found.size(), 1u);
        EXPECT_EQ(found[0].id, 11);
        const auto truth = test::true_corners_px(camera, s);
        for (int k = 0; k < 4; ++k) EXPECT_LT((found[0].corners_px[k] - truth[k]).norm(), 1.0) << k;
      }
  }
}

// The hard end of the target (docs/results/markers.md): markers of 20-26 px
// blurred by 1.1-1.5 px at any exposure. Of these 40 frames 34 are found; OpenCV's own
// threshold settings with the margin read against one threshold between the darkest
// and the brightest cell (the code before) found 27. (Blur keeps a white cell brighter
// than its black neighbours, not above that threshold.)
TEST(MarkerDetector, ArucoFindsSmallMarkersUnderHeavyBlur) {
  const CameraModel camera = marker_camera();
  const auto det = detector(aruco4x4());
  Rng rng(7);
  const RandomViews views{.distance_m = {6.0, 8.5},
                          .max_off_axis_deg = 40.0,
                          .blur_px = {1.1, 1.5},
                          .noise = {1.0, 5.0},
                          .exposure_gain = {0.6, 1.4}};
  int tried = 0, found = 0;
  while (tried < 40) {
    const MarkerScene s = random_scene(rng, aruco4x4(), views);
    const double shortest = shortest_side_px(test::true_corners_px(camera, s));
    if (shortest < 20.0 || shortest > 26.0) continue;
    ++tried;
    const auto out = det->detect(test::render_marker_frame(camera, s), camera);
    for (const auto& m : out) EXPECT_EQ(m.id, s.id) << "a marker read as another";
    if (out.size() == 1 && out[0].id == s.id) ++found;
  }
  EXPECT_GE(found, 31) << "of " << tried;
}

}  // namespace
}  // namespace ferret
