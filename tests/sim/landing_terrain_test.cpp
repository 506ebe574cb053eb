// The landing terrains and their geometric ground truth.
#include "ferret/sim/landing_terrain.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "ferret/uav/landing_zone.hpp"
#include "ferret/urdf/robot_description.hpp"

namespace ferret {
namespace {

WorldSpec world_from(const std::string& body) {
  return parse_world("resolution_m: 0.05\nbounds_m: {min: [-5, -5, -3], max: [5, 5, 5]}\n" + body,
                     "test");
}

TEST(LandingTerrain, SameSeedAndIndexGiveTheSameWorld) {
  const auto a = landing_terrain(7, 3), b = landing_terrain(7, 3), c = landing_terrain(7, 4);
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.slope_deg, b.slope_deg);
  ASSERT_EQ(a.world.solid_boxes().size(), b.world.solid_boxes().size());
  for (std::size_t k = 0; k < a.world.solid_boxes().size(); ++k)
    EXPECT_EQ(a.world.solid_boxes()[k].center_m, b.world.solid_boxes()[k].center_m);
  EXPECT_NE(a.slope_deg, c.slope_deg);
}

TEST(LandingTerrain, TwoHundredTerrainsCoverTheSlopesAndEveryKind) {
  double lo = 90, hi = 0;
  int rubble = 0, steps = 0, walls = 0, poles = 0;
  for (int i = 0; i < 200; ++i) {
    const auto t = landing_terrain(1, i);
    lo = std::min(lo, t.slope_deg);
    hi = std::max(hi, t.slope_deg);
    ASSERT_EQ(t.world.hidden_spaces.size(), 1u);
    // The opening faces the middle of the site and lies within 4.5 m of it.
    const auto& h = t.world.hidden_spaces[0];
    EXPECT_LT(h.p_WE.head<2>().norm(), 4.5);
    rubble += t.kind.find("rubble") != std::string::npos;
    steps += t.kind.find("steps") != std::string::npos;
    walls += t.kind.find("walls") != std::string::npos;
    poles += t.kind.find("poles") != std::string::npos;
    // The terrain's ground slope is the one it reports.
    EXPECT_NEAR(rad_to_deg(std::atan(std::hypot(t.world.ground.slope_x, t.world.ground.slope_y))),
                t.slope_deg, 1e-3);
  }
  EXPECT_LT(lo, 2.0);
  EXPECT_GT(hi, 23.0);
  EXPECT_GT(rubble, 50);
  EXPECT_GT(steps, 50);
  EXPECT_GT(walls, 40);
  EXPECT_GT(poles, 40);
}

TEST(TerrainGroundTruth, FlatGroundIsSafeAndSlopesBeyondTheLimitAreNot) {
  const LandingCriteria crit;
  const TerrainGroundTruth flat(world_from("ground: {height_m: 0.5}\n"));
  EXPECT_NEAR(flat.surface_height(1.0, 1.0), 0.5, 1e-6);
  EXPECT_TRUE(flat.is_safe({0, 0}, 0.49, crit));
  // Near the world's edge the disc and its clearance leave the world: not safe.
  EXPECT_FALSE(flat.is_safe({4.6, 0}, 0.49, crit));
  const double g10 = std::tan(deg_to_rad(10.0)), g20 = std::tan(deg_to_rad(20.0));
  const TerrainGroundTruth s10(world_from(fmt::format("ground: {{slope: [{}, 0]}}\n", g10)));
  const TerrainGroundTruth s20(world_from(fmt::format("ground: {{slope: [0, {}]}}\n", g20)));
  EXPECT_TRUE(s10.is_safe({0, 0}, 0.49, crit));
  EXPECT_FALSE(s20.is_safe({0, 0}, 0.49, crit));
}

TEST(TerrainGroundTruth, StepsAndPolesAreJudgedByTheirDistance) {
  const LandingCriteria crit;  // step 0.10 m, clearance 0.30 m of things 0.20 m taller
  // A 0.3 m platform whose edge is at x = 1.
  const TerrainGroundTruth step(
      world_from("boxes:\n  - {center_m: [3, 0], size_m: [4, 6, 0.3]}\n"));
  EXPECT_NEAR(step.surface_height(1.5, 0), 0.3, 1e-6);
  EXPECT_FALSE(step.is_safe({0.7, 0}, 0.49, crit));  // the disc crosses the edge
  EXPECT_FALSE(step.is_safe({0.3, 0}, 0.49, crit));  // the platform within the clearance ring
  EXPECT_TRUE(step.is_safe({0.1, 0}, 0.49, crit));   // 0.9 m away: 0.49 + 0.3 + a cell
  EXPECT_TRUE(step.is_safe({1.9, 0}, 0.49, crit));   // on the platform, away from its edge
  // A low (0.05 m) plate inside the disc is within the step limit.
  const TerrainGroundTruth low(
      world_from("boxes:\n  - {center_m: [0.2, 0], size_m: [0.4, 0.4, 0.05]}\n"));
  EXPECT_TRUE(low.is_safe({0, 0}, 0.49, crit));
  // A pole of radius 0.2 m: its surface must stay 0.49 + 0.30 m from the centre.
  const TerrainGroundTruth pole(
      world_from("cylinders:\n  - {center_m: [0, 0], radius_m: 0.2, height_m: 2}\n"));
  EXPECT_FALSE(pole.is_safe({0.9, 0}, 0.49, crit));
  EXPECT_TRUE(pole.is_safe({1.1, 0}, 0.49, crit));
}

TEST(TerrainGroundTruth, InViewNeedsTheImageAndAClearLineOfSight) {
  const auto cam = CameraModel::from_fov("d", 320, 240, deg_to_rad(65.0));
  Pose3 X_WC;
  X_WC.linear() << 1, 0, 0, 0, -1, 0, 0, 0, -1;
  X_WC.translation() = Eigen::Vector3d(0, 0, 3);
  const TerrainGroundTruth open(world_from(""));
  EXPECT_TRUE(open.in_view({0, 0}, 0.9, cam, X_WC));
  EXPECT_FALSE(open.in_view({1.2, 0}, 0.9, cam, X_WC));  // half-width of the view is 1.9 m
  // A 2.5 m wall between the camera and the disc's far side hides part of it.
  const TerrainGroundTruth wall(
      world_from("boxes:\n  - {center_m: [0.5, 0], size_m: [0.3, 4, 2.5]}\n"));
  EXPECT_FALSE(wall.in_view({1.0, 0}, 0.5, cam, X_WC));
  EXPECT_TRUE(open.safe_zone_in_view(0.49, 0.89, LandingCriteria{}, cam, X_WC));
}

// The evaluation in small (the bench runs 200 terrains): on 20 seeded terrains seen
// from the M100's depth camera at 640 x 480, ferret's chosen zone is never unsafe by
// the ground truth, and the PX4 rule on the same frames chooses unsafe zones.
// The bench's set-up: the M100's depth camera at 640 x 480, its detector options, and
// the scenes' options to match (the view the detector needs round a zone).
struct Evaluation {
  RobotDescription robot =
      load_robot_description(std::string(FERRET_SOURCE_DIR) + "/urdf/models/m100.urdf");
  CameraSensor sensor = robot.depth_camera();
  CameraModel cam = CameraModel::from_fov(sensor.name, 640, 480, sensor.horizontal_fov_rad);
  LandingZoneDetector::Options o = LandingZoneDetector::Options::for_robot(robot);
  LandingSceneOptions so = [this] {
    LandingSceneOptions s;
    s.footprint_radius_m = o.footprint_radius_m;
    s.view_radius_m =
        o.footprint_radius_m + o.margin_m + o.min_clearance_m + o.cell_size_m * std::sqrt(2.0);
    return s;
  }();
};

TEST(LandingEvaluation, TwentyTerrainsNoUnsafeChoiceAndFewerThanThePx4Rule) {
  const Evaluation e;
  const auto& [robot, sensor, cam, o, so] = e;
  const LandingZoneDetector det(o);
  const Px4LandingBaseline px4(Px4LandingBaseline::Options{});
  int ours_unsafe = 0, px4_unsafe = 0, ours_found = 0, exists = 0;
  for (int i = 0; i < 20; ++i) {
    const auto scene = landing_scene(5, i, sensor, cam, so);
    for (const auto& f : scene.frames) {
      exists += f.safe_zone_in_view;
      const auto a = det.detect(f.depth, cam, f.X_WC);
      if (!a.zones.empty()) {
        ours_found += f.safe_zone_in_view;
        ours_unsafe +=
            !scene.truth.is_safe(a.zones[0].center_m.head<2>(), so.footprint_radius_m, so.criteria);
      }
      const auto b = px4.detect(f.depth, cam, f.X_WC, f.X_WB.translation());
      if (!b.zones.empty())
        px4_unsafe +=
            !scene.truth.is_safe(b.zones[0].center_m.head<2>(), so.footprint_radius_m, so.criteria);
    }
  }
  EXPECT_EQ(ours_unsafe, 0);
  EXPECT_GT(px4_unsafe, ours_unsafe);
  // Where the truth sees a safe zone, ferret finds one in most frames (the bench
  // reports the rate; a conservative detector may miss a marginal one).
  EXPECT_GT(exists, 5);
  EXPECT_GT(ours_found, exists / 2);
}

// Two frames of the evaluation's family that once went wrong. Terrain 77 of seed 1 has
// a 2.45 m pole beside its view centre: flown at 2 m the UAV would be inside it (its
// camera within the pole's radius sees nothing of it), so that frame is not made.
// Terrain 113 of seed 1, rendered without depth noise: a rubble corner at the edge of
// the truth's clearance ring at 3 m (0.789 m of 0.79) covered too little of any
// half-size cell to lift its mean over the taller-than test; ferret chose that zone.
// The frames' noise had hidden it (it inflates the step test, so the zone fell on the
// step).
TEST(LandingEvaluation, TheUavIsNotFlownInsideAPoleAndACornerInTheRingIsSeenWithoutNoise) {
  Evaluation e;
  e.so.depth.noise_coefficient_per_m = 0.0;
  const auto& [robot, sensor, cam, o, so] = e;

  const auto poles = landing_scene(1, 77, sensor, cam, so);
  ASSERT_EQ(poles.frames.size(), 2u);
  EXPECT_EQ(poles.frames[0].height_m, 3.0);
  EXPECT_GT(
      poles.truth.highest_within(poles.terrain.view_center_m, so.footprint_radius_m),
      poles.truth.surface_height(poles.terrain.view_center_m.x(), poles.terrain.view_center_m.y()) +
          2.0 - so.hover_clearance_m);

  // (All three heights: each frame's pose takes the random draws in turn.)
  const auto corner = landing_scene(1, 113, sensor, cam, so);
  ASSERT_EQ(corner.frames.size(), 3u);
  const auto& f = corner.frames[1];
  ASSERT_EQ(f.height_m, 3.0);
  const auto r = LandingZoneDetector(o).detect(f.depth, cam, f.X_WC);
  for (const auto& z : r.zones)
    EXPECT_TRUE(corner.truth.is_safe(z.center_m.head<2>(), so.footprint_radius_m, so.criteria))
        << z.center_m.transpose();
}

// At the M100's own depth resolution (1280 x 720, the URDF's), terrain 36 of seed 1 at
// 3 m: a rubble block 0.105 m high, 1 cm from the footprint's rim, covered the cells the
// rim cuts only in part and measured 0.066 m (under the 0.08 m step limit); ferret
// chose that zone. The step test's overlapping windows hold it whole.
TEST(LandingEvaluation, ABlockAtTheFootprintsRimIsSeenAtTheUrdfsResolution) {
  Evaluation e;
  e.cam = CameraModel::from_fov(e.sensor.name, 1280, 720, e.sensor.horizontal_fov_rad);
  const auto& [robot, sensor, cam, o, so] = e;
  const auto scene = landing_scene(1, 36, sensor, cam, so);
  ASSERT_EQ(scene.frames.size(), 3u);
  const auto& f = scene.frames[1];
  ASSERT_EQ(f.height_m, 3.0);
  const auto r = LandingZoneDetector(o).detect(f.depth, cam, f.X_WC);
  // (Now it finds none in this frame; any zone it lists must be safe.)
  for (const auto& z : r.zones) {
    EXPECT_TRUE(scene.truth.is_safe(z.center_m.head<2>(), so.footprint_radius_m, so.criteria))
        << z.center_m.transpose();
  }
}

// A hover's further frames: drawn apart from the first, so the first frame is the same
// bytes whatever frames_per_view is; each from a pose within the drift's bounds, with
// noise of its own.
TEST(LandingTerrain, AHoversFurtherFramesDriftWithinBoundsAndLeaveTheFirstAsItWas) {
  Evaluation e;
  e.cam = CameraModel::from_fov(e.sensor.name, 160, 120, e.sensor.horizontal_fov_rad);
  const auto& [robot, sensor, cam, o, so] = e;
  LandingSceneOptions three = so;
  three.frames_per_view = 3;
  const auto a = landing_scene(5, 4, sensor, cam, so), b = landing_scene(5, 4, sensor, cam, three);
  ASSERT_EQ(a.frames.size(), b.frames.size());
  for (std::size_t k = 0; k < a.frames.size(); ++k) {
    const LandingFrame &fa = a.frames[k], &fb = b.frames[k];
    EXPECT_EQ(fa.depth.data, fb.depth.data);
    EXPECT_TRUE(fa.X_WC.isApprox(fb.X_WC));
    EXPECT_TRUE(fa.more_depth.empty());
    ASSERT_EQ(fb.more_depth.size(), 2u);
    ASSERT_EQ(fb.more_X_WC.size(), 2u);
    for (std::size_t m = 0; m < 2; ++m) {
      EXPECT_NE(fb.more_depth[m].data, fb.depth.data);
      // The base moves by up to 3 cm an axis and turns by up to 0.5 degrees an axis; the
      // camera, 0.1-0.2 m from the base, moves with the turn by under 2 mm more.
      const Eigen::Vector3d d = fb.more_X_WC[m].translation() - fb.X_WC.translation();
      EXPECT_LE(d.cwiseAbs().maxCoeff(), three.hover_drift_m + 0.002) << d.transpose();
      EXPECT_GT(d.norm(), 1e-4);
      const double turn =
          Eigen::AngleAxisd(fb.X_WC.linear().transpose() * fb.more_X_WC[m].linear()).angle();
      EXPECT_LE(turn, std::sqrt(3.0) * three.hover_drift_rad + 1e-9);
    }
  }
}

// Terrain 18 of seed 5 (a 1.3 degree slope with steps and walls): in one frame at 3 m
// the D415's noise lifts the step test over its limit everywhere the truth sees a safe
// zone; the hover's eight frames fused find one, and every zone they list is safe.
TEST(LandingEvaluation, EightFramesOfAHoverFindAZoneOneFrameMissesAndOnlySafeOnes) {
  Evaluation e;
  e.so.frames_per_view = 8;
  const auto& [robot, sensor, cam, o, so] = e;
  const auto scene = landing_scene(5, 18, sensor, cam, so);
  ASSERT_EQ(scene.frames.size(), 3u);
  const auto& f = scene.frames[1];
  ASSERT_EQ(f.height_m, 3.0);
  ASSERT_TRUE(f.safe_zone_in_view);
  const LandingZoneDetector det(o);
  EXPECT_TRUE(det.detect(f.depth, cam, f.X_WC).zones.empty());
  std::vector<PosedDepthFrame> hover{{&f.depth, f.X_WC}};
  for (std::size_t m = 0; m < f.more_depth.size(); ++m)
    hover.push_back({&f.more_depth[m], f.more_X_WC[m]});
  const LandingResult r = det.detect(hover, cam);
  ASSERT_FALSE(r.zones.empty()) << r.reason;
  for (const auto& z : r.zones)
    EXPECT_TRUE(scene.truth.is_safe(z.center_m.head<2>(), so.footprint_radius_m, so.criteria))
        << z.center_m.transpose();
}

}  // namespace
}  // namespace ferret
