#include "ferret/sim/sensor_sim.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "ferret/core/error.hpp"
#include "ferret/perception/colour.hpp"
#include "ferret/perception/object_appearance.hpp"

namespace ferret {
namespace {

constexpr double kPi = std::numbers::pi;

// The optical frame (x right, y down, z forward) of a camera at `eye` looking at
// `target`, with `up` (world) towards the top of the image.
Pose3 look_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
              const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ()) {
  const Eigen::Vector3d z = (target - eye).normalized();
  const Eigen::Vector3d x = (-up).cross(z).normalized();
  Pose3 X = Pose3::Identity();
  X.linear().col(0) = x;
  X.linear().col(1) = z.cross(x);
  X.linear().col(2) = z;
  X.translation() = eye;
  return X;
}

// Straight down from (x, y, z), the image's top towards +y.
Pose3 looking_down(double x, double y, double z) {
  return look_at({x, y, z}, {x, y, z - 1}, Eigen::Vector3d::UnitY());
}

WorldSpec world(const std::string& body) {
  return parse_world(
      "name: t\nresolution_m: 0.05\nbounds_m: {min: [-20, -20, -1], max: [20, 20, "
      "10]}\n" +
          body,
      "test world");
}

DepthFrameOptions exact_depth() {
  DepthFrameOptions o;
  o.noise_coefficient_per_m = 0.0;
  o.dropout_fraction = 0.0;
  return o;
}

CameraFrameOptions clean_camera() {
  CameraFrameOptions o;
  o.noise_sigma = 0.0;
  o.blur_sigma_px = 0.0;
  return o;
}

const CameraModel kCam = CameraModel::from_fov("cam", 640, 480, deg_to_rad(60.0));

// A hidden space (5 x 4 m inside, 0.5 m high, 0.1 m walls, centred at the origin, its
// opening in the +x wall) with its marker on the outer face of the +x wall: centre at
// x = 2.6 m + 1 mm, facing +x.
std::string hidden_space(const std::string& marker) {
  return "hidden_spaces:\n  - name: hs\n    center_m: [0, 0]\n    interior_size_m: [5, 4, "
         "0.5]\n    wall_thickness_m: 0.1\n    opening: {wall: +x, width_m: 0.15, height_m: "
         "0.07}\n    marker: " +
         marker + "\n";
}

TEST(SensorSim, FlatGroundSeenStraightDownReadsItsHeightInEveryPixel) {
  const SensorSimulator sim(world("ground: {height_m: 0.0}\n"));
  const double h = 2.0;
  // Exact: z along the optical axis is h everywhere (the ray length would grow to
  // h / cos(36 deg) in the corners).
  const DepthImageMm exact = sim.render_depth(kCam, looking_down(1, 2, h), exact_depth(), 1);
  ASSERT_EQ(exact.width_px, 640);
  for (const auto v : exact.data) ASSERT_EQ(v, 2000);
  // With the D415 noise (sigma_z = 0.01 * z^2 = 4 cm at 2 m) and 1 % dropouts.
  const DepthFrameOptions d415;
  const DepthImageMm noisy = sim.render_depth(kCam, looking_down(1, 2, h), d415, 1);
  const double sigma_mm = 1000.0 * d415.noise_coefficient_per_m * h * h;
  double sum = 0, sum2 = 0;
  int n = 0, zeros = 0;
  for (const auto v : noisy.data) {
    if (v == 0) {
      ++zeros;
      continue;
    }
    ASSERT_LT(std::abs(v - 2000.0), 5 * sigma_mm);
    sum += v;
    sum2 += (v - 2000.0) * (v - 2000.0);
    ++n;
  }
  const double N = static_cast<double>(noisy.data.size());
  EXPECT_NEAR(zeros / N, d415.dropout_fraction, 0.002);
  EXPECT_NEAR(sum / n, 2000.0, 1.0);  // unbiased: under 0.03 sigma
  EXPECT_NEAR(std::sqrt(sum2 / n), sigma_mm, 0.02 * sigma_mm);
}

TEST(SensorSim, DepthThroughADistortingLensIsStillZAlongTheAxis) {
  // Barrel distortion bends each pixel's ray, not the plane: every pixel reads h.
  CameraModel lens = kCam;
  lens.distortion = DistortionModel::kPlumbBob;
  lens.distortion_coefficients = {-0.28, 0.07, 0.0005, -0.0004, 0.0};
  const SensorSimulator sim(world("ground: {height_m: 0.5}\n"));
  const DepthImageMm d = sim.render_depth(lens, looking_down(0, 0, 2.0), exact_depth(), 1);
  for (const auto v : d.data) ASSERT_EQ(v, 1500);
}

TEST(SensorSim, ACylinderSeenFromAboveAndFromTheSide) {
  // A post of radius 0.3 m and height 1.2 m at (1, 0) on flat ground.
  const SensorSimulator sim(
      world("cylinders:\n  - {name: p, center_m: [1, 0], radius_m: 0.3, height_m: 1.2}\n"));
  const DepthImageMm top = sim.render_depth(kCam, looking_down(1, 0, 3.0), exact_depth(), 1);
  EXPECT_EQ(top.at(320, 240), 1800);  // its cap
  EXPECT_EQ(top.at(10, 10), 3000);    // the ground
  // From the side, 2 m from its axis at half its height: the surface is 1.7 m away on
  // the axis; the ray at 0.25 m off the axis meets it at depth 2 - sqrt(0.3^2 - 0.25^2).
  const Pose3 X_WC = look_at({-1, 0, 0.6}, {1, 0, 0.6});
  const DepthImageMm side = sim.render_depth(kCam, X_WC, exact_depth(), 1);
  EXPECT_NEAR(side.at(320, 240), 1700, 1);
  // A pixel about 0.25 m right of the axis: its ray (r.x, ~0, 1) in C is, in the world,
  // (t - 1, -r.x t) in plan; it meets (x - 1)^2 + y^2 = 0.3^2 where
  // (1 + r.x^2) t^2 - 4 t + 3.91 = 0.
  const int u = static_cast<int>(std::lround(kCam.cx_px + kCam.fx_px * 0.25 / 1.75));
  const double rx = kCam.ray({static_cast<double>(u), 240.0}).x();
  const double a = 1 + rx * rx;
  const double z = (4 - std::sqrt(16 - 4 * a * 3.91)) / (2 * a);
  EXPECT_GT(z, 1.75);
  EXPECT_NEAR(side.at(u, 240), 1000 * z, 1);
  // The normal a ray meets: the cylinder's side faces the camera.
  Eigen::Vector3d n;
  const auto t = sim.cast_ray({-1, 0, 0.6}, Eigen::Vector3d::UnitX(), 10.0, &n);
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, 1.7, 1e-12);
  EXPECT_LT((n - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-12);
  EXPECT_FALSE(sim.cast_ray({-1, 0, 0.6}, Eigen::Vector3d::UnitX(), 1.6));
}

TEST(SensorSim, CamerasArePickedByRole) {
  const RobotDescription uav = load_robot("m100"), ugv = load_robot("miniugv");
  EXPECT_EQ(camera_for(uav, false).name, uav.marker_camera().name);
  EXPECT_EQ(camera_for(uav, true).name, uav.depth_camera().name);
  EXPECT_EQ(camera_for(ugv, false).name, ugv.object_camera().name);
  EXPECT_EQ(camera_for(uav, false, "depth_camera").name, uav.depth_camera().name);
  EXPECT_THROW((void)camera_for(uav, true, "marker_camera"), InputError);  // not a depth camera
  EXPECT_THROW((void)camera_for(uav, false, "front"), InputError);
  EXPECT_THROW((void)camera_for(ugv, true), InputError);  // the miniUGV has no depth camera
  // The optical frame looks along the sensor's x: the M100's depth camera looks down.
  const Pose3 X_WC = optical_pose(Pose3::Identity(), uav.depth_camera());
  EXPECT_LT((X_WC.linear().col(2) - Eigen::Vector3d(0, 0, -1)).norm(), 1e-9);
}

TEST(SensorSim, AFloorSlabInTheGroundPlaneDoesNotStripeWithIt) {
  // The hidden space's floor slab top lies in the ground plane (z = 0): seen from
  // inside, the floor is the slab's face, every pixel of it the colour of the same
  // material facing up elsewhere (the roof, seen from above), never the ground's.
  const SensorSimulator sim(world(hidden_space("{id: 3, size_m: 0.2, placement: wall}")));
  const RgbImage roof = sim.render_camera(kCam, looking_down(0, 0, 2.0), clean_camera(), 1);
  const RgbImage ground = sim.render_camera(kCam, looking_down(8, 8, 2.0), clean_camera(), 1);
  ASSERT_NE(roof.at(320, 240, 0), ground.at(320, 240, 0));
  const Pose3 X_WC = look_at({-1.0, 0.2, 0.1}, {1.0, 0.0, 0.0});
  const RgbImage img = sim.render_camera(kCam, X_WC, clean_camera(), 1);
  for (int v = 300; v < 480; ++v)
    for (int u = 0; u < 640; u += 3)
      ASSERT_EQ(img.at(u, v, 0), roof.at(320, 240, 0)) << u << "," << v;
}

TEST(SensorSim, ABoxGivesItsHeightAsADepthStep) {
  // A 1 x 1 x 0.8 m box on the ground at the origin, seen from 3 m straight above.
  const SensorSimulator sim(
      world("boxes:\n  - {name: b, center_m: [0, 0], size_m: [1, 1, 0.8], yaw_deg: 20}\n"));
  const DepthImageMm d = sim.render_depth(kCam, looking_down(0, 0, 3.0), exact_depth(), 1);
  EXPECT_EQ(d.at(320, 240), 2200);  // the box top
  EXPECT_EQ(d.at(5, 5), 3000);      // the ground beside it
  // The box's edge: its top spans f * 1 m / 2.2 m = 252 px; at 0.4 m from the centre
  // along the box's own x (yawed 20 deg) the pixel is inside, at 0.6 m outside.
  const double f = kCam.fx_px;
  const auto pixel_at = [&](double r_m) {
    const double x = r_m * std::cos(deg_to_rad(20)), y = r_m * std::sin(deg_to_rad(20));
    // Looking down with +y up in the image: u = cx + f x / z, v = cy - f y / z.
    return d.at(static_cast<int>(std::lround(319.5 + f * x / 2.2)),
                static_cast<int>(std::lround(239.5 - f * y / 2.2)));
  };
  EXPECT_EQ(pixel_at(0.45), 2200);
  EXPECT_EQ(pixel_at(0.58), 3000);
}

TEST(SensorSim, NoReturnBeyondMaxRangeOrAtGrazingIncidence) {
  const SensorSimulator sim(world("ground: {height_m: 0.0}\n"));
  DepthFrameOptions o = exact_depth();
  o.max_range_m = 1.5;
  const DepthImageMm far = sim.render_depth(kCam, looking_down(0, 0, 2.0), o, 1);
  EXPECT_TRUE(std::all_of(far.data.begin(), far.data.end(), [](auto v) { return v == 0; }));
  o.max_range_m = 1.9;
  o.min_range_m = 2.1;  // nor below the minimum range
  const DepthImageMm near = sim.render_depth(kCam, looking_down(0, 0, 2.0), o, 1);
  EXPECT_TRUE(std::all_of(near.data.begin(), near.data.end(), [](auto v) { return v == 0; }));

  // From 1 m up, the optical axis 30 deg below the horizon: the centre ray meets the
  // ground 2 m away at 60 deg from its normal; the top rows see the ground at up to
  // 83 deg, beyond the 75 deg limit (their z stays under 10 m).
  const Pose3 X_WC = look_at({0, 0, 1}, {std::cos(kPi / 6), 0, 1 - std::sin(kPi / 6)});
  const DepthImageMm d = sim.render_depth(kCam, X_WC, exact_depth(), 1);
  // On the axis z = 1 m / sin 30 deg = 2 m; pixel (320, 240) is half a pixel off it,
  // where z = height / (the ray's fall per unit z).
  const Eigen::Vector3d centre_W = X_WC.linear() * kCam.ray({320, 240});
  EXPECT_NEAR(1.0 / -centre_W.z(), 2.0, 0.005);
  EXPECT_NEAR(d.at(320, 240), 1000.0 / -centre_W.z(), 0.5);
  int checked_zero = 0, checked_return = 0;
  for (int v = 0; v < 480; v += 4) {
    const Eigen::Vector3d ray_W = X_WC.linear() * kCam.ray({320, v});
    const double incidence_deg = rad_to_deg(std::acos(-ray_W.z() / ray_W.norm()));
    if (incidence_deg > 75.5) {
      EXPECT_EQ(d.at(320, v), 0) << "row " << v;
      ++checked_zero;
    } else if (incidence_deg < 74.5) {
      EXPECT_GT(d.at(320, v), 0) << "row " << v;
      ++checked_return;
    }
  }
  EXPECT_GT(checked_zero, 10);
  EXPECT_GT(checked_return, 10);
}

TEST(SensorSim, SameSeedSameBytesOtherSeedOtherBytes) {
  const SensorSimulator sim(world(hidden_space("{id: 3, size_m: 0.2, placement: wall}")));
  const Pose3 X_WC = look_at({4.0, 0.5, 1.0}, {2.6, 0, 0.3});
  const CameraFrameOptions co;
  const DepthFrameOptions dopt;
  EXPECT_EQ(sim.render_camera(kCam, X_WC, co, 5).data, sim.render_camera(kCam, X_WC, co, 5).data);
  EXPECT_NE(sim.render_camera(kCam, X_WC, co, 5).data, sim.render_camera(kCam, X_WC, co, 6).data);
  EXPECT_EQ(sim.render_depth(kCam, X_WC, dopt, 5).data, sim.render_depth(kCam, X_WC, dopt, 5).data);
  EXPECT_NE(sim.render_depth(kCam, X_WC, dopt, 5).data, sim.render_depth(kCam, X_WC, dopt, 6).data);
}

// The grey camera is the colour camera's luminance: equal but for the one rounding
// without blur and noise, equal on average with them, and its noise the luminance of
// three channels' noise (0.668 sigma), not sigma.
TEST(SensorSim, TheGreyFrameIsTheColourFramesLuminance) {
  const SensorSimulator sim(world(hidden_space("{id: 3, size_m: 0.2, placement: wall}")));
  const Pose3 X_WC = look_at({4.0, 0.5, 1.0}, {2.6, 0, 0.3});
  const GrayImage exact = sim.render_gray(kCam, X_WC, clean_camera(), 1);
  const GrayImage from_colour = to_gray(sim.render_camera(kCam, X_WC, clean_camera(), 1));
  ASSERT_EQ(exact.data.size(), from_colour.data.size());
  int off_by_more_than_one = 0;
  for (std::size_t i = 0; i < exact.data.size(); ++i)
    off_by_more_than_one += std::abs(int(exact.data[i]) - int(from_colour.data[i])) > 1;
  EXPECT_EQ(off_by_more_than_one, 0);
  CameraFrameOptions noisy = clean_camera();
  noisy.noise_sigma = 6.0;
  const GrayImage n = sim.render_gray(kCam, X_WC, noisy, 7);
  double sum = 0, sum2 = 0;
  int count = 0;
  for (std::size_t i = 0; i < n.data.size(); ++i) {
    if (exact.data[i] < 20 || exact.data[i] > 235) continue;  // clear of the clamp at 0 and 255
    const double d = double(n.data[i]) - double(exact.data[i]);
    sum += d, sum2 += d * d, ++count;
  }
  ASSERT_GT(count, 10000);
  EXPECT_NEAR(sum / count, 0.0, 0.05);
  EXPECT_NEAR(std::sqrt(sum2 / count), 0.668 * 6.0, 0.1);
  // Blur and noise: the same bytes for a seed, other bytes for another.
  const CameraFrameOptions co;
  EXPECT_EQ(sim.render_gray(kCam, X_WC, co, 5).data, sim.render_gray(kCam, X_WC, co, 5).data);
  EXPECT_NE(sim.render_gray(kCam, X_WC, co, 5).data, sim.render_gray(kCam, X_WC, co, 6).data);
}

TEST(SensorSim, VisibleMarkerCornersAreTheProjectionsOfTheMarkersCorners) {
  const WorldSpec w = world(hidden_space("{id: 3, size_m: 0.2, placement: roof}"));
  const SensorSimulator sim(w);
  const FiducialMarker& m = w.hidden_spaces[0].marker;
  // Straight above the roof marker, 1.4 m over it, the image's top along the marker's up.
  const Eigen::Vector3d c = m.X_WM.translation();
  const Pose3 X_WC = look_at(c + Eigen::Vector3d(0, 0, 1.4), c, m.X_WM.linear().col(1));
  const auto seen = sim.visible_markers(kCam, X_WC);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].id, 3);
  EXPECT_DOUBLE_EQ(seen[0].visible_fraction, 1.0);
  EXPECT_NEAR(seen[0].distance_m, 1.4, 1e-9);
  EXPECT_NEAR(seen[0].off_axis_rad, 0.0, 1e-9);
  // By hand: the marker is centred, upright in the image, f * 0.2 / 1.4 px wide; the
  // corners in OpenCV's order (top-left first, clockwise).
  const double half_px = kCam.fx_px * 0.1 / 1.4;
  const Eigen::Vector2d expect[4] = {{319.5 - half_px, 239.5 - half_px},
                                     {319.5 + half_px, 239.5 - half_px},
                                     {319.5 + half_px, 239.5 + half_px},
                                     {319.5 - half_px, 239.5 + half_px}};
  for (int k = 0; k < 4; ++k) EXPECT_LT((seen[0].corners_px[k] - expect[k]).norm(), 1e-6) << k;

  // A distorted camera, obliquely: the corners are project() of the world corners.
  CameraModel lens = kCam;
  lens.distortion = DistortionModel::kPlumbBob;
  lens.distortion_coefficients = {-0.3, 0.1, 0.001, -0.002, 0.0};
  const Pose3 X_WC2 = look_at(c + Eigen::Vector3d(0.6, 0.4, 0.9), c);
  const auto seen2 = sim.visible_markers(lens, X_WC2);
  ASSERT_EQ(seen2.size(), 1u);
  const Eigen::Vector2d corners_M[4] = {{-0.1, 0.1}, {0.1, 0.1}, {0.1, -0.1}, {-0.1, -0.1}};
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d p_W = m.X_WM * Eigen::Vector3d(corners_M[k].x(), corners_M[k].y(), 0);
    const auto px = lens.project(X_WC2.inverse() * p_W);
    ASSERT_TRUE(px);
    EXPECT_LT((seen2[0].corners_px[k] - *px).norm(), 1e-9) << k;
  }
  EXPECT_NEAR(seen2[0].off_axis_rad, std::acos(0.9 / std::sqrt(0.36 + 0.16 + 0.81)), 1e-9);
}

