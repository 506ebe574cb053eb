#include "ferret/sim/hidden_space_sim.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/test_maps.hpp"

namespace ferret {
namespace {

OccupancyMap2D room() { return test::room_with_partition(); }

TEST(HiddenSpaceSim, IrBeamsReturnAtTheWall) {
  const auto map = room();
  SensorOptions o;
  o.ir_dropout = 0.0;
  HiddenSpaceSim sim(map, {3.5, 2.5}, o, 7);
  const RangeScan scan = sim.ir_scan({1.025, 1.0, 0.0});  // wall face at x = 2.5
  // Enough beams to touch every cell at 4 m across 30 degrees.
  EXPECT_EQ(scan.beams.size(),
            static_cast<std::size_t>(std::ceil(deg_to_rad(30) * 4.0 / 0.05)) + 1);
  const auto& mid = scan.beams[scan.beams.size() / 2];
  EXPECT_NEAR(mid.bearing_rad, 0.0, 1e-9);
  EXPECT_NEAR(mid.range_m, 1.475, 0.05);
  EXPECT_NEAR(sim.cast(Eigen::Vector2d(1.025, 2.0), 0.0, 4.0), 2.925,
              1e-9);  // above the wall segment: far wall
}

TEST(HiddenSpaceSim, DetectsTheObjectInViewWithDistanceFromApparentSize) {
  const auto map = room();
  SensorOptions o;
  o.detection_probability = 1.0;
  HiddenSpaceSim sim(map, {3.0, 2.0}, o, 3);
  EXPECT_NEAR(sim.focal_length_px(), 320.0, 1e-9);  // 640 px over 90 degrees
  const auto frame = sim.camera_frame({1.0, 2.0, 0.0}, 0.0);
  ASSERT_EQ(frame.detections.size(), 1u);
  const auto& d = frame.detections[0];
  // 0.2 m at 2 m is 32 px; half a pixel of noise is about 3 cm of distance.
  EXPECT_NEAR(d.distance_m, 2.0, 0.1);
  EXPECT_NEAR(d.bearing_rad, 0.0, 0.02);
  EXPECT_NEAR(d.confidence, 1.0 / d.distance_m, 0.08);
  EXPECT_EQ(frame.view.max_range_m, 4.0);
  EXPECT_FALSE(frame.view.beams.empty());
}

TEST(HiddenSpaceSim, NoDetectionBehindWallsOutsideTheFovOrBeyondRange) {
  const auto map = room();
  SensorOptions o;
  o.detection_probability = 1.0;
  HiddenSpaceSim behind(map, {3.0, 0.75}, o, 1);
  EXPECT_TRUE(
      behind.camera_frame({1.0, 0.75, 0.0}, 0.0).detections.empty());  // the wall at x = 2.5
  HiddenSpaceSim side(map, {1.0, 2.5}, o, 1);
  EXPECT_TRUE(
      side.camera_frame({1.0, 1.0, 0.0}, 0.0).detections.empty());  // 90 degrees off the axis
  o.camera_range_m = 1.5;
  HiddenSpaceSim far(map, {3.0, 2.0}, o, 1);
  EXPECT_TRUE(far.camera_frame({1.0, 2.0, 0.0}, 0.0).detections.empty());
}

TEST(HiddenSpaceSim, SameSeedSameMeasurements) {
  const auto map = room();
  HiddenSpaceSim a(map, {3.0, 2.0}, {}, 11), b(map, {3.0, 2.0}, {}, 11), c(map, {3.0, 2.0}, {}, 12);
  const Pose2 pose{1.0, 2.0, 0.1};
  const auto sa = a.ir_scan(pose), sb = b.ir_scan(pose), sc = c.ir_scan(pose);
  ASSERT_EQ(sa.beams.size(), sb.beams.size());
  bool differs = sa.beams.size() != sc.beams.size();
  for (std::size_t k = 0; k < sa.beams.size(); ++k) {
    EXPECT_EQ(sa.beams[k].range_m, sb.beams[k].range_m);
    if (k < sc.beams.size()) differs = differs || sa.beams[k].range_m != sc.beams[k].range_m;
  }
  EXPECT_TRUE(differs);
  const auto fa = a.camera_frame(pose, 0.0), fb = b.camera_frame(pose, 0.0);
  ASSERT_EQ(fa.detections.size(), fb.detections.size());
  if (!fa.detections.empty()) {
    EXPECT_EQ(fa.detections[0].distance_m, fb.detections[0].distance_m);
  }
}

}  // namespace
}  // namespace ferret
