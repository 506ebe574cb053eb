// The miniUGV's hardware backend against a fake MCU on a pseudo-terminal and a video
// file as its camera. No timing assertions: every wait is for an event, with a
// generous deadline (the fake is a thread on a loaded machine).
#include "ferret/ugv/hw_ugv_base.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <opencv2/videoio.hpp>
#include <thread>

#include "fake_ugv_mcu.hpp"
#include "ferret/core/error.hpp"
#include "object_scene.hpp"

namespace ferret::ugv {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

const RobotDescription& miniugv() {
  static const RobotDescription robot = load_robot("miniugv");
  return robot;
}

/// Polls `done` until it holds or `timeout_s` passes; true when it held.
bool wait_until(const std::function<bool()>& done, double timeout_s = 15.0) {
  const auto deadline = std::chrono::steady_clock::now() +
                        std::chrono::milliseconds(static_cast<int>(timeout_s * 1000));
  while (std::chrono::steady_clock::now() < deadline) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return done();
}

HwUgvConfig config_for(const std::string& port, const std::string& camera = "none") {
  HwUgvConfig c;
  c.serial.port = port;
  c.camera.device = camera;
  c.link.connect_timeout_s = 5.0;
  c.link.telemetry_timeout_s = 5.0;  // generous: only the silence tests shorten it
  c.link.command_timeout_s = 0.0;    // hold commands: the tests command once
  c.link.epm_retry_s = 0.05;
  // Scripted counts jump by hundreds between two STATEs (20 ms): far faster than a wheel,
  // which the odometry would drop as a glitch (diff_drive_odometry_test covers that).
  c.odometry = {0.02, 360.0, 0.1, 0.1, 1000.0};
  return c;
}

test::FakeUgvMcu::Options scripted() {
  test::FakeUgvMcu::Options o;
  o.integrate_drive = false;
  return o;
}

double metres(int ticks) { return ticks * 2.0 * std::numbers::pi * 0.02 / 360.0; }

/// The HwUgvError a bring-up throws.
HwUgvError bring_up_error(const HwUgvConfig& config) {
  try {
    HwUgvBase base(config, miniugv());
  } catch (const HwUgvError& e) {
    return e;
  }
  ADD_FAILURE() << "the base came up";
  return HwUgvError(HwUgvError::Kind::kGpio, "none");
}

/// Waits until the base has used a STATE whose counts are these.
void wait_for_ticks(const HwUgvBase& base, std::int32_t left, std::int32_t right) {
  ASSERT_TRUE(wait_until([&] {
    const auto t = base.telemetry();
    return t.state && t.state->left_ticks == left && t.state->right_ticks == right;
  })) << "the base never saw "
      << left << " / " << right;
}

// ---------------------------------------------------------------- bring-up errors

TEST(HwUgvBase, AMissingSerialDeviceNamesThePort) {
  const HwUgvError e = bring_up_error(config_for("/dev/ttyFERRET-none"));
  EXPECT_EQ(e.kind(), HwUgvError::Kind::kSerialMissing);
  EXPECT_THAT(e.what(), HasSubstr("'/dev/ttyFERRET-none'"));
  EXPECT_THAT(e.what(), HasSubstr("no such device"));
}

/// The error of a bring-up against a fake that `misbehave` set up, with a short
/// connection timeout (every such fake fails it).
HwUgvError bring_up_error_with(const std::function<void(test::FakeUgvMcu&)>& misbehave,
                               test::FakeUgvMcu& fake) {
  misbehave(fake);
  HwUgvConfig c = config_for(fake.port());
  c.link.connect_timeout_s = 0.5;
  return bring_up_error(c);
}

TEST(HwUgvBase, ASilentMcuIsNoResponse) {
  test::FakeUgvMcu fake;
  const HwUgvError e = bring_up_error_with([](auto& f) { f.go_silent(true); }, fake);
  EXPECT_EQ(e.kind(), HwUgvError::Kind::kNoResponse);
  EXPECT_THAT(e.what(), HasSubstr("no reply"));
  EXPECT_THAT(e.what(), HasSubstr(fake.port()));
  EXPECT_GE(fake.hello_frames(), 1);  // it was asked
}

TEST(HwUgvBase, ADeviceThatSendsOnlyGarbageIsTheWrongDevice) {
  test::FakeUgvMcu fake;
  const HwUgvError e = bring_up_error_with([](auto& f) { f.send_garbage_only(true); }, fake);
  EXPECT_EQ(e.kind(), HwUgvError::Kind::kWrongDevice);
  EXPECT_THAT(e.what(), HasSubstr("none of them a valid frame"));
  EXPECT_THAT(e.what(), HasSubstr("115200 baud"));
}

TEST(HwUgvBase, AnMcuOfAnotherProtocolVersionIsNamedWithItsVersion) {
  test::FakeUgvMcu fake;
  const HwUgvError e = bring_up_error_with([](auto& f) { f.set_protocol_version(2); }, fake);
  EXPECT_EQ(e.kind(), HwUgvError::Kind::kProtocolVersion);
  EXPECT_THAT(e.what(), HasSubstr("protocol version 2"));
}

TEST(HwUgvBase, AnMcuThatStreamsButNeverAnswersHelloIsNoResponse) {
  test::FakeUgvMcu fake;
  const HwUgvError e = bring_up_error_with([](auto& f) { f.ignore_hello(true); }, fake);
  EXPECT_EQ(e.kind(), HwUgvError::Kind::kNoResponse);
  EXPECT_THAT(e.what(), HasSubstr("no INFO reply"));
}

TEST(HwUgvBase, AnIrCountOtherThanTheUrdfsIsAMismatch) {
  test::FakeUgvMcu::Options o;
  o.ir_count = 2;
  test::FakeUgvMcu fake(o);
  const HwUgvError e = bring_up_error(config_for(fake.port()));
  EXPECT_EQ(e.kind(), HwUgvError::Kind::kMismatch);
  EXPECT_THAT(e.what(), HasSubstr("reports 2 IR sensors"));
  EXPECT_THAT(e.what(), HasSubstr("ir_left, ir_center, ir_right"));
}

TEST(HwUgvBase, AnEpmGpioChipThatIsNotThereIsNamed) {
  test::FakeUgvMcu fake;
  HwUgvConfig c = config_for(fake.port());
  c.epm.via = HwUgvConfig::Epm::Via::kGpio;
  c.epm.chip = "gpiochip-ferret-none";
  c.epm.line = 17;
  const HwUgvError e = bring_up_error(c);
  EXPECT_EQ(e.kind(), HwUgvError::Kind::kGpio);
  EXPECT_THAT(e.what(), HasSubstr("'gpiochip-ferret-none'"));
}

TEST(HwUgvBase, AnInvalidConfigIsAnInputErrorNamingTheField) {
  test::FakeUgvMcu fake;
  HwUgvConfig c = config_for(fake.port());
  c.odometry.track_width_m = std::nan("");
  try {
    HwUgvBase base(c, miniugv());
    FAIL() << "a NaN track width was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "ugv.base.odometry.track_width_m");
  }
}

// ---------------------------------------------------------------- the happy path

TEST(HwUgvBase, CommandsReachTheMcuAsWheelSpeeds) {
  test::FakeUgvMcu fake;
  HwUgvBase base(config_for(fake.port()), miniugv());
  EXPECT_EQ(base.backend(), "hw");
  // v = 0.2 m/s, w = 1 rad/s on a 0.1 m track: the wheels at 0.2 -+ 0.05 m/s.
  base.command_velocity(0.2, 1.0);
  EXPECT_TRUE(wait_until([&] {
    const auto d = fake.last_drive();
    return d.left_mmps == 150 && d.right_mmps == 250;
  }));
  base.command_velocity(std::nan(""), 0.5);  // a controller's bug stops the forward motion
  EXPECT_TRUE(wait_until([&] {
    const auto d = fake.last_drive();
    return d.left_mmps == -25 && d.right_mmps == 25;
  }));
  // Far beyond the limits: clipped to the URDF's speed, straight on.
  base.command_velocity(100.0, 0.0);
  const double v_max =
      std::min(miniugv().limits.max_velocity_mps, miniugv().wheel_speed_limit_mps.value_or(1e9));
  const auto expected = static_cast<std::int16_t>(std::lround(v_max * 1000));
  EXPECT_TRUE(wait_until([&] {
    const auto d = fake.last_drive();
    return d.left_mmps == expected && d.right_mmps == expected;
  })) << "expected "
      << expected << " mm/s";
  EXPECT_EQ(base.wheel_command(100.0, 0.0).left_mmps, expected);
}

TEST(HwUgvBase, AWheelPastItsLimitSlowsBothWheelsAndKeepsTheCurvature) {
  test::FakeUgvMcu fake;
  HwUgvConfig c = config_for(fake.port());
  c.odometry.track_width_m = 0.4;  // wide enough that full speed and yaw rate pass the limit
  const HwUgvBase base(c, miniugv());
  const double v_max =
      std::min(miniugv().limits.max_velocity_mps, miniugv().wheel_speed_limit_mps.value_or(1e9));
  const double w_max = miniugv().limits.max_yaw_rate_radps;
  const double wheel_limit_mmps = 1000 * miniugv().wheel_speed_limit_mps.value_or(v_max);
  ASSERT_GT(1000 * (v_max + w_max * 0.2), wheel_limit_mmps) << "the arc would not clip";
  const mcu::DriveCommand arc = base.wheel_command(v_max, w_max);
  // The outer wheel at its limit, not beyond it and not far below it.
  EXPECT_NEAR(arc.right_mmps, wheel_limit_mmps, 0.5);
  EXPECT_LT(arc.left_mmps, arc.right_mmps);
  // w / v = ((right - left) / b) / ((right + left) / 2): the controller's curvature.
  const double v = 0.5 * (arc.right_mmps + arc.left_mmps);
  const double w = (arc.right_mmps - arc.left_mmps) / 0.4;
  EXPECT_NEAR(w / v, w_max / v_max, 0.01 * w_max / v_max);
  EXPECT_LT(v, 1000 * v_max);  // it slowed down rather than turning less
}

TEST(HwUgvBase, OdometryFromScriptedEncoderCountsMatchesTheHandComputedPose) {
  test::FakeUgvMcu fake(scripted());
  HwUgvBase base(config_for(fake.port()), miniugv(), ObjectSearchParams{}, Pose2{0.5, -0.25, 0.0});
  wait_for_ticks(base, 0, 0);  // the baseline
  fake.add_ticks(1000, 1000);  // straight
  wait_for_ticks(base, 1000, 1000);
  fake.add_ticks(-125, 125);  // on the spot
  wait_for_ticks(base, 875, 1125);
  fake.add_ticks(500, 500);  // straight along the new heading
  wait_for_ticks(base, 1375, 1625);
  const double turn = 2.0 * metres(125) / 0.1;
  const Pose2 pose = base.odometry();
  EXPECT_NEAR(pose.x_m, 0.5 + metres(1000) + metres(500) * std::cos(turn), 1e-9);
  EXPECT_NEAR(pose.y_m, -0.25 + metres(500) * std::sin(turn), 1e-9);
  EXPECT_NEAR(pose.yaw_rad, turn, 1e-9);
}

TEST(HwUgvBase, DrivingForwardMovesTheOdometryStraightAhead) {
  test::FakeUgvMcu fake;  // its wheels follow DRIVE
  HwUgvBase base(config_for(fake.port()), miniugv());
  base.command_velocity(0.3, 0.0);
  double top_speed = 0.0;
  ASSERT_TRUE(wait_until([&] {
    top_speed = std::max(top_speed, base.speed_mps());
    return base.odometry().x_m > 0.05;
  }));
  base.command_velocity(0.0, 0.0);
  EXPECT_GT(top_speed, 0.0);
  EXPECT_LT(top_speed, 0.3 * 1.5);
  // Equal wheels: no turn, no sideways motion, whatever the timing.
  EXPECT_NEAR(base.odometry().y_m, 0.0, 1e-12);
  EXPECT_NEAR(base.odometry().yaw_rad, 0.0, 1e-12);
}

TEST(HwUgvBase, AControllerThatStopsCommandingStopsTheWheels) {
  test::FakeUgvMcu fake(scripted());
  HwUgvConfig c = config_for(fake.port());
  c.link.command_timeout_s = 0.3;
  HwUgvBase base(c, miniugv());
  base.command_velocity(0.2, 0.0);
  ASSERT_TRUE(wait_until([&] { return fake.last_drive().left_mmps == 200; }));
  EXPECT_TRUE(wait_until([&] { return fake.last_drive().left_mmps == 0; }));
}

TEST(HwUgvBase, IrScanBeamsLieAtTheUrdfBeamsWithTheMcusRanges) {
  test::FakeUgvMcu fake(scripted());
  HwUgvBase base(config_for(fake.port()), miniugv());
  const std::vector<std::uint16_t> mm = {500, mcu::kIrNoReturn, 1234};
  fake.set_ir_mm(mm);
  RangeScan scan;
  ASSERT_TRUE(wait_until([&] {
    scan = base.ir_scan();  // the fake's first reading (all "no return") may come first
    return scan.beams.size() == 9 && scan.beams[0].range_m < scan.max_range_m;
  }));
  // Each sensor's range on each of its URDF beams; the hit point is where the sensor
  // (not the robot's origin) saw it. The robot is at the origin, so B = W.
  const auto& names = miniugv().roles.at("ir");
  ASSERT_EQ(scan.beams.size(), 9u);
  std::size_t k = 0;
  for (std::size_t s = 0; s < names.size(); ++s) {
    const RangeSensor& r = *miniugv().find_range_sensor(names[s]);
    for (int i = 0; i < r.samples; ++i, ++k) {
      const RangeBeam& b = scan.beams[k];
      const double a = r.beam_angle_rad(i);
      const Eigen::Vector3d d3 = r.X_BS.linear() * Eigen::Vector3d(std::cos(a), std::sin(a), 0);
      const Eigen::Vector2d dir = Eigen::Vector2d(d3.x(), d3.y()).normalized();
      const Eigen::Vector2d p_BO = r.X_BS.translation().head<2>();
      const Eigen::Vector2d got(b.range_m * std::cos(b.bearing_rad),
                                b.range_m * std::sin(b.bearing_rad));
      if (mm[s] == mcu::kIrNoReturn) {
        EXPECT_GE(b.range_m, scan.max_range_m) << names[s];  // no return
        const Eigen::Vector2d far = p_BO + r.range_max_m * dir;
        EXPECT_NEAR(b.bearing_rad, std::atan2(far.y(), far.x()), 1e-12);
      } else {
        const Eigen::Vector2d want = p_BO + mm[s] / 1000.0 * dir;
        EXPECT_NEAR((got - want).norm(), 0.0, 1e-12) << names[s] << " beam " << i;
        EXPECT_LT(b.range_m, scan.max_range_m);
      }
    }
  }
  // A reading is used once: until the MCU has a new one, scans are empty.
  EXPECT_TRUE(base.ir_scan().beams.empty());
  fake.set_ir_mm({600, 600, 600});
  ASSERT_TRUE(wait_until([&] { return !(scan = base.ir_scan()).beams.empty(); }));
  EXPECT_EQ(scan.beams.size(), 9u);
}

TEST(HwUgvBase, TheEpmSwitchesThroughTheMcuWithOnePulseAChange) {
  test::FakeUgvMcu fake(scripted());
  HwUgvBase base(config_for(fake.port()), miniugv());
  EXPECT_FALSE(base.status().epm_on);
  base.set_epm(true);
  ASSERT_TRUE(wait_until([&] { return base.status().epm_on; }));
  EXPECT_TRUE(fake.epm_on());
  EXPECT_EQ(fake.epm_pulses(), 1);
  base.set_epm(true);  // already on: no second pulse
  base.set_epm(false);
  ASSERT_TRUE(wait_until([&] { return !base.status().epm_on; }));
  EXPECT_EQ(fake.epm_pulses(), 2);
  EXPECT_FALSE(base.status().has(UgvFault::kEpm));
}

TEST(HwUgvBase, AnEpmThatDoesNotSwitchIsRetriedAndReported) {
  test::FakeUgvMcu fake(scripted());
  fake.break_epm(true);
  HwUgvBase base(config_for(fake.port()), miniugv());
  base.set_epm(true);
  ASSERT_TRUE(wait_until([&] { return base.status().has(UgvFault::kEpm); }));
  EXPECT_TRUE(wait_until([&] { return fake.epm_pulses() >= 2; }));  // retried
  EXPECT_FALSE(base.status().epm_on);
  EXPECT_THAT(base.diagnosis(), HasSubstr("epm"));
}

TEST(HwUgvBase, StatusCarriesTheMcusBatteryContactAndFaults) {
  test::FakeUgvMcu fake(scripted());
  HwUgvBase base(config_for(fake.port()), miniugv());
  fake.set_battery(7400, 42);
  fake.set_contact(true);
  fake.set_faults(mcu::fault::kMotorLeft | mcu::fault::kImu);
  fake.set_imu_cdeg(150, -300, 9000);
  ASSERT_TRUE(wait_until([&] {
    const UgvStatus s = base.status();
    return s.contact && s.has(UgvFault::kDrive) && s.has(UgvFault::kSensor);
  }));
  const UgvStatus s = base.status();
  EXPECT_DOUBLE_EQ(s.battery_fraction, 0.42);
  EXPECT_FALSE(s.has(UgvFault::kLinkLost));
  EXPECT_TRUE(s.has(UgvFault::kCamera));  // camera: none
  const auto t = base.telemetry();
  EXPECT_EQ(t.state->battery_mv, 7400);
  EXPECT_EQ(t.state->pitch_cdeg, -300);
  EXPECT_EQ(t.info->watchdog_ms, 300);
  EXPECT_THAT(base.diagnosis(), HasSubstr("motor_left, imu"));
  EXPECT_THAT(describe_faults(s.faults), HasSubstr("drive, sensor, camera"));
}

// ---------------------------------------------------------------- a link in trouble

TEST(HwUgvBase, AnMcuGoingSilentIsLinkLostTheWheelsStopAndItRecovers) {
  test::FakeUgvMcu fake(scripted());
  HwUgvConfig c = config_for(fake.port());
  c.link.telemetry_timeout_s = 0.3;
  HwUgvBase base(c, miniugv());
  fake.set_ir_mm({500, 500, 500});
  base.command_velocity(0.2, 0.0);
  ASSERT_TRUE(wait_until([&] { return fake.last_drive().left_mmps == 200; }));

  fake.go_silent(true);
  ASSERT_TRUE(wait_until([&] { return base.status().has(UgvFault::kLinkLost); }));
  // The host keeps talking: zeros, so an MCU that only lost its transmit line stops too.
  EXPECT_TRUE(wait_until([&] { return fake.last_drive().left_mmps == 0; }));
  EXPECT_TRUE(base.ir_scan().beams.empty());
  EXPECT_EQ(base.speed_mps(), 0.0);
  EXPECT_THAT(base.diagnosis(), HasSubstr("link lost"));
  EXPECT_GE(base.link_stats().link_losses, 1u);

  fake.go_silent(false);
  ASSERT_TRUE(wait_until([&] { return !base.status().has(UgvFault::kLinkLost); }));
  // The command from before the loss is not resumed: the controller must command anew.
  const int frames = fake.drive_frames();
  ASSERT_TRUE(wait_until([&] { return fake.drive_frames() >= frames + 5; }));
  EXPECT_EQ(fake.last_drive().left_mmps, 0);
  base.command_velocity(0.1, 0.0);
  EXPECT_TRUE(wait_until([&] { return fake.last_drive().left_mmps == 100; }));
}

TEST(HwUgvBase, GarbledFramesAreDroppedAndTheStreamResynchronises) {
  test::FakeUgvMcu fake(scripted());
  HwUgvBase base(config_for(fake.port()), miniugv());
  wait_for_ticks(base, 0, 0);
  fake.noise_between_frames(7);
  fake.corrupt_next(20);
  fake.add_ticks(400, 400);
  ASSERT_TRUE(wait_until([&] { return base.link_stats().reader.bad_crc >= 20; }));
  wait_for_ticks(base, 400, 400);
  fake.noise_between_frames(0);
  EXPECT_NEAR(base.odometry().x_m, metres(400), 1e-9);
  const HwLinkStats stats = base.link_stats();
  EXPECT_GT(stats.reader.noise_bytes, 0u);
  EXPECT_GE(stats.lost_states, 20u);  // the corrupt frames are gaps in the sequence
  EXPECT_FALSE(base.status().has(UgvFault::kLinkLost));
}

TEST(HwUgvBase, AnotherProtocolVersionWhileRunningIsAFault) {
  test::FakeUgvMcu fake(scripted());
  HwUgvConfig c = config_for(fake.port());
  c.link.telemetry_timeout_s = 0.3;
  HwUgvBase base(c, miniugv());
  fake.set_protocol_version(3);
  ASSERT_TRUE(wait_until([&] {
    const UgvStatus s = base.status();
    return s.has(UgvFault::kProtocolVersion) && s.has(UgvFault::kLinkLost);
  }));
  EXPECT_THAT(base.diagnosis(), HasSubstr("protocol version 3"));
}

TEST(HwUgvBase, AnMcuRestartKeepsThePoseAndCountsOnFromZero) {
  test::FakeUgvMcu fake(scripted());
  HwUgvBase base(config_for(fake.port()), miniugv());
  wait_for_ticks(base, 0, 0);
  fake.add_ticks(1000, 1000);
  wait_for_ticks(base, 1000, 1000);
  // Let its clock pass the restart's, so "time went back" is what the base sees.
  ASSERT_TRUE(wait_until([&] {
    const auto t = base.telemetry();
    return t.state && t.state->mcu_time_ms > 200;
  }));
  fake.restart();
  ASSERT_TRUE(wait_until([&] { return base.link_stats().mcu_restarts >= 1; }));
  EXPECT_NEAR(base.odometry().x_m, metres(1000), 1e-9);
  fake.add_ticks(100, 100);
  wait_for_ticks(base, 100, 100);
  EXPECT_NEAR(base.odometry().x_m, metres(1100), 1e-9);
}

// ---------------------------------------------------------------- the camera

/// A short MJPG video of the object at `view`, rendered with the project's object
/// appearance by the simulator's camera.
fs::path write_object_video(const test::ObjectScene& scene, const test::ObjectView& view,
                            int frames) {
  const fs::path path =
      fs::temp_directory_path() / ("ferret_hw_ugv_" + std::to_string(::getpid()) + "_object.avi");
  const CameraModel& cam = scene.camera();
  cv::VideoWriter writer(path.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 15.0,
                         cv::Size(cam.width_px, cam.height_px));
  if (!writer.isOpened()) return {};
  for (int k = 0; k < frames; ++k) {
    const RgbImage rgb =
        scene.frame(view, CameraFrameOptions{}, 10 + static_cast<std::uint64_t>(k));
    cv::Mat bgr(rgb.height_px, rgb.width_px, CV_8UC3);
    for (int y = 0; y < rgb.height_px; ++y)
      for (int x = 0; x < rgb.width_px; ++x)
        bgr.at<cv::Vec3b>(y, x) = {rgb.at(x, y, 2), rgb.at(x, y, 1), rgb.at(x, y, 0)};
    writer.write(bgr);
  }
  return path;
}

TEST(HwUgvBase, AVideoFileAsTheCameraGivesDetectionsFromTheRobotsOrigin) {
  const test::ObjectScene scene(miniugv(), ObjectSearchParams{});
  const test::ObjectView view{1.0, 0.25, 0.0};
  const fs::path video = write_object_video(scene, view, 4);
  ASSERT_FALSE(video.empty()) << "OpenCV cannot write MJPG";
  test::FakeUgvMcu fake(scripted());
  HwUgvBase base(config_for(fake.port(), video.string()), miniugv());
  fake.set_ir_mm({2000, 2000, 2000});
  ASSERT_TRUE(wait_until([&] {
    const auto t = base.telemetry();
    return t.state && t.state->ir_mm[0] == 2000;
  }));

  // Where the object (at the world's origin) lies from the robot's origin.
  const Pose3 X_WB = scene.X_WB(view);
  const Eigen::Vector3d p_BO = X_WB.inverse() * Eigen::Vector3d(0, 0, 0);
  const double bearing_B = std::atan2(p_BO.y(), p_BO.x());
  const double distance_B = p_BO.head<2>().norm();
  for (int k = 0; k < 6; ++k) {  // past the end of the 4 frames: the file replays
    const CameraFrame f = base.camera_frame(0.1 * k);
    EXPECT_DOUBLE_EQ(f.time_s, 0.1 * k);
    ASSERT_EQ(f.detections.size(), 1u) << "frame " << k;
    // MJPG and the detector's pixel edges: a few per cent of range, a degree of bearing.
    EXPECT_NEAR(f.detections[0].bearing_rad, bearing_B, 0.02) << "frame " << k;
    EXPECT_NEAR(f.detections[0].distance_m, distance_B, 0.08 * distance_B) << "frame " << k;
    EXPECT_GT(f.detections[0].confidence, 0.5);
    // The view: the IR beams (all within the camera's 90 degrees), to their returns.
    ASSERT_EQ(f.view.beams.size(), 9u);
    for (const auto& b : f.view.beams) EXPECT_LT(b.range_m, 2.1);
    EXPECT_DOUBLE_EQ(f.view.max_range_m, 4.0);  // D_cam
  }
  EXPECT_FALSE(base.status().has(UgvFault::kCamera));
  fs::remove(video);
}

TEST(HwUgvBase, ACameraThatIsNotThereOrNotAVideoIsNamed) {
  test::FakeUgvMcu fake;
  const HwUgvError missing = bring_up_error(config_for(fake.port(), "/tmp/ferret-no-such.avi"));
  EXPECT_EQ(missing.kind(), HwUgvError::Kind::kCameraMissing);
  EXPECT_THAT(missing.what(), HasSubstr("'/tmp/ferret-no-such.avi'"));

  const fs::path junk =
      fs::temp_directory_path() / ("ferret_hw_ugv_" + std::to_string(::getpid()) + "_junk.avi");
  std::ofstream(junk) << "this is not a video\n";
  const HwUgvError not_video = bring_up_error(config_for(fake.port(), junk.string()));
  EXPECT_TRUE(not_video.kind() == HwUgvError::Kind::kCameraMissing ||
              not_video.kind() == HwUgvError::Kind::kCameraNoFrames)
      << to_string(not_video.kind());
  EXPECT_THAT(not_video.what(), HasSubstr(junk.string()));
  fs::remove(junk);
}

TEST(HwUgvBase, WithoutACameraFramesAreEmptyAndTheFaultSaysSo) {
  test::FakeUgvMcu fake;
  HwUgvBase base(config_for(fake.port(), "none"), miniugv());
  const CameraFrame f = base.camera_frame(1.0);
  EXPECT_TRUE(f.detections.empty());
  EXPECT_TRUE(f.view.beams.empty());
  EXPECT_TRUE(base.status().has(UgvFault::kCamera));
  EXPECT_THAT(base.diagnosis(), HasSubstr("no camera"));
}

}  // namespace
}  // namespace ferret::ugv