// Samples a clean frame at the projected centre of every bitmap cell; true when each
// is on the right side of the middle between the darkest and brightest samples.
void expect_cells_match(const SensorSimulator& sim, const FiducialMarker& m,
                        const CameraModel& camera, const Pose3& X_WC) {
  const RgbImage img = sim.render_camera(camera, X_WC, clean_camera(), 1);
  const MarkerBitmap bmp = marker_bitmap(m.dictionary, m.id);
  const int n = bmp.cells.width_px;
  const double cell = m.size_m / bmp.black_square_cells, half = cell * n / 2;
  std::vector<int> values;
  const auto sample = [&](double x_M, double y_M) {
    const auto px = camera.project(X_WC.inverse() * (m.X_WM * Eigen::Vector3d(x_M, y_M, 0)));
    EXPECT_TRUE(px && camera.in_image(*px));
    return img.at(static_cast<int>(std::lround(px->x())), static_cast<int>(std::lround(px->y())),
                  1);
  };
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      values.push_back(sample(-half + (c + 0.5) * cell, half - (r + 0.5) * cell));
  const auto [lo, hi] = std::minmax_element(values.begin(), values.end());
  ASSERT_GT(*hi - *lo, 60);  // real contrast, not a flat patch
  const int mid = (*lo + *hi) / 2;
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c)
      EXPECT_EQ(values[r * n + c] > mid, bmp.cells.at(c, r) > 127) << "cell " << c << "," << r;
  // The quiet zone: half a cell outside the bitmap, on all four sides, is as white as
  // the white cells (the bare wall beyond it is a darker grey), and two cells out the
  // wall shows again.
  const int white = (mid + *hi) / 2;
  for (const double t : {-half + cell, 0.0, half - cell}) {
    EXPECT_GT(sample(-half - cell / 2, t), white);
    EXPECT_GT(sample(half + cell / 2, t), white);
    EXPECT_GT(sample(t, -half - cell / 2), white);
    EXPECT_GT(sample(t, half + cell / 2), white);
  }
  EXPECT_LT(sample(half + 2 * cell, 0.0), white);
}

