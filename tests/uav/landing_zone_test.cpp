// LandingZoneDetector and Px4LandingBaseline on depth frames computed analytically here:
// the ray through every pixel (CameraModel::ray) is intersected with a height field
// whose answer is known by construction.
#include "ferret/uav/landing_zone.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "ferret/core/error.hpp"
#include "ferret/core/random.hpp"
#include "ferret/planning/mission_config.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

using HeightField = std::function<double(double x, double y)>;

// A depth camera looking straight down from `p_W`: optical z = -z_W, x = x_W, y = -y_W.
Pose3 downward(const Eigen::Vector3d& p_W) {
  Pose3 X;
  X.linear() << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  X.translation() = p_W;
  return X;
}

CameraModel test_camera() { return CameraModel::from_fov("depth", 320, 240, deg_to_rad(65.0)); }

// The first crossing of the ray with the height field (marching in 1 cm, then
// bisecting), as mm along the optical axis, with optional seeded z noise.
DepthImageMm render(const CameraModel& cam, const Pose3& X_WC, const HeightField& h,
                    double noise_m = 0.0, std::uint64_t seed = 1, double h_max = 2.0) {
  DepthImageMm img(cam.width_px, cam.height_px, 0);
  Rng rng(seed);
  for (int v = 0; v < cam.height_px; ++v)
    for (int u = 0; u < cam.width_px; ++u) {
      const Eigen::Vector3d r_C = cam.ray({u, v});  // z = 1
      const Eigen::Vector3d d_W = X_WC.linear() * r_C;
      const Eigen::Vector3d o = X_WC.translation();
      // Start where the ray reaches h_max (the camera looks down: d_W.z < 0).
      double t0 = std::max(0.0, (o.z() - h_max) / -d_W.z());
      const double step = 0.01 / r_C.norm();
      double t = t0;
      const auto below = [&](double tt) {
        const Eigen::Vector3d p = o + tt * d_W;
        return p.z() <= h(p.x(), p.y());
      };
      if (below(t)) continue;
      while (t < 20.0 && !below(t + step)) t += step;
      if (t >= 20.0) continue;
      double a = t, b = t + step;
      for (int k = 0; k < 30; ++k) {
        const double m = 0.5 * (a + b);
        (below(m) ? b : a) = m;
      }
      const double z = 0.5 * (a + b) + (noise_m > 0 ? rng.normal(0.0, noise_m) : 0.0);
      img.at(u, v) = static_cast<std::uint16_t>(std::lround(z * 1000.0));
    }
  return img;
}

LandingZoneDetector detector() { return LandingZoneDetector(LandingZoneDetector::Options{}); }

TEST(LandingZone, FlatGroundGivesAZoneBelowTheCameraWithZeroSlope) {
  const auto cam = test_camera();
  const Pose3 X_WC = downward({1.0, 2.0, 3.0});
  const auto depth = render(
      cam, X_WC, [](double, double) { return 0.2; }, 0.003, 7);
  const auto r = detector().detect(depth, cam, X_WC);
  ASSERT_FALSE(r.no_safe_zone) << r.reason;
  ASSERT_FALSE(r.zones.empty());
  const auto& best = r.zones.front();
  // Without an opening the ranking prefers the point under the camera (one cell off at
  // most, the grid's cells are 0.1 m).
  EXPECT_NEAR(best.center_m.x(), 1.0, 0.1);
  EXPECT_NEAR(best.center_m.y(), 2.0, 0.1);
  EXPECT_NEAR(best.center_m.z(), 0.2, 0.01);
  EXPECT_LT(best.slope_deg, 0.5);
  EXPECT_LT(best.roughness_m, 0.01);
  EXPECT_TRUE(std::isnan(best.distance_to_opening_m));
  // Zones are distinct: at least a footprint apart.
  for (std::size_t a = 0; a < r.zones.size(); ++a)
    for (std::size_t b = a + 1; b < r.zones.size(); ++b)
      EXPECT_GE((r.zones[a].center_m - r.zones[b].center_m).head<2>().norm(), 0.49);
}

TEST(LandingZone, ThirtyDegreeSlopeHasNoZone) {
  const auto cam = test_camera();
  const Pose3 X_WC = downward({0.0, 0.0, 3.0});
  const double g = std::tan(deg_to_rad(30.0));
  const auto depth = render(
      cam, X_WC, [g](double x, double) { return g * x; }, 0.0, 1, 3.0);
  const auto r = detector().detect(depth, cam, X_WC);
  EXPECT_TRUE(r.no_safe_zone);
  EXPECT_TRUE(r.zones.empty());
  EXPECT_NE(r.reason.find("slope"), std::string::npos) << r.reason;
}

TEST(LandingZone, TenDegreeSlopeIsMeasuredToHalfADegree) {
  const auto cam = test_camera();
  const Pose3 X_WC = downward({0.5, -0.5, 3.0});
  // Down-slope towards -x+y, at 10 degrees.
  const double g = std::tan(deg_to_rad(10.0));
  const Eigen::Vector2d dir = Eigen::Vector2d(1.0, -1.0).normalized();
  const auto depth = render(
      cam, X_WC, [&](double x, double y) { return g * (dir.x() * x + dir.y() * y); }, 0.003, 3);
  const auto r = detector().detect(depth, cam, X_WC);
  ASSERT_FALSE(r.zones.empty()) << r.reason;
  for (const auto& z : r.zones) {
    EXPECT_NEAR(z.slope_deg, 10.0, 0.5);
    EXPECT_NEAR(z.center_m.z(), g * (dir.x() * z.center_m.x() + dir.y() * z.center_m.y()), 0.01);
  }
}

