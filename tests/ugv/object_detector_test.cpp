// The colour-patch object detector on frames drawn here: rectangles of known pixel
// size on a textured, noisy background; expected values computed by hand from the
// camera's fx, cx (docs/perception.md, "Object detection").

#include "ferret/ugv/object_detector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "ferret/core/error.hpp"
#include "ugv/object_frames.hpp"

namespace ferret::ugv {
namespace {

using test::add_noise;
using test::fill_rect;
using test::kOrange;
using test::textured_background;

// 640 x 480, 90 deg: fx = fy = 320 px, cx = 319.5, cy = 239.5 (pixel centres at
// integers, so a rectangle of columns 312..327 is centred on cx).
CameraModel camera() { return CameraModel::from_fov("test", 640, 480, std::numbers::pi / 2); }

// The rectangles drawn here are flat patches: no depth behind the face they show.
ColourObjectDetector patch_detector() {
  ColourObjectDetector::Options o;
  o.object_depth_m = 0.0;
  return ColourObjectDetector(o);
}

RgbImage scene(std::uint64_t seed) { return textured_background(640, 480, seed); }

TEST(ObjectDetector, DistanceFromABlobOfKnownSize) {
  // The canister's 5 cm height over 10 px at fy = 320: z = 0.05 * 320 / 10 = 1.6 m, on
  // the optical axis, so d = z; conf = eta / d = 1 / 1.6 = 0.625 (inside [0.55, 0.99]).
  RgbImage img = scene(1);
  fill_rect(img, 312, 235, 16, 10, kOrange);
  add_noise(img, 3.0, 2);
  const auto dets = patch_detector().detect(img, camera());
  ASSERT_EQ(dets.size(), 1u);
  EXPECT_NEAR(dets[0].distance_m, 1.6, 1e-9);
  EXPECT_NEAR(dets[0].bearing_rad, 0.0, 1e-12);
  EXPECT_EQ(dets[0].size_axis, SizeAxis::kHeight);
  EXPECT_DOUBLE_EQ(dets[0].apparent_size_px, 10.0);
  EXPECT_NEAR(dets[0].confidence, 0.625, 1e-9);
  EXPECT_NEAR(dets[0].centroid_px.x(), 319.5, 1e-9);
  EXPECT_NEAR(dets[0].centroid_px.y(), 239.5, 1e-9);
  EXPECT_EQ(dets[0].box.x_px, 312);
  EXPECT_EQ(dets[0].box.width_px, 16);
  EXPECT_FALSE(dets[0].truncated);
  EXPECT_DOUBLE_EQ(dets[0].visibility, 1.0);
}

TEST(ObjectDetector, ABoxCentreLiesBehindItsNearFace) {
  // The default object is the 8 x 8 x 5 cm canister: its centre lies 2 * 0.08 / pi =
  // 0.050930 m behind the face whose extent the blob shows (yaw average).
  RgbImage img = scene(1);
  fill_rect(img, 312, 235, 16, 10, kOrange);
  const auto dets = ColourObjectDetector().detect(img, camera());
  ASSERT_EQ(dets.size(), 1u);
  EXPECT_NEAR(dets[0].distance_m, 1.6 + 0.050930, 1e-6);
  EXPECT_NEAR(dets[0].confidence, 1.0 / (1.6 + 0.050930), 1e-6);
}

TEST(ObjectDetector, BearingOfABlobAtAKnownColumn) {
  // Columns 400..415: centroid u = 407.5, x = (407.5 - 319.5) / 320 = 0.275 right of
  // the axis, bearing = atan2(-0.275, 1) = -0.268366 rad (right is negative). Off axis
  // the range is z * |ray|: 1.6 * sqrt(1 + 0.275^2) = 1.659397 m.
  RgbImage img = scene(3);
  fill_rect(img, 400, 235, 16, 10, kOrange);
  add_noise(img, 3.0, 4);
  const auto dets = patch_detector().detect(img, camera());
  ASSERT_EQ(dets.size(), 1u);
  EXPECT_NEAR(dets[0].bearing_rad, -0.268366, 1e-6);
  EXPECT_NEAR(dets[0].distance_m, 1.659397, 1e-6);
  // And on the left: columns 100..115, u = 107.5, x = -0.6625, bearing atan(0.6625) = +0.585112
  // rad.
  RgbImage left = scene(5);
  fill_rect(left, 100, 235, 16, 10, kOrange);
  const auto l = patch_detector().detect(left, camera());
  ASSERT_EQ(l.size(), 1u);
  EXPECT_NEAR(l[0].bearing_rad, 0.585112, 1e-6);
}

TEST(ObjectDetector, BearingAndDistanceGoThroughTheLensDistortion) {
  // A barrel lens (k1 = -0.2). A 5 x 5 cm patch at z = 1 m, x = 0.3 m: its edges are
  // drawn where the lens puts x = 0.3 +- 0.025, y = +-0.025. Undistorted, the blob's
  // centre gives bearing atan(-0.3) = -0.291457 rad; read without undistortion it would
  // give atan(-0.3 * (1 - 0.2 * 0.0906)) = -0.286521 rad, 4.9e-3 rad off. Edges are
  // rounded to whole pixels (half a pixel: 1.6e-3 in x), hence the 2.5e-3 tolerance.
  CameraModel cam = camera();
  cam.distortion = DistortionModel::kPlumbBob;
  cam.distortion_coefficients = {-0.2, 0.0, 0.0, 0.0, 0.0};
  const auto pixel = [&](double x, double y) {
    const Eigen::Vector2d d = cam.distort({x, y});
    return Eigen::Vector2d(cam.cx_px + cam.fx_px * d.x(), cam.cy_px + cam.fy_px * d.y());
  };
  const Eigen::Vector2d lo = pixel(0.275, -0.025), hi = pixel(0.325, 0.025);
  const int u0 = static_cast<int>(std::lround(lo.x())), u1 = static_cast<int>(std::lround(hi.x()));
  const int v0 = static_cast<int>(std::lround(lo.y())), v1 = static_cast<int>(std::lround(hi.y()));
  RgbImage img = scene(7);
  fill_rect(img, u0, v0, u1 - u0, v1 - v0, kOrange);
  ColourObjectDetector::Options o;
  o.object_depth_m = 0.0;
  o.object_width_m = 0.05;
  o.object_height_m = 0.05;
  const auto dets = ColourObjectDetector(o).detect(img, cam);
  ASSERT_EQ(dets.size(), 1u);
  EXPECT_NEAR(dets[0].bearing_rad, -0.291457, 2.5e-3);
  // Range sqrt(1 + 0.09) = 1.044031 m; one pixel of the 15-px height is 7 %.
  EXPECT_NEAR(dets[0].distance_m, 1.044031, 0.07 * 1.044031);
}

TEST(ObjectDetector, NoDetectionInAFrameWithoutTheColour) {
  for (std::uint64_t seed = 10; seed < 20; ++seed) {
    RgbImage img = scene(seed);
    fill_rect(img, 200, 200, 40, 25, {30, 200, 40});    // green
    fill_rect(img, 400, 100, 40, 25, {20, 60, 220});    // blue
    fill_rect(img, 100, 300, 40, 25, {200, 200, 200});  // white
    add_noise(img, 6.0, seed + 100);
    EXPECT_TRUE(patch_detector().detect(img, camera()).empty()) << "seed " << seed;
  }
}

TEST(ObjectDetector, RedAndYellowDistractorsAreNotDetected) {
  // Orange's hue is 26 deg; red (~3 deg) and yellow (~55 deg) are more than the 12 deg
  // tolerance away. Same sizes as the object, same noise: only the orange one is found.
  RgbImage img = scene(21);
  fill_rect(img, 100, 235, 16, 10, {230, 20, 10});  // red
  fill_rect(img, 500, 235, 16, 10, {240, 220, 0});  // yellow
  fill_rect(img, 300, 100, 32, 20, {255, 40, 40});  // bright red, twice the size
  fill_rect(img, 312, 300, 16, 10, kOrange);
  add_noise(img, 4.0, 22);
  const auto dets = patch_detector().detect(img, camera());
  ASSERT_EQ(dets.size(), 1u);
  EXPECT_EQ(dets[0].box.x_px, 312);
  EXPECT_EQ(dets[0].box.y_px, 300);
}

TEST(ObjectDetector, AnObjectCutByTheImageBorderIsPartlyVisible) {
  // At z = 0.5 m the object is 0.08 * 320 / 0.5 = 51.2 px wide and 32 px tall. Only 20
  // columns show at the left border: the height still gives z = 0.5 m, and the
  // visibility is 20 / 51.2 = 0.390625, so conf = clip(0.390625 * eta / d).
  RgbImage img = scene(31);
  fill_rect(img, 0, 224, 20, 32, kOrange);
  add_noise(img, 3.0, 32);
  const ColourObjectDetector det = patch_detector();
  const auto dets = det.detect(img, camera());
  ASSERT_EQ(dets.size(), 1u);
  const ObjectDetection& d = dets[0];
  EXPECT_TRUE(d.truncated);
  EXPECT_EQ(d.size_axis, SizeAxis::kHeight);
  // Centroid u = 9.5: x = -310 / 320, range = 0.5 * sqrt(1 + 0.96875^2).
  const double x = (9.5 - 319.5) / 320.0;
  EXPECT_NEAR(d.distance_m, 0.5 * std::sqrt(1 + x * x), 1e-9);
  EXPECT_NEAR(d.visibility, 20.0 / 51.2, 1e-9);
  EXPECT_NEAR(d.confidence, std::clamp(20.0 / 51.2 / d.distance_m, 0.55, 0.99), 1e-9);
  // The same object whole would be capped at 0.99: the cut one is less sure.
  EXPECT_LT(d.confidence, 0.99);

  // Cut at the bottom: the height is a lower bound, the width (51 px, whole) gives z =
  // 0.08 * 320 / 51 = 0.50196 m.
  RgbImage bottom = scene(33);
  fill_rect(bottom, 300, 470, 51, 10, kOrange);
  const auto b = det.detect(bottom, camera());
  ASSERT_EQ(b.size(), 1u);
  EXPECT_TRUE(b[0].truncated);
  EXPECT_EQ(b[0].size_axis, SizeAxis::kWidth);
  const Eigen::Vector3d ray = camera().ray(b[0].centroid_px);
  EXPECT_NEAR(b[0].distance_m, 0.08 * 320.0 / 51.0 * ray.norm(), 1e-9);
  // 10 of the 32 px the height would span at that depth.
  EXPECT_NEAR(b[0].visibility, 10.0 / (320.0 * 0.05 / (0.08 * 320.0 / 51.0)), 1e-9);
}

TEST(ObjectDetector, ConfidenceFallsWithDistanceAsEtaOverD) {
  // Heights 40, 12, 10, 5 px: z = 0.4, 1.333, 1.6, 3.2 m; conf = clip(eta / d, 0.55,
  // 0.99) with d = z |ray| (the centroids are within half a pixel of the axis), scaled
  // by 5 / 8 for the 5 px blob (below full_visibility_px) -> the floor anyway.
  const double visibility[] = {1.0, 1.0, 1.0, 5.0 / 8.0};
  const int heights[] = {40, 12, 10, 5};
  for (int k = 0; k < 4; ++k) {
    RgbImage img = scene(40 + static_cast<std::uint64_t>(k));
    const int h = heights[k], w = static_cast<int>(std::lround(h * 1.6));
    fill_rect(img, 320 - w / 2, 240 - h / 2, w, h, kOrange);
    const auto dets = patch_detector().detect(img, camera());
    ASSERT_EQ(dets.size(), 1u) << h;
    const double z = 0.05 * 320.0 / h;
    const double d = z * camera().ray(dets[0].centroid_px).norm();
    EXPECT_NEAR(dets[0].distance_m, d, 1e-9);
    EXPECT_NEAR(dets[0].confidence, std::clamp(visibility[k] / d, 0.55, 0.99), 1e-9) << h;
  }
}

TEST(ObjectDetector, MissionConstantsSetTheConfidence) {
  // eta = 2 m, floor 0.6, cap 0.9: at 1.6 m, 2 / 1.6 = 1.25 -> the cap 0.9; at 3.2 m,
  // 5 px tall: 5/8 * 2/3.2 = 0.39 -> the floor 0.6.
  ColourObjectDetector::Options o;
  o.object_depth_m = 0.0;
  o.search.eta_m = 2.0;
  o.search.conf_floor = 0.6;
  o.search.conf_cap = 0.9;
  const ColourObjectDetector det(o);
  RgbImage a = scene(50);
  fill_rect(a, 312, 235, 16, 10, kOrange);
  ASSERT_EQ(det.detect(a, camera()).size(), 1u);
  EXPECT_DOUBLE_EQ(det.detect(a, camera())[0].confidence, 0.9);
  RgbImage b = scene(51);
  fill_rect(b, 316, 237, 8, 5, kOrange);
  ASSERT_EQ(det.detect(b, camera()).size(), 1u);
  EXPECT_DOUBLE_EQ(det.detect(b, camera())[0].confidence, 0.6);
}

TEST(ObjectDetector, SpeckleNoiseAndThinLinesAreNotObjects) {
  // Isolated orange pixels and a 1-px orange line: the opening removes them.
  RgbImage img = scene(60);
  Rng rng(61);
  for (int k = 0; k < 300; ++k)
    fill_rect(img, static_cast<int>(rng.uniform_int(0, 639)),
              static_cast<int>(rng.uniform_int(0, 479)), 1, 1, kOrange);
  fill_rect(img, 50, 400, 300, 1, kOrange);
  fill_rect(img, 600, 50, 2, 200, kOrange);
  EXPECT_TRUE(patch_detector().detect(img, camera()).empty());
}

TEST(ObjectDetector, SameFrameSameDetections) {
  RgbImage img = scene(70);
  fill_rect(img, 100, 100, 24, 15, kOrange);
  fill_rect(img, 400, 300, 16, 10, kOrange);
  add_noise(img, 5.0, 71);
  RgbImage again = scene(70);
  fill_rect(again, 100, 100, 24, 15, kOrange);
  fill_rect(again, 400, 300, 16, 10, kOrange);
  add_noise(again, 5.0, 71);
  ASSERT_EQ(img.data, again.data);
  const auto a = patch_detector().detect(img, camera());
  const auto b = patch_detector().detect(again, camera());
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(b.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(a[k].distance_m, b[k].distance_m);
    EXPECT_EQ(a[k].bearing_rad, b[k].bearing_rad);
    EXPECT_EQ(a[k].confidence, b[k].confidence);
    EXPECT_EQ(a[k].centroid_px, b[k].centroid_px);
  }
  // Best first: the larger (nearer) blob has the higher confidence.
  EXPECT_EQ(a[0].box.x_px, 100);
}

TEST(ObjectDetector, AnImageOfTheWrongSizeIsBadInput) {
  const RgbImage img(320, 240);
  try {
    (void)patch_detector().detect(img, camera());
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "image size");
    EXPECT_NE(std::string(e.what()).find("320 x 240"), std::string::npos) << e.what();
  }
}

TEST(ObjectDetector, OptionsOutOfRangeAreRefusedByField) {
  const auto field_of = [](ColourObjectDetector::Options o) {
    try {
      o.check("mission.yaml");
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), "mission.yaml");
      return e.field();
    }
    return std::string("(accepted)");
  };
  ColourObjectDetector::Options o;
  o.object_depth_m = 0.0;
  EXPECT_EQ(field_of(o), "(accepted)");
  o.colour_rgb = {128, 128, 128};
  EXPECT_EQ(field_of(o), "object_detector.colour_rgb");
  o = {};
  o.object_height_m = std::nan("");
  EXPECT_EQ(field_of(o), "object_detector.object_height_m");
  o = {};
  o.object_width_m = 1e9;
  EXPECT_EQ(field_of(o), "object_detector.object_width_m");
  o = {};
  o.open_kernel_px = 4;
  EXPECT_EQ(field_of(o), "object_detector.open_kernel_px");
  o = {};
  o.hue_tolerance_deg = 0;
  EXPECT_EQ(field_of(o), "object_detector.hue_tolerance_deg");
  o = {};
  o.search.conf_floor = 0.95;
  o.search.conf_cap = 0.9;
  EXPECT_EQ(field_of(o), "object_detector.search.conf_floor");
}