TEST(SensorSim, RenderedMarkerCellsMatchTheBitmapForArucoAndAprilTag) {
  for (const std::string marker :
       {"{id: 3, size_m: 0.2, placement: wall}",
        "{id: 17, size_m: 0.25, family: apriltag, dictionary: tag36h11, placement: wall}",
        "{id: 5, size_m: 0.2, family: apriltag, dictionary: tagStandard41h12, placement: wall}"}) {
    SCOPED_TRACE(marker);
    const WorldSpec w = world(hidden_space(marker));
    const SensorSimulator sim(w);
    const FiducialMarker& m = w.hidden_spaces[0].marker;
    const Eigen::Vector3d c = m.X_WM.translation();
    expect_cells_match(sim, m, kCam, look_at(c + Eigen::Vector3d(0.7, 0, 0), c));
    // Oblique and through a distorting lens.
    CameraModel lens = kCam;
    lens.distortion = DistortionModel::kPlumbBob;
    lens.distortion_coefficients = {-0.25, 0.08, 0.0, 0.0, 0.0};
    expect_cells_match(sim, m, lens, look_at(c + Eigen::Vector3d(0.5, 0.35, 0.2), c));
  }
}

TEST(SensorSim, AMarkerBehindAWallIsNeitherVisibleNorDrawn) {
  // A 2 m high wall between the camera and the marker on the +x face of the space.
  const WorldSpec w = world(hidden_space("{id: 3, size_m: 0.2, placement: wall}") +
                            "boxes:\n  - {name: wall, center_m: [3.3, 0], size_m: [0.1, 3, 2]}\n");
  const SensorSimulator sim(w);
  const FiducialMarker& m = w.hidden_spaces[0].marker;
  const Eigen::Vector3d c = m.X_WM.translation();
  const Pose3 X_WC = look_at(c + Eigen::Vector3d(1.5, 0, 0), c);
  EXPECT_TRUE(sim.visible_markers(kCam, X_WC).empty());
  // Where the marker would be, the frame shows the wall's uniform grey.
  const RgbImage img = sim.render_camera(kCam, X_WC, clean_camera(), 1);
  const auto centre = kCam.project(X_WC.inverse() * c);
  ASSERT_TRUE(centre);
  const int u0 = static_cast<int>(std::lround(centre->x())),
            v0 = static_cast<int>(std::lround(centre->y()));
  const int half_px = static_cast<int>(kCam.fx_px * 0.1 / 1.5);
  const std::uint8_t ref = img.at(u0, v0, 1);
  for (int v = v0 - half_px; v <= v0 + half_px; ++v)
    for (int u = u0 - half_px; u <= u0 + half_px; ++u) ASSERT_EQ(img.at(u, v, 1), ref);
  // Without the wall the same view sees it whole, and draws black cells there.
  const SensorSimulator open(world(hidden_space("{id: 3, size_m: 0.2, placement: wall}")));
  const auto seen = open.visible_markers(kCam, X_WC);
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_DOUBLE_EQ(seen[0].visible_fraction, 1.0);
  const RgbImage img2 = open.render_camera(kCam, X_WC, clean_camera(), 1);
  int dark = 0;
  for (int v = v0 - half_px; v <= v0 + half_px; ++v)
    for (int u = u0 - half_px; u <= u0 + half_px; ++u) dark += img2.at(u, v, 1) < 40;
  EXPECT_GT(dark, half_px * half_px);  // a 4x4 ArUco marker is mostly black
}