TEST(LandingZone, SeededBumpsBeyondTheRoughnessLimitGiveNoZone) {
  const auto cam = test_camera();
  const Pose3 X_WC = downward({0.0, 0.0, 3.0});
  // Tiles of 0.3 m at random heights in [0, 0.2] m: RMS about 6 cm over a disc.
  Rng rng(42);
  std::vector<double> tiles(40 * 40);
  for (auto& t : tiles) t = rng.uniform(0.0, 0.2);
  const auto h = [&](double x, double y) {
    const int i = std::clamp(static_cast<int>(std::floor(x / 0.3)) + 20, 0, 39);
    const int j = std::clamp(static_cast<int>(std::floor(y / 0.3)) + 20, 0, 39);
    return tiles[static_cast<std::size_t>(j * 40 + i)];
  };
  const auto r = detector().detect(render(cam, X_WC, h, 0.003, 9), cam, X_WC);
  EXPECT_TRUE(r.no_safe_zone) << r.zones.size() << " zones, first step " << r.zones[0].step_m;
  EXPECT_NE(r.reason.find("roughness"), std::string::npos) << r.reason;
}

TEST(LandingZone, StepThroughTheMiddleKeepsZonesAFootprintAway) {
  const auto cam = test_camera();
  const Pose3 X_WC = downward({1.0, 0.0, 3.0});
  const double step_x = 1.03;  // not on a cell boundary
  const auto depth = render(
      cam, X_WC, [&](double x, double) { return x >= step_x ? 0.3 : 0.0; }, 0.003, 5);
  const auto det = detector();
  const auto r = det.detect(depth, cam, X_WC);
  ASSERT_FALSE(r.zones.empty()) << r.reason;
  bool low = false, high = false;
  for (const auto& z : r.zones) {
    EXPECT_GE(std::abs(z.center_m.x() - step_x), det.options().footprint_radius_m)
        << "zone at " << z.center_m.transpose();
    (z.center_m.x() < step_x ? low : high) = true;
    EXPECT_NEAR(z.center_m.z(), z.center_m.x() < step_x ? 0.0 : 0.3, 0.01);
  }
  EXPECT_TRUE(low && high);  // both sides are flat and wide enough
}

TEST(LandingZone, TallPoleKeepsFootprintPlusClearanceFree) {
  const auto cam = test_camera();
  const Pose3 X_WC = downward({0.0, 0.0, 3.0});
  const Eigen::Vector2d pole(0.3, 0.2);
  const double pole_r = 0.15;
  const auto depth = render(
      cam, X_WC,
      [&](double x, double y) {
        return (Eigen::Vector2d(x, y) - pole).norm() <= pole_r ? 1.5 : 0.0;
      },
      0.003, 11);
  const auto det = detector();
  const auto r = det.detect(depth, cam, X_WC);
  ASSERT_FALSE(r.zones.empty()) << r.reason;
  const double keep = det.options().footprint_radius_m + det.options().min_clearance_m + pole_r;
  for (const auto& z : r.zones) {
    EXPECT_GE((z.center_m.head<2>() - pole).norm(), keep) << z.center_m.transpose();
    EXPECT_GE(z.clearance_m, det.options().min_clearance_m);
  }
  // Something was turned down for clearance (the pole is in view).
  bool clearance = false;
  for (const auto& z : r.rejected) clearance |= z.reject == LandingReject::kClearance;
  EXPECT_TRUE(clearance);
}

TEST(LandingZone, AThinRodBesideTheDiscIsNotAveragedAwayInItsCells) {
  // A rod 3 cm wide and 0.3 m tall, at an angle to the grid: it covers at most about
  // 40 % of any 0.1 m cell, whose mean rises by 0.13 m at most, under the 0.15 m
  // taller-than test; the clearance test's half-size cells see it.
  const auto cam = test_camera();
  const Pose3 X_WC = downward({0.0, 0.0, 4.0});
  const Eigen::Vector2d through(0.1, 0.0), along(std::cos(0.61), std::sin(0.61));
  const Eigen::Vector2d normal(-along.y(), along.x());
  const double half_width = 0.015, height = 0.3;
  const auto rod_distance = [&](const Eigen::Vector2d& p) {
    return std::abs((p - through).dot(normal)) - half_width;
  };
  const auto depth = render(
      cam, X_WC,
      [&](double x, double y) {
        return rod_distance({x, y}) <= 0.0 ? height : 0.0;
      },
      0.003, 13);
  const auto det = detector();
  const auto r = det.detect(depth, cam, X_WC);
  ASSERT_FALSE(r.zones.empty()) << r.reason;
  const double keep =
      det.options().footprint_radius_m + det.options().margin_m + det.options().min_clearance_m;
  for (const auto& z : r.zones)
    EXPECT_GE(rod_distance(z.center_m.head<2>()), keep - 0.01) << z.center_m.transpose();
}