TEST(ObjectDetector, MapDetectionKeepsBearingDistanceConfidence) {
  ObjectDetection d;
  d.bearing_rad = 0.3;
  d.distance_m = 2.0;
  d.confidence = 0.6;
  const ::ferret::ObjectDetection m = to_map_detection(d);
  EXPECT_EQ(m.bearing_rad, 0.3);
  EXPECT_EQ(m.distance_m, 2.0);
  EXPECT_EQ(m.confidence, 0.6);
}

TEST(ObjectDetector, OverlayDrawsOnlyAroundTheDetection) {
  RgbImage img = scene(80);
  fill_rect(img, 312, 235, 16, 10, kOrange);
  const auto dets = patch_detector().detect(img, camera());
  ASSERT_EQ(dets.size(), 1u);
  const RgbImage over = draw_object_overlay(img, dets);
  ASSERT_EQ(over.width_px, 640);
  // The box's outline (one pixel outside the blob) is green; far corners untouched.
  EXPECT_EQ(over.at(311, 240, 0), 0);
  EXPECT_EQ(over.at(311, 240, 1), 255);
  EXPECT_EQ(over.at(600, 450, 0), img.at(600, 450, 0));
  EXPECT_EQ(draw_object_overlay(img, {}).data, img.data);
}

}  // namespace
}  // namespace ferret::ugv