// markers_in_frame is the mission's reason not to render a frame: it must be false only
// when the frame is the one the scene gives without the marker. Two worlds that differ
// only in the marker's id give the same bytes exactly then; panning the camera across
// the marker and past it sweeps both sides of the image's edge.
TEST(SensorSim, AFrameNoMarkerIsInIsTheSameWhateverTheMarker) {
  const WorldSpec w3 = world(hidden_space("{id: 3, size_m: 0.2, placement: wall}"));
  const WorldSpec w4 = world(hidden_space("{id: 4, size_m: 0.2, placement: wall}"));
  const SensorSimulator sim3(w3), sim4(w4);
  CameraModel lens = kCam;  // a distorting lens: the image is not a rectangle of rays
  lens.distortion = DistortionModel::kPlumbBob;
  lens.distortion_coefficients = {-0.25, 0.08, 0.0, 0.0, 0.0};
  const Eigen::Vector3d c = w3.hidden_spaces[0].marker.X_WM.translation();
  int out_of_frame = 0, seen = 0;
  for (const CameraModel* cam : std::array<const CameraModel*, 2>{&kCam, &lens})
    for (const double distance_m : {1.0, 3.0})
      for (int deg = -70; deg <= 70; deg += 4) {
        const Eigen::Vector3d eye = c + Eigen::Vector3d(distance_m, 0.1, 0.05);
        const double a = deg_to_rad(deg);
        // Looking from `eye` towards the marker, turned by `deg` about the vertical.
        const Eigen::Vector3d ahead = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) * (c - eye);
        const Pose3 X_WC = look_at(eye, eye + ahead);
        const bool in = sim3.markers_in_frame(*cam, X_WC);
        EXPECT_EQ(in, sim4.markers_in_frame(*cam, X_WC));
        const GrayImage a3 = sim3.render_gray(*cam, X_WC, CameraFrameOptions{}, 9);
        const GrayImage a4 = sim4.render_gray(*cam, X_WC, CameraFrameOptions{}, 9);
        const auto visible = sim3.visible_markers(*cam, X_WC);
        if (!in) {
          ++out_of_frame;
          EXPECT_TRUE(a3.data == a4.data) << deg << " deg at " << distance_m << " m";
          EXPECT_TRUE(visible.empty()) << deg;
        } else if (!visible.empty() &&
                   visible[0].visible_fraction == 1.0) {  // (the border is every id's)
          ++seen;
          EXPECT_FALSE(a3.data == a4.data) << deg << " deg at " << distance_m << " m";
        }
      }
  EXPECT_GT(out_of_frame, 20);
  EXPECT_GT(seen, 20);
  // Behind the camera, and facing away: not in the frame.
  EXPECT_FALSE(sim3.markers_in_frame(
      kCam, look_at(c + Eigen::Vector3d(1, 0, 0), c + Eigen::Vector3d(2, 0, 0))));
}