// The same rod in a hover's eight frames, each from a pose up to 3 cm and half a degree
// from the first: fused, a pixel by the rod averages the rod's top and the ground
// behind it from frame to frame, and the rod's mean over a window is what it was. No
// zone lets it within the clearance either.
TEST(LandingZone, AThinRodBesideTheDiscIsSeenInAHoversDriftingFramesFused) {
  const auto cam = test_camera();
  const Eigen::Vector2d through(0.1, 0.0), along(std::cos(0.61), std::sin(0.61));
  const Eigen::Vector2d normal(-along.y(), along.x());
  const auto rod_distance = [&](const Eigen::Vector2d& p) {
    return std::abs((p - through).dot(normal)) - 0.015;
  };
  const HeightField rod = [&](double x, double y) {
    return rod_distance({x, y}) <= 0.0 ? 0.3 : 0.0;
  };
  Rng drift(5);
  std::vector<DepthImageMm> frames;
  std::vector<Pose3> poses;
  for (std::uint64_t k = 0; k < 8; ++k) {
    Pose3 X_WC = downward({0.0, 0.0, 4.0});
    if (k > 0) {
      X_WC.translation() += Eigen::Vector3d(drift.uniform(-0.03, 0.03), drift.uniform(-0.03, 0.03),
                                            drift.uniform(-0.03, 0.03));
      const double r = deg_to_rad(0.5);
      X_WC.linear() =
          X_WC.linear() * (Eigen::AngleAxisd(drift.uniform(-r, r), Eigen::Vector3d::UnitX()) *
                           Eigen::AngleAxisd(drift.uniform(-r, r), Eigen::Vector3d::UnitY()))
                              .toRotationMatrix();
    }
    poses.push_back(X_WC);
    frames.push_back(render(cam, X_WC, rod, 0.003, 13 + k));
  }
  std::vector<PosedDepthFrame> hover;
  for (std::size_t k = 0; k < frames.size(); ++k) hover.push_back({&frames[k], poses[k]});
  const auto det = detector();
  const auto r = det.detect(hover, cam);
  ASSERT_FALSE(r.zones.empty()) << r.reason;
  const LandingZoneDetector::Options& o = det.options_for_frames(hover.size());
  const double keep = o.footprint_radius_m + o.margin_m + o.min_clearance_m;
  for (const auto& z : r.zones)
    EXPECT_GE(rod_distance(z.center_m.head<2>()), keep - 0.01) << z.center_m.transpose();
}

// A hover's frames fused are judged in smaller cells with a smaller margin (half a
// cell): a corridor between two walls 1.72 m apart leaves 0.86 m on each side of its
// middle, short of one frame's footprint + margin + clearance + its cells' slack
// (0.49 + 0.05 + 0.30 m and up to a quarter cell) but enough for the hover's
// (0.49 + 0.025 + 0.30 m). Every zone found still keeps the footprint and its
// clearance off the walls.
TEST(LandingZone, AHoversFinerCellsFitADiscBetweenWallsThatOneFramesDoNot) {
  const auto cam = test_camera();
  const Pose3 X_WC = downward({0.0, 0.0, 3.0});
  const double half_width = 0.86;
  const HeightField corridor = [&](double x, double) {
    return std::abs(x) >= half_width ? 1.0 : 0.0;
  };
  std::vector<DepthImageMm> frames;
  for (std::uint64_t k = 0; k < 8; ++k)
    frames.push_back(render(cam, X_WC, corridor, 0.003, 31 + k));
  std::vector<PosedDepthFrame> hover;
  for (const auto& f : frames) hover.push_back({&f, X_WC});
  const auto det = detector();
  EXPECT_DOUBLE_EQ(det.options_for_frames(1).cell_size_m, 0.10);
  EXPECT_DOUBLE_EQ(det.options_for_frames(7).cell_size_m, 0.10);
  EXPECT_DOUBLE_EQ(det.options_for_frames(8).cell_size_m, 0.05);
  EXPECT_DOUBLE_EQ(det.options_for_frames(8).margin_m, 0.025);

  const auto one = det.detect(std::vector<PosedDepthFrame>{hover.front()}, cam);
  EXPECT_TRUE(one.zones.empty()) << one.zones.front().center_m.transpose();
  const auto fused = det.detect(hover, cam);
  ASSERT_FALSE(fused.zones.empty()) << fused.reason;
  const double keep = det.options().footprint_radius_m + det.options().min_clearance_m;
  for (const auto& z : fused.zones)
    EXPECT_LE(std::abs(z.center_m.x()), half_width - keep) << z.center_m.transpose();
  // Without the hover's cells the same fused frames give nothing either.
  LandingZoneDetector::Options same = det.options();
  same.hover_cell_size_m = 0.0;
  EXPECT_TRUE(LandingZoneDetector(same).detect(hover, cam).zones.empty());
}

// A block's corner that just reaches into the clearance ring covers only part of any
// half-size cell near it: a block 0.21 m tall must cover three quarters of a cell to
// lift its mean over the 0.15 m taller-than test, and the first cell it covers that
// much can lie a cell's diagonal beyond the corner (7 cm), more than the margin (5 cm).
// The clearance windows overlap by half, which halves that distance. Whatever the
// corner's place on the grid, no zone listed lets it within the footprint's clearance
// (0.49 + 0.30 m of the zone's centre).
TEST(LandingZone, ABlockCornerReachingIntoTheClearanceRingIsSeen) {
  const auto cam = test_camera();
  const auto det = detector();
  const double keep = det.options().footprint_radius_m + det.options().min_clearance_m;
  int zones = 0;
  for (int k = 0; k < 10; ++k) {
    const Pose3 X_WC = downward({0.0, 0.0, 3.0});
    // A square of 0.8 m side turned 45 degrees (a corner pointing at -x), moved over the
    // grid in steps of 1 cm.
    const Eigen::Vector2d centre(0.75 + 0.01 * k, 0.003 * k);
    const auto block_distance = [&](const Eigen::Vector2d& p) {
      const Eigen::Vector2d d = p - centre;
      const double u = (d.x() + d.y()) / std::sqrt(2.0), v = (d.y() - d.x()) / std::sqrt(2.0);
      const Eigen::Vector2d out(std::max(0.0, std::abs(u) - 0.4), std::max(0.0, std::abs(v) - 0.4));
      return out.norm();
    };
    const auto depth = render(
        cam, X_WC,
        [&](double x, double y) {
          return block_distance({x, y}) <= 0.0 ? 0.21 : 0.0;
        },
        0.003, 17 + k);
    const auto r = det.detect(depth, cam, X_WC);
    for (const auto& z : r.zones) {
      ++zones;
      EXPECT_GE(block_distance(z.center_m.head<2>()), keep)
          << "offset " << k << ": zone at " << z.center_m.head<2>().transpose();
    }
  }
  EXPECT_GT(zones, 0);  // the far side of the frame holds zones
}

