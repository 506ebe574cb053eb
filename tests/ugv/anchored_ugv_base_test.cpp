#include "ferret/ugv/anchored_ugv_base.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace ferret::ugv {
namespace {

constexpr double kPi = std::numbers::pi;

// Odometry and sensor poses a test sets; commands recorded.
class ScriptedBase final : public UgvBase {
 public:
  std::string backend() const override { return "hw"; }
  Pose2 odometry() const override { return pose; }
  double speed_mps() const override { return 0.2; }
  RangeScan ir_scan() override {
    RangeScan s;
    s.X_WS = pose;
    s.max_range_m = 0.8;
    s.beams = {{0.25, 0.5}};
    return s;
  }
  CameraFrame camera_frame(double time_s) override {
    CameraFrame f;
    f.time_s = time_s;
    f.view = ir_scan();
    f.detections = {{0.1, 1.5, 0.6}};
    return f;
  }
  void command_velocity(double v, double w) override {
    v_mps = v;
    w_radps = w;
  }
  void set_epm(bool on) override { epm = on; }
  UgvStatus status() const override { return {0.5, epm, false, 0u}; }

  Pose2 pose;
  double v_mps = 0.0, w_radps = 0.0;
  bool epm = false;
};

void expect_pose(const Pose2& actual, const Pose2& expected) {
  EXPECT_NEAR(actual.x_m, expected.x_m, 1e-12);
  EXPECT_NEAR(actual.y_m, expected.y_m, 1e-12);
  EXPECT_NEAR(wrap_angle_rad(actual.yaw_rad - expected.yaw_rad), 0.0, 1e-12);
}

TEST(AnchoredUgvBase, InverseComposesToTheIdentity) {
  const Pose2 X{1.5, -2.0, 2.5};
  expect_pose(X * inverse(X), {});
  expect_pose(inverse(X) * X, {});
  // By hand: facing +y at (1, 0), the origin lies 1 m to its left, facing its right.
  expect_pose(inverse(Pose2{1.0, 0.0, kPi / 2}), {0.0, 1.0, -kPi / 2});
}

TEST(AnchoredUgvBase, BeforeAnAnchorItReadsAsTheBase) {
  ScriptedBase base;
  base.pose = {0.3, 0.4, 0.5};
  AnchoredUgvBase anchored(base);
  expect_pose(anchored.odometry(), base.pose);
  EXPECT_EQ(anchored.backend(), "hw");
}

TEST(AnchoredUgvBase, TheAnchoredPoseAndTheDriveSinceAreInTheEntrysFrame) {
  ScriptedBase base;
  base.pose = {2.0, 1.0, kPi / 2};  // odometry: facing +y at (2, 1)
  AnchoredUgvBase anchored(base);
  const Pose2 entry{10.0, 20.0, kPi};  // the UAV's world: facing -x at (10, 20)
  anchored.anchor(entry);
  expect_pose(anchored.odometry(), entry);
  // 1 m forward in odometry (+y there) is 1 m forward in the world (-x here).
  base.pose = {2.0, 2.0, kPi / 2};
  expect_pose(anchored.odometry(), {9.0, 20.0, kPi});
  // A quarter turn left and 0.5 m on (odometry -x): the world's -y, heading -pi/2.
  base.pose = {1.5, 2.0, kPi};
  expect_pose(anchored.odometry(), {9.0, 19.5, -kPi / 2});
  // Scans and frames carry the same sensor pose; beams and detections are untouched.
  const RangeScan s = anchored.ir_scan();
  expect_pose(s.X_WS, {9.0, 19.5, -kPi / 2});
  ASSERT_EQ(s.beams.size(), 1u);
  EXPECT_DOUBLE_EQ(s.beams[0].range_m, 0.5);
  const CameraFrame f = anchored.camera_frame(3.0);
  expect_pose(f.view.X_WS, {9.0, 19.5, -kPi / 2});
  EXPECT_DOUBLE_EQ(f.time_s, 3.0);
  ASSERT_EQ(f.detections.size(), 1u);
  EXPECT_DOUBLE_EQ(f.detections[0].distance_m, 1.5);
}

TEST(AnchoredUgvBase, ASecondAnchorReplacesTheFirst) {
  ScriptedBase base;
  base.pose = {5.0, 5.0, 0.0};
  AnchoredUgvBase anchored(base);
  anchored.anchor({1.0, 1.0, 0.0});
  base.pose = {6.0, 5.0, 0.0};
  expect_pose(anchored.odometry(), {2.0, 1.0, 0.0});
  anchored.anchor({-3.0, 4.0, kPi / 2});  // the next hidden space
  expect_pose(anchored.odometry(), {-3.0, 4.0, kPi / 2});
}

TEST(AnchoredUgvBase, CommandsReachTheBase) {
  ScriptedBase base;
  AnchoredUgvBase anchored(base);
  anchored.anchor({1.0, 2.0, 0.3});
  anchored.command_velocity(0.25, -0.5);
  anchored.set_epm(true);
  EXPECT_DOUBLE_EQ(base.v_mps, 0.25);
  EXPECT_DOUBLE_EQ(base.w_radps, -0.5);
  EXPECT_TRUE(base.epm);
  EXPECT_TRUE(anchored.status().epm_on);
  EXPECT_DOUBLE_EQ(anchored.speed_mps(), 0.2);
}

}  // namespace
}  // namespace ferret::ugv