TEST(SensorSim, AMarkerHalfBehindAPostIsPartlyVisible) {
  // A post covering the marker's left half (seen from the front, +x looking at -x,
  // the marker's x is world +y... its left is world -y).
  const WorldSpec w =
      world(hidden_space("{id: 3, size_m: 0.2, placement: wall}") +
            "boxes:\n  - {name: post, center_m: [3.0, -0.5], size_m: [0.1, 1.0, 2]}\n");
  const SensorSimulator sim(w);
  const Eigen::Vector3d c = w.hidden_spaces[0].marker.X_WM.translation();
  const auto seen = sim.visible_markers(kCam, look_at(c + Eigen::Vector3d(1.5, 0, 0), c));
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_NEAR(seen[0].visible_fraction, 0.5, 1.0 / 16);
}

double hue_deg(double r, double g, double b) {
  const double mx = std::max({r, g, b}), mn = std::min({r, g, b});
  if (mx == mn) return 0;
  double h = 0;
  if (mx == r)
    h = 60 * std::fmod((g - b) / (mx - mn), 6.0);
  else if (mx == g)
    h = 60 * ((b - r) / (mx - mn) + 2);
  else
    h = 60 * ((r - g) / (mx - mn) + 4);
  return h < 0 ? h + 360 : h;
}