TEST(LandingZone, NoReturnsMeansNoSafeZone) {
  const auto cam = test_camera();
  const DepthImageMm depth(cam.width_px, cam.height_px, 0);
  const auto r = detector().detect(depth, cam, downward({0, 0, 3}));
  EXPECT_TRUE(r.no_safe_zone);
  EXPECT_TRUE(r.zones.empty());
  EXPECT_NE(r.reason.find("no depth returns"), std::string::npos) << r.reason;
}

TEST(LandingZone, AHoleWithoutReturnsUnderTheCameraIsNotLandedIn) {
  // Unknown is not free: a patch without returns (a black or absorbing surface, or a
  // pit) must not be inside any zone.
  const auto cam = test_camera();
  // High enough that the view holds a footprint and its clearance ring beside the hole.
  const Pose3 X_WC = downward({0.0, 0.0, 4.5});
  auto depth = render(cam, X_WC, [](double, double) { return 0.0; });
  for (int v = 100; v < 140; ++v)
    for (int u = 140; u < 180; ++u) depth.at(u, v) = 0;  // about 0.7 m square at the centre
  const auto det = detector();
  const auto r = det.detect(depth, cam, X_WC);
  ASSERT_FALSE(r.zones.empty()) << r.reason;
  for (const auto& z : r.zones)
    EXPECT_GE(z.center_m.head<2>().cwiseAbs().maxCoeff(), det.options().footprint_radius_m + 0.2)
        << z.center_m.transpose();
}

TEST(LandingZone, OpeningReachIsRespected) {
  const auto cam = test_camera();
  const Pose3 X_WC = downward({0.0, 0.0, 3.0});
  const auto depth = render(
      cam, X_WC, [](double, double) { return 0.0; }, 0.003, 13);
  auto o = LandingZoneDetector::Options{};
  o.p_WE = Eigen::Vector3d(1.2, 0.4, 0.0);
  o.reach_m = 1.0;
  o.p_ZW_xy_m = {0.0, 0.04};  // the winch beside the body centre, as on the M100
  const LandingZoneDetector det(o);
  const auto r = det.detect(depth, cam, X_WC);
  ASSERT_FALSE(r.zones.empty()) << r.reason;
  for (const auto& z : r.zones) {
    const double d = (z.center_m.head<2>() + o.p_ZW_xy_m - o.p_WE->head<2>()).norm();
    EXPECT_LE(d, 1.0);
    EXPECT_NEAR(z.distance_to_opening_m, d, 1e-9);
  }
  // Ranked towards the opening: the best zone is the one nearest to it.
  for (const auto& z : r.zones)
    EXPECT_LE(r.zones.front().distance_to_opening_m, z.distance_to_opening_m + 1e-9);
  // An opening out of reach of anything in view: none, and the reason says so.
  o.p_WE = Eigen::Vector3d(8.0, 0.0, 0.0);
  const auto far = LandingZoneDetector(o).detect(depth, cam, X_WC);
  EXPECT_TRUE(far.no_safe_zone);
  EXPECT_NE(far.reason.find("out of reach"), std::string::npos) << far.reason;
}

TEST(LandingZone, OptionsFromTheM100Urdf) {
  const auto robot =
      load_robot_description(std::string(FERRET_SOURCE_DIR) + "/urdf/models/m100.urdf");
  MissionConfig mission;
  mission.tether.entry_offset_m = 1.7;
  const auto o = LandingZoneDetector::Options::for_robot(robot, &mission);
  // Rotor centres at 0.325 m on the diagonals plus the 0.1651 m propeller disc.
  EXPECT_NEAR(o.footprint_radius_m, 0.325 + 0.1651, 1e-6);
  EXPECT_DOUBLE_EQ(o.reach_m, 1.7);
  // The tether leaves 0.04 m to the side of the body centre (winch spool joint).
  EXPECT_NEAR(o.p_ZW_xy_m.y(), 0.04, 1e-9);
}

