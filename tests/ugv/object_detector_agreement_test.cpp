// The image detector (ColourObjectDetector on frames the simulator renders) against
// the fast geometric detector the experiments use (HiddenSpaceSim, noise off), over
// distances 0.2 m ... beyond D_cam and bearings across the fov, on the miniUGV's object
// camera (640 x 480, 90 deg, D_cam = 4 m, from its URDF) with blur, noise and exposure
// changes (docs/perception.md, "Object detection").
//
// The stated tolerances follow from the distance estimate: d comes from the blob's
// height h_px = f H / d (f = 320 px, H = 0.05 m), and each of the blob's two edges may
// be off by one pixel (blurred mixed pixels, quantisation), so |d_est - d| / d <=
// 2 px / h_px, plus 0.011 m / cos(bearing) for the object's yaw (the near face lies
// 0.040 ... 0.057 m before the centre of the 8 cm box, taken as 0.051), and since conf =
// clip(eta / d) has |d conf / d d| <= eta / d^2, |conf - conf_geo| <= 2 eta / (f H) =
// 0.125 (the clip only shrinks it).
// Detection agrees (same yes/no) except in two bands:
//  - D_cam < d with depth d cos(bearing) <= f H / 2 px = 8 m: the image detector still
//    sees a blob of >= 2 px (grown to 3 by blur, what the opening keeps) where the
//    geometric one stops at D_cam;
//  - the fov edge, | |bearing| - fov / 2 | <= atan(r / d) + 1 px: part of the object is
//    in the image while its centre is out (r = 0.0566 m, the footprint's half diagonal).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ferret/core/random.hpp"
#include "ferret/ugv/object_detector.hpp"
#include "ugv/object_scene.hpp"

namespace ferret::ugv {
namespace {

const RobotDescription& miniugv() {
  static const RobotDescription r =
      load_robot_description(std::string(FERRET_SOURCE_DIR) + "/urdf/models/miniugv.urdf");
  return r;
}

struct Agreement {
  int both = 0, neither = 0, band = 0;
  double max_conf_gap = 0.0;
};

class ObjectDetectorAgreement : public ::testing::Test {
 protected:
  const ObjectSearchParams search;
  const test::ObjectScene scene{miniugv(), search};
  const ColourObjectDetector detector{scene.detector_options(search)};
  const double f = scene.camera().fx_px;
  const double H = 0.05;
  const double half_fov = scene.camera().horizontal_fov_rad() / 2;
  const double D_cam = scene.range_m();

  /// Renders the view with seeded exposure, blur and noise; compares both detectors.
  void check(const test::ObjectView& v, Rng& rng, Agreement& a) {
    CameraFrameOptions fo;
    fo.exposure_gain = rng.uniform(0.7, 1.3);
    const auto dets = detector.detect(scene.frame(v, fo, rng.next_u64()), scene.camera());
    const auto geo = scene.geometric(v);
    const double d = v.distance_m;
    const double edge_band = std::atan(0.0566 / d) + 1.0 / f;
    // The blob's height is f H / z with z = d cos(bearing) the depth: off the axis
    // the object looks taller.
    const bool in_band = (d > D_cam && d * std::cos(v.bearing_rad) <= f * H / 2.0) ||
                         std::abs(std::abs(v.bearing_rad) - half_fov) <= edge_band;
    const std::string where = "d " + std::to_string(d) + " m, bearing " +
                              std::to_string(rad_to_deg(v.bearing_rad)) + " deg, heading " +
                              std::to_string(v.heading_rad);
    if (in_band) {
      ++a.band;
      return;
    }
    ASSERT_EQ(!dets.empty(), geo.has_value()) << where;
    if (!geo) {
      ++a.neither;
      return;
    }
    ++a.both;
    ASSERT_EQ(dets.size(), 1u) << where;  // one object, one blob: no false detections
    const ObjectDetection& o = dets.front();
    // Bearing: the blob's centroid against the true bearing of the centre; the
    // silhouette of a yawed box is off-centre by at most its half diagonal's angle.
    EXPECT_NEAR(o.bearing_rad, v.bearing_rad, std::atan(0.0566 / d) * 0.5 + 2.0 / f) << where;
    const double truth = scene.true_range_m(v);
    const double h_px = f * H / d;
    EXPECT_NEAR(o.distance_m, truth, truth * 2.0 / h_px + 0.011 / std::cos(v.bearing_rad)) << where;
    const double conf_geo = clip_confidence(geo->confidence, search.conf_floor, search.conf_cap);
    const double gap = std::abs(o.confidence - conf_geo);
    EXPECT_LE(gap, 2.0 * search.eta_m / (f * H)) << where;
    a.max_conf_gap = std::max(a.max_conf_gap, gap);
  }
};

TEST_F(ObjectDetectorAgreement, AcrossDistancesUpToDcamOnTheAxisAndOffIt) {
  Rng rng(11);
  Agreement a;
  for (int k = 1; k <= 20; ++k)
    for (const double b_deg : {0.0, 15.0, -25.0})
      check({0.2 * k, deg_to_rad(b_deg), rng.uniform(-std::numbers::pi, std::numbers::pi)}, rng, a);
  // All inside D_cam and the fov, clear of its edge band (16 deg at 0.2 m): both
  // detect every one.
  EXPECT_EQ(a.both, 60);
  EXPECT_EQ(a.band, 0);
  std::printf("max |conf - geometric| %.3f (tolerance %.3f)\n", a.max_conf_gap,
              2.0 * search.eta_m / (f * H));
}

TEST_F(ObjectDetectorAgreement, RandomViewsAcrossTheFovAndBeyondDcam) {
  // Distances to 8.8 m (past both bands), bearings to 30 deg outside the fov.
  Rng rng(12);
  Agreement a;
  for (int k = 0; k < 120; ++k) {
    const test::ObjectView v{rng.uniform(0.2, 8.8),
                             rng.uniform(-half_fov - deg_to_rad(30), half_fov + deg_to_rad(30)),
                             rng.uniform(-std::numbers::pi, std::numbers::pi)};
    check(v, rng, a);
  }
  // Every kind of case happened.
  EXPECT_GE(a.both, 25);
  EXPECT_GE(a.neither, 5);
  EXPECT_GE(a.band, 5);
}

TEST_F(ObjectDetectorAgreement, TheObjectUnpaintedIsNotDetected) {
  // The same views with the object grey (draw_objects = false): the geometry is there,
  // its colour is not, and nothing else in the scene is orange.
  Rng rng(13);
  for (const double d : {0.3, 1.0, 2.5}) {
    CameraFrameOptions fo;
    fo.draw_objects = false;
    const test::ObjectView v{d, 0.1, rng.uniform(-3.0, 3.0)};
    EXPECT_TRUE(detector.detect(scene.frame(v, fo, rng.next_u64()), scene.camera()).empty()) << d;
  }
}

TEST_F(ObjectDetectorAgreement, SameSeedSameFrameSameDetection) {
  const test::ObjectView v{1.3, 0.2, 0.7};
  const auto a = detector.detect(scene.frame(v, {}, 99), scene.camera());
  const auto b = detector.detect(scene.frame(v, {}, 99), scene.camera());
  ASSERT_EQ(a.size(), 1u);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(a[0].distance_m, b[0].distance_m);
  EXPECT_EQ(a[0].confidence, b[0].confidence);
  EXPECT_EQ(a[0].centroid_px, b[0].centroid_px);
}

}  // namespace
}  // namespace ferret::ugv