TEST(SensorSim, ObjectsAppearInTheirPaintHue) {
  // A 0.3 m cube object inside the space, seen through the roof-less view of a camera
  // inside it (as the miniUGV's): 0.8 m in front of it.
  const WorldSpec w = world(hidden_space("{id: 3, size_m: 0.2, placement: wall}") +
                            "objects:\n  - {name: o, hidden_space: hs, position_m: [1.0, 0.5], "
                            "size_m: [0.3, 0.3, 0.3]}\n");
  const SensorSimulator sim(w);
  const Eigen::Vector3d p_O = w.objects[0].box.center_m;
  const Pose3 X_WC = look_at(p_O + Eigen::Vector3d(-0.8, 0, 0.05), p_O);
  CameraFrameOptions o;  // default blur and noise
  const RgbImage img = sim.render_camera(kCam, X_WC, o, 2);
  const double paint = hue_deg(kObjectColourRgb[0], kObjectColourRgb[1], kObjectColourRgb[2]);
  for (const auto& [du, dv] : std::vector<std::pair<int, int>>{{0, 0}, {-20, 10}, {15, -15}}) {
    const int u = 320 + du, v = 240 + dv;
    EXPECT_NEAR(hue_deg(img.at(u, v, 0), img.at(u, v, 1), img.at(u, v, 2)), paint, 5.0);
    EXPECT_GT(img.at(u, v, 0) - img.at(u, v, 2), 80);  // saturated, not grey
  }
  // Painted grey on request: the same pixel is neutral.
  o.draw_objects = false;
  const RgbImage grey = sim.render_camera(kCam, X_WC, o, 2);
  EXPECT_LT(std::abs(grey.at(320, 240, 0) - grey.at(320, 240, 2)), 15);
}