TEST(LandingZone, BadOptionsAndAFrameOfTheWrongSizeAreInputErrors) {
  auto o = LandingZoneDetector::Options{};
  o.cell_size_m = std::nan("");
  EXPECT_THROW(LandingZoneDetector{o}, InputError);
  o = {};
  o.max_depth_m = 0.1;  // below min_depth_m
  EXPECT_THROW(LandingZoneDetector{o}, InputError);
  // The hover's cells: a size (or 0), and a frame count within a hover's.
  for (const double cell_m : {-0.05, std::nan(""), 0.001, 5.0}) {
    o = {};
    o.hover_cell_size_m = cell_m;
    try {
      const LandingZoneDetector d{o};
      ADD_FAILURE() << "no error at " << cell_m;
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "hover_cell_size_m") << cell_m;
    }
  }
  for (const int frames : {0, kMaxHoverFrames + 1}) {
    o = {};
    o.hover_min_frames = frames;
    EXPECT_THROW(LandingZoneDetector{o}, InputError) << frames;
  }
  // The slope's, the step's and the taller-than's allowances: numbers in range, the
  // step's and the taller-than's under what they are allowances of.
  for (const auto& [field, set] : std::vector<std::pair<std::string, std::function<void(double)>>>{
           {"slope_sigmas", [&](double v) { o.slope_sigmas = v; }},
           {"slope_allowance_deg", [&](double v) { o.slope_allowance_deg = v; }},
           {"step_allowance_m", [&](double v) { o.step_allowance_m = v; }},
           {"taller_allowance_m", [&](double v) { o.taller_allowance_m = v; }}})
    for (const double v : {-0.1, std::nan(""), 1e6, 0.20}) {
      // 0.20: not under the step's 0.10 nor under the taller-than's 0.20.
      if (field.find("slope") != std::string::npos && v == 0.20) continue;  // in range there
      o = {};
      set(v);
      try {
        const LandingZoneDetector d{o};
        ADD_FAILURE() << "no error at " << field << " = " << v;
      } catch (const InputError& e) {
        EXPECT_EQ(e.field(), field) << v;
      }
    }
  o = {};
  o.hover_cell_size_m = 0.0;  // a hover in one frame's cells
  EXPECT_DOUBLE_EQ(LandingZoneDetector(o).options_for_frames(kMaxHoverFrames).cell_size_m, 0.10);
  const auto cam = test_camera();
  const DepthImageMm wrong(100, 100, 1000);
  try {
    (void)detector().detect(wrong, cam, downward({0, 0, 3}));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "size");
  }
  // Ground 9.9 m below a 65 degree camera spans 12.6 x 9.4 m: 1.2 million cells of
  // 1 cm and 0.3 million of 2 cm, more than a frame may (250,000: the clearance grid
  // would hold sixteen times as many).
  o = {};
  const DepthImageMm far(cam.width_px, cam.height_px, 9900);
  for (const double cell_m : {0.01, 0.02}) {
    o.cell_size_m = cell_m;
    try {
      (void)LandingZoneDetector(o).detect(far, cam, downward({0, 0, 10}));
      FAIL() << "no error at " << cell_m << " m";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "extent");
    }
  }
  // At 3 cm the same frame is 0.13 million cells: answered.
  o.cell_size_m = 0.03;
  EXPECT_NO_THROW((void)LandingZoneDetector(o).detect(far, cam, downward({0, 0, 10})));
}

TEST(FuseDepthFrames, FramesOfOnePoseAreAveragedPixelByPixel) {
  const auto cam = test_camera();
  const Pose3 X_WC = downward({0, 0, 3});
  DepthImageMm a(cam.width_px, cam.height_px, 1000), b(cam.width_px, cam.height_px, 1010);
  a.at(5, 7) = 0;  // no return in one frame: the other's
  a.at(9, 9) = 0;
  b.at(9, 9) = 0;  // in neither: none
  const DepthImageMm f = fuse_depth_frames({{&a, X_WC}, {&b, X_WC}}, cam);
  EXPECT_EQ(f.at(0, 0), 1005);
  EXPECT_EQ(f.at(cam.width_px - 1, cam.height_px - 1), 1005);
  EXPECT_EQ(f.at(5, 7), 1010);
  EXPECT_EQ(f.at(9, 9), 0);
  // One frame comes out as it went in (the command line fuses whatever it is given).
  EXPECT_EQ(fuse_depth_frames({{&a, X_WC}}, cam).data, a.data);
}

TEST(FuseDepthFrames, AFrameFromAnotherPoseIsReprojectedIntoTheFirst) {
  // Flat ground at z = 0: from 3 m every depth is 3000 mm, from 3.05 m 3050 mm. The
  // second frame, 0.1 m along x and 5 cm higher, re-projected into the first, says
  // 3000 mm wherever it lands (a pixel-by-pixel mean would say 3025), and fills a hole
  // the first frame has where it sees the ground. (Seen from higher up, its returns lie
  // a little farther apart than the first frame's pixels: 1.6 % of those get none.)
  const auto cam = test_camera();
  const Pose3 X_WA = downward({0, 0, 3}), X_WB = downward({0.1, 0, 3.05});
  DepthImageMm a(cam.width_px, cam.height_px, 3000);
  const DepthImageMm b(cam.width_px, cam.height_px, 3050);
  for (int v = 100; v < 140; ++v)
    for (int u = 140; u < 180; ++u) a.at(u, v) = 0;
  const DepthImageMm f = fuse_depth_frames({{&a, X_WA}, {&b, X_WB}}, cam);
  int filled = 0;
  for (int v = 0; v < cam.height_px; ++v)
    for (int u = 0; u < cam.width_px; ++u) {
      const bool hole = u >= 140 && u < 180 && v >= 100 && v < 140;
      if (hole && f.at(u, v) == 0) continue;
      ASSERT_NEAR(f.at(u, v), 3000, 1) << u << ", " << v;
      filled += hole;
    }
  EXPECT_GE(filled, 0.95 * 40 * 40);
}

// Eight frames of flat ground (z = 0) 3 m under a downward camera, each with its own
// seeded depth noise, and the same frames posed for fusion.
struct NoisyHover {
  CameraModel cam = test_camera();
  Pose3 X_WC = downward({0, 0, 3});
  std::vector<DepthImageMm> frames;
  std::vector<PosedDepthFrame> posed;
  NoisyHover(
      double noise_m, std::uint64_t seed, const HeightField& h = [](double, double) { return 0.0; },
      int n = 8) {
    for (std::uint64_t k = 0; k < static_cast<std::uint64_t>(n); ++k)
      frames.push_back(render(cam, X_WC, h, noise_m, seed + k));
    for (const auto& d : frames) posed.push_back({&d, X_WC});
  }
  NoisyHover(const NoisyHover&) = delete;  // posed points into frames
  NoisyHover& operator=(const NoisyHover&) = delete;
};

TEST(FuseDepthFrames, EightNoisyFramesHaveANoiseOfTheSquareRootOfEight) {
  const NoisyHover h(0.05, 100);
  const auto& [cam, X_WC, frames, posed] = h;
  const auto rms_mm = [&](const DepthImageMm& d) {
    double s = 0.0;
    for (const std::uint16_t mm : d.data) s += (mm - 3000.0) * (mm - 3000.0);
    return std::sqrt(s / static_cast<double>(d.data.size()));
  };
  EXPECT_NEAR(rms_mm(frames.front()), 50.0, 2.0);
  EXPECT_NEAR(rms_mm(fuse_depth_frames(posed, cam)), 50.0 / std::sqrt(8.0), 1.5);
}

TEST(FuseDepthFrames, NoisyFlatGroundRefusedInOneFrameIsAZoneInEightFused) {
  // sigma 0.15 m a pixel at 3 m (a D415 at its datasheet bound about 4 m away): one
  // frame's cell means differ by more than the step limit; eight frames' do not.
  const NoisyHover h(0.15, 200);
  const auto& [cam, X_WC, frames, posed] = h;
  const LandingResult one = detector().detect(frames.front(), cam, X_WC);
  EXPECT_TRUE(one.zones.empty()) << "best step " << one.zones.front().step_m;
  const LandingResult eight = detector().detect(posed, cam);
  ASSERT_FALSE(eight.zones.empty()) << eight.reason;
  EXPECT_NEAR(eight.zones.front().center_m.z(), 0.0, 0.02);
  EXPECT_LT(eight.zones.front().slope_deg, 2.0);
}

TEST(LandingZone, AHoverLandsOnASlopeThatOneFrameLeavesToItsAllowance) {
  // 14.4 degrees, under the M100's 15. One frame's 0.1 m cells keep a degree's
  // allowance (a step beyond the rim tilts their plane); a hover's half-size cells half
  // of it, and 8 frames fused leave the noise's three standard errors well under that.
  const double g = std::tan(deg_to_rad(14.4));
  const NoisyHover h(0.01, 300, [g](double x, double) { return g * x; });
  const LandingResult one = detector().detect(h.frames.front(), h.cam, h.X_WC);
  EXPECT_TRUE(one.zones.empty()) << one.zones.front().slope_deg;
  EXPECT_NE(one.reason.find("slope"), std::string::npos) << one.reason;
  const LandingZoneDetector det = detector();  // the options below are its own
  const auto& hover = det.options_for_frames(8);
  EXPECT_DOUBLE_EQ(hover.slope_allowance_deg, 0.5);
  EXPECT_DOUBLE_EQ(hover.step_allowance_m, 0.01);
  EXPECT_DOUBLE_EQ(hover.taller_allowance_m, 0.025);
  const LandingResult eight = det.detect(h.posed, h.cam);
  ASSERT_FALSE(eight.zones.empty()) << eight.reason;
  for (const auto& z : eight.zones) {
    EXPECT_NEAR(z.slope_deg, 14.4, 0.2);
    EXPECT_LT(3.0 * z.slope_sigma_deg, 0.5);
  }
  // And 14.6 degrees is refused by the hover too: 14.6 + 0.5 > 15.
  const double g2 = std::tan(deg_to_rad(14.6));
  const NoisyHover steeper(0.01, 300, [g2](double x, double) { return g2 * x; });
  EXPECT_TRUE(detector().detect(steeper.posed, steeper.cam).zones.empty());
}

TEST(LandingZone, AHoverThatFindsNothingLooksLongerAndFindsWhatTheNoiseHid) {
  // The frames a survey judges after a miss: twice as many, up to its most.
  EXPECT_EQ(hover_frames_after_miss(8, 32), 16);
  EXPECT_EQ(hover_frames_after_miss(16, 32), 32);
  EXPECT_EQ(hover_frames_after_miss(32, 32), 32);  // done
  EXPECT_EQ(hover_frames_after_miss(8, 12), 12);
  EXPECT_EQ(hover_frames_after_miss(8, 8), 8);
  EXPECT_EQ(hover_frames_after_miss(40, 32), 40);  // already past it
  // Flat ground 3 m below, 0.2 m of noise a pixel: in 8 frames fused the cells' noise
  // alone makes a step over the hover's 0.09 m everywhere; in 16 it is under it (the
  // step's noise falls as 1/sqrt(frames): 0.045, 0.035, 0.025 m at 0.1 m a pixel).
  const NoisyHover h(
      0.2, 500, [](double, double) { return 0.0; }, 16);
  const LandingZoneDetector det = detector();
  int taken = 8;
  LandingResult r = det.detect({h.posed.begin(), h.posed.begin() + taken}, h.cam);
  EXPECT_TRUE(r.zones.empty());
  EXPECT_NE(r.reason.find("step"), std::string::npos) << r.reason;
  while (r.zones.empty() && hover_frames_after_miss(taken, 16) > taken) {
    taken = hover_frames_after_miss(taken, 16);
    r = det.detect({h.posed.begin(), h.posed.begin() + taken}, h.cam);
  }
  EXPECT_EQ(taken, 16);
  ASSERT_FALSE(r.zones.empty()) << r.reason;
  EXPECT_LT(r.zones.front().step_m, 0.09);
  EXPECT_LT(r.zones.front().slope_deg, 1.0);
}