TEST(SensorSim, IrBeamsStartAtTheirUrdfPosesAndReadTheWall) {
  const RobotDescription robot = load_robot("miniugv");
  // A wall whose face is at x = 1.0 m, the robot at the origin facing +x.
  const SensorSimulator sim(
      world("boxes:\n  - {name: w, center_m: [1.05, 0], size_m: [0.1, 4, 1]}\n"));
  SensorOptions exact;
  exact.ir_noise_m = 0.0;
  exact.ir_dropout = 0.0;
  const Pose3 X_WB = pose_from_xyz_rpy({0, 0, 0}, 0, 0, 0);
  const auto r = sim.ir_ranges(robot, X_WB, exact, 1);
  const IrArray ir = robot.ir_array();
  ASSERT_EQ(r.size(), ir.beams.size());
  for (std::size_t i = 0; i < r.size(); ++i) {
    SCOPED_TRACE(r[i].sensor);
    const RangeSensor* s = robot.find_range_sensor(r[i].sensor);
    ASSERT_NE(s, nullptr);
    EXPECT_LT((r[i].p_WO - s->X_BS.translation()).norm(), 1e-12);  // not the base origin
    EXPECT_GT(r[i].p_WO.x(), 0.05);
    EXPECT_NEAR(r[i].direction_W.z(), 0.0, 1e-12);
    const double expected = (1.0 - r[i].p_WO.x()) / r[i].direction_W.x();
    if (expected <= s->range_max_m) {
      EXPECT_TRUE(r[i].hit);
      EXPECT_NEAR(r[i].range_m, expected, 1e-9);
    } else {
      EXPECT_FALSE(r[i].hit);
    }
  }
  // Turned away from the wall, nothing returns; with noise, same seed same readings.
  const auto away = sim.ir_ranges(robot, pose_from_xyz_rpy({0, 0, 0}, 0, 0, kPi), exact, 1);
  for (const auto& b : away) EXPECT_FALSE(b.hit);
  const SensorOptions noisy;
  const auto a1 = sim.ir_ranges(robot, X_WB, noisy, 9), a2 = sim.ir_ranges(robot, X_WB, noisy, 9);
  for (std::size_t i = 0; i < a1.size(); ++i) EXPECT_EQ(a1[i].range_m, a2[i].range_m);
}