TEST(LandingZone, ASlopesStandardErrorIsTheSpreadOfItsFitFromFrameToFrame) {
  // One frame of a 10 degree slope with 5 cm of noise a pixel, 24 times: the slope
  // fitted at a fixed place scatters by what slope_sigma_deg says (the tests that
  // would refuse it switched off, so every candidate is listed).
  auto o = LandingZoneDetector::Options{};
  o.slope_sigmas = 0.0;
  o.slope_allowance_deg = 0.0;
  o.max_step_m = 5.0;
  o.max_roughness_m = 5.0;
  o.taller_than_m = 5.0;
  o.max_zones = 10000;
  const LandingZoneDetector det(o);
  const auto cam = test_camera();
  const Pose3 X_WC = downward({0.0, 0.0, 3.0});
  const double g = std::tan(deg_to_rad(10.0));
  const Eigen::Vector2d at(0.3, -0.2);
  std::vector<double> slopes, sigmas;
  for (std::uint64_t seed = 1; seed <= 24; ++seed) {
    const auto depth = render(
        cam, X_WC, [g](double x, double) { return g * x; }, 0.05, 1000 + seed, 2.5);
    const LandingResult r = det.detect(depth, cam, X_WC);
    ASSERT_FALSE(r.zones.empty()) << r.reason;
    const auto nearest = std::min_element(r.zones.begin(), r.zones.end(), [&](auto& a, auto& b) {
      return (a.center_m.template head<2>() - at).norm() <
             (b.center_m.template head<2>() - at).norm();
    });
    ASSERT_LT((nearest->center_m.head<2>() - at).norm(), 0.5);
    slopes.push_back(nearest->slope_deg);
    sigmas.push_back(nearest->slope_sigma_deg);
  }
  const double n = static_cast<double>(slopes.size());
  double mean = 0.0, mean_sigma = 0.0;
  for (std::size_t k = 0; k < slopes.size(); ++k) {
    mean += slopes[k] / n;
    mean_sigma += sigmas[k] / n;
  }
  double var = 0.0;
  for (const double s : slopes) var += (s - mean) * (s - mean) / (n - 1.0);
  EXPECT_NEAR(mean, 10.0, 0.3);
  EXPECT_GT(mean_sigma, 0.02);  // not the noise-free fit's 0
  EXPECT_GT(std::sqrt(var) / mean_sigma, 0.6) << std::sqrt(var) << " against " << mean_sigma;
  EXPECT_LT(std::sqrt(var) / mean_sigma, 1.6) << std::sqrt(var) << " against " << mean_sigma;
  // Without noise the fit is exact and claims so.
  const auto clean = render(
      cam, X_WC, [g](double x, double) { return g * x; }, 0.0, 1, 2.5);
  const LandingResult r = det.detect(clean, cam, X_WC);
  ASSERT_FALSE(r.zones.empty());
  EXPECT_LT(r.zones.front().slope_sigma_deg, 0.02);
}

TEST(DepthFrameFusion, FusedAsTheyComeIsFuseDepthFramesBitForBitAndJudgedTheSame) {
  // A drifting hover's noisy frames over a slope with a low wall: fused a frame at a time
  // (the survey), then judged after 8 and 16, as fuse_depth_frames of all of them at once.
  const auto cam = test_camera();
  const HeightField ground = [](double x, double y) { return 0.1 * x + (y > 0.6 ? 0.3 : 0.0); };
  std::vector<DepthImageMm> frames;
  std::vector<PosedDepthFrame> posed;
  for (int k = 0; k < 16; ++k)
    frames.push_back(render(cam, downward({0.01 * k, -0.006 * k, 3.0 + 0.003 * k}), ground, 0.08,
                            300 + static_cast<std::uint64_t>(k)));
  for (int k = 0; k < 16; ++k)
    posed.push_back({&frames[k], downward({0.01 * k, -0.006 * k, 3.0 + 0.003 * k})});
  DepthFrameFusion fusion(cam);
  for (int k = 0; k < 16; ++k) {
    fusion.add(*posed[k].depth, posed[k].X_WC);
    EXPECT_EQ(fusion.frames(), static_cast<std::size_t>(k + 1));
    if (k + 1 != 8 && k + 1 != 16) continue;
    const std::vector<PosedDepthFrame> first(posed.begin(), posed.begin() + k + 1);
    EXPECT_EQ(fusion.fused().data, fuse_depth_frames(first, cam).data) << k + 1 << " frames";
    EXPECT_TRUE(fusion.X_WC().isApprox(posed.front().X_WC));
    const LandingResult at_once = detector().detect(first, cam);
    const LandingResult as_they_came = detector().detect(fusion);
    ASSERT_FALSE(at_once.zones.empty()) << at_once.reason;  // the slope's lower part is a zone
    ASSERT_EQ(as_they_came.zones.size(), at_once.zones.size()) << k + 1 << " frames";
    for (std::size_t i = 0; i < at_once.zones.size(); ++i)
      EXPECT_EQ(as_they_came.zones[i].center_m, at_once.zones[i].center_m);
    EXPECT_EQ(as_they_came.reason, at_once.reason);
  }
  // Cleared, the next frame starts a new hover at its own pose.
  fusion.clear();
  EXPECT_EQ(fusion.frames(), 0u);
  fusion.add(frames[5], posed[5].X_WC);
  EXPECT_EQ(fusion.fused().data, frames[5].data);
  EXPECT_TRUE(fusion.X_WC().isApprox(posed[5].X_WC));
  // A frame of another size is refused and not counted; nothing fused is an error.
  const auto field = [](const auto& call) {
    try {
      call();
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("no error");
  };
  EXPECT_EQ(field([&] { fusion.add(DepthImageMm(100, 100, 3000), posed[0].X_WC); }), "size");
  EXPECT_EQ(fusion.frames(), 1u);
  EXPECT_EQ(field([&] { (void)DepthFrameFusion(cam).fused(); }), "count");
  EXPECT_THROW((void)detector().detect(DepthFrameFusion(cam)), InputError);
}

TEST(FuseDepthFrames, NoFramesANullFrameAndAFrameOfAnotherSizeAreInputErrors) {
  const auto cam = test_camera();
  const Pose3 X_WC = downward({0, 0, 3});
  const DepthImageMm ok(cam.width_px, cam.height_px, 3000), wrong(100, 100, 3000);
  const auto field = [&](const std::vector<PosedDepthFrame>& frames) {
    try {
      (void)fuse_depth_frames(frames, cam);
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("no error");
  };
  EXPECT_EQ(field({}), "count");
  EXPECT_EQ(field({{&ok, X_WC}, {nullptr, X_WC}}), "depth");
  EXPECT_EQ(field({{&ok, X_WC}, {&wrong, X_WC}}), "size");
  EXPECT_THROW((void)detector().detect(std::vector<PosedDepthFrame>{}, cam), InputError);
}

// The PX4 rule on a hand-checked case: a 0.3 m step at x = 1.0 m, on a cell boundary of
// its grid (centred on the vehicle at x = 1, y = 2: boundaries every 0.25 m from -4).
// A cell next to the step sees 5 of the 11 columns of its 11 x 11 neighbourhood on the
// other side: 55 cells differ by more than 0.1 m, within the 70 allowed, and all 121
// are landable (flat, > 100 points): the rule keeps it. The vehicle is above the step,
// so the rule's choice, the kept cell nearest to it, is a cell centre 0.125 m from a
// 0.3 m step; ferret's detector keeps a footprint away from it.
TEST(Px4LandingBaseline, KeepsCellsNextToAStepAsPublished) {
  const auto cam = test_camera();
  const Eigen::Vector3d p_WV(1.0, 2.0, 5.0);
  const Pose3 X_WC = downward(p_WV);
  const auto depth = render(cam, X_WC, [](double x, double) { return x >= 1.0 ? 0.3 : 0.0; });
  const Px4LandingBaseline px4(Px4LandingBaseline::Options{});
  const auto r = px4.detect(depth, cam, X_WC, p_WV);
  ASSERT_FALSE(r.zones.empty()) << r.reason;
  const auto& best = r.zones.front();
  EXPECT_NEAR(std::abs(best.center_m.x() - 1.0), 0.125, 1e-9);
  EXPECT_NEAR(std::abs(best.center_m.y() - 2.0), 0.125, 1e-9);
  EXPECT_NEAR(best.center_m.z(), best.center_m.x() > 1.0 ? 0.3 : 0.0, 1e-3);
  // On the same frame ferret's detector keeps every zone a footprint from the step.
  const auto ours = detector().detect(depth, cam, X_WC);
  for (const auto& z : ours.zones) EXPECT_GE(std::abs(z.center_m.x() - 1.0), 0.49);
}

// The original's temporal low-pass over a hover's frames: the ground 3 m below in the
// first frame and 2.5 m below in the second (it rose 0.5 m). With alpha 0.9 of
// history the cells' mean is 0.9 * 0 + 0.1 * 0.5 = 0.05 m; with alpha 0, the last
// frame's 0.5 m.
TEST(Px4LandingBaseline, AHoversFramesGoThroughTheOriginalsLowPass) {
  const auto cam = test_camera();
  const Eigen::Vector3d p_WV(0.0, 0.0, 3.0);
  const Pose3 X_WC = downward(p_WV);
  const DepthImageMm low(cam.width_px, cam.height_px, 3000),
      high(cam.width_px, cam.height_px, 2500);
  const std::vector<PosedDepthFrame> hover{{&low, X_WC}, {&high, X_WC}};
  Px4LandingBaseline::Options o;
  const auto r = Px4LandingBaseline(o).detect(hover, cam, p_WV);
  ASSERT_FALSE(r.zones.empty()) << r.reason;
  EXPECT_NEAR(r.zones.front().center_m.z(), 0.05, 1e-6);
  o.alpha = 0.0;
  const auto last = Px4LandingBaseline(o).detect(hover, cam, p_WV);
  ASSERT_FALSE(last.zones.empty()) << last.reason;
  EXPECT_NEAR(last.zones.front().center_m.z(), 0.5, 1e-6);
  EXPECT_THROW((void)Px4LandingBaseline(o).detect(std::vector<PosedDepthFrame>{}, cam, p_WV),
               InputError);
}

TEST(Px4LandingBaseline, RejectsANoisyCellAboveTheStandardDeviationLimit) {
  // sigma 0.25 m > 0.2 m: no cell is landable, so no neighbourhood has > 70 of them.
  const auto cam = test_camera();
  const Eigen::Vector3d p_WV(0.0, 0.0, 5.0);
  const Pose3 X_WC = downward(p_WV);
  const auto depth = render(
      cam, X_WC, [](double, double) { return 0.0; }, 0.25, 17);
  const auto r = Px4LandingBaseline(Px4LandingBaseline::Options{}).detect(depth, cam, X_WC, p_WV);
  EXPECT_TRUE(r.no_safe_zone);
}

}  // namespace
}  // namespace ferret