TEST(SensorSim, ImuReadsTheSlopeUnderTheRobot) {
  // Ground rising 0.1 m per m along x: heading +x the robot pitches nose up by
  // atan(0.1) (negative pitch in the rpy convention), heading +y it rolls.
  const SensorSimulator sim(world("ground: {height_m: 0.2, slope: [0.1, 0.0]}\n"));
  const auto up = sim.resting_pose({2.0, 1.0}, 0.0, 5.0, 0.03);
  ASSERT_TRUE(up);
  EXPECT_NEAR(up->translation().z(), 0.4 + 0.03 / std::sqrt(1.01), 1e-9);
  ImuOptions exact;
  exact.tilt_noise_rad = exact.yaw_noise_rad = 0.0;
  const ImuReading a = sim.imu(*up, exact, 1);
  EXPECT_NEAR(a.pitch_rad, -std::atan(0.1), 1e-9);
  EXPECT_NEAR(a.roll_rad, 0.0, 1e-9);
  EXPECT_NEAR(a.yaw_rad, 0.0, 1e-9);
  const ImuReading b = sim.imu(*sim.resting_pose({2.0, 1.0}, kPi / 2, 5.0), exact, 1);
  EXPECT_NEAR(b.roll_rad, -std::atan(0.1), 1e-9);  // its left (-x, downhill) lower
  EXPECT_NEAR(b.pitch_rad, 0.0, 1e-9);
  EXPECT_NEAR(b.yaw_rad, kPi / 2, 1e-9);
  // On a box top the robot is level again, at the box's height.
  const SensorSimulator boxed(
      world("boxes:\n  - {name: b, center_m: [0, 0, 0.5], size_m: [2, 2, 1]}\n"));
  const auto top = boxed.resting_pose({0.3, 0.2}, 1.0, 3.0);
  ASSERT_TRUE(top);
  EXPECT_NEAR(top->translation().z(), 1.0, 1e-9);
  EXPECT_NEAR(sim.imu(*top, exact, 1).pitch_rad, 0.0, 1e-9);
  // The noise is seeded and of the stated size.
  const ImuOptions noisy;
  double s2 = 0;
  for (std::uint64_t seed = 0; seed < 400; ++seed) {
    const double e = sim.imu(*up, noisy, seed).pitch_rad + std::atan(0.1);
    s2 += e * e;
  }
  EXPECT_NEAR(std::sqrt(s2 / 400), noisy.tilt_noise_rad, 0.15 * noisy.tilt_noise_rad);
  EXPECT_EQ(sim.imu(*up, noisy, 3).roll_rad, sim.imu(*up, noisy, 3).roll_rad);
  // No surface under a point outside the world's bounds.
  EXPECT_FALSE(sim.resting_pose({50.0, 0.0}, 0.0, 5.0));
}

TEST(SensorSim, PoseFromXyzRpyRoundTrips) {
  const Pose3 X = pose_from_xyz_rpy({1, 2, 3}, 0.1, -0.4, 2.5);
  const ImuReading r = rpy_of(X.linear());
  EXPECT_NEAR(r.roll_rad, 0.1, 1e-12);
  EXPECT_NEAR(r.pitch_rad, -0.4, 1e-12);
  EXPECT_NEAR(r.yaw_rad, 2.5, 1e-12);
  // Roll about x first: the body's y axis tilts up by the roll.
  EXPECT_NEAR(pose_from_xyz_rpy({0, 0, 0}, 0.3, 0, 0).linear()(2, 1), std::sin(0.3), 1e-12);
}

}  // namespace
}  // namespace ferret
