#include "ferret/tether_model/dynamixel_winch.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <thread>

#include "fake_dynamixel.hpp"

namespace ferret::tether {
namespace {

using ::testing::HasSubstr;

DynamixelWinch::Options options_for(const test::FakeDynamixel& fake) {
  DynamixelWinch::Options o;
  o.port = fake.port();
  o.spool_radius_m = 0.05;
  o.bus.timeout_ms = 200;  // generous: the fake servo is a thread on a loaded machine
  o.bus.retries = 2;
  return o;
}

TEST(DynamixelBus, PingReadsModelAndFirmwareOverAPty) {
  test::FakeDynamixel fake(311);
  DynamixelBus bus(open_serial_port(fake.port(), 57600), {200, 2});
  const PingReply r = bus.ping(1);
  EXPECT_EQ(r.model_number, 311);
  EXPECT_EQ(r.firmware_version, 41);
  EXPECT_EQ(bus.read_u16(1, mx2::kModelNumber), 311);
}

TEST(DynamixelBus, WriteThenReadRoundTripsAndStatusErrorsAreReported) {
  test::FakeDynamixel fake;
  DynamixelBus bus(open_serial_port(fake.port(), 57600), {200, 2});
  bus.write_u32(1, mx2::kProfileAcceleration, 123456);
  EXPECT_EQ(bus.read_u32(1, mx2::kProfileAcceleration), 123456u);
  bus.write_u8(1, mx2::kTorqueEnable, 1);
  // The operating mode is in EEPROM: locked while torque is on.
  try {
    bus.write_u8(1, mx2::kOperatingMode, mx2::kVelocityMode);
    FAIL() << "expected an access error";
  } catch (const DynamixelError& e) {
    EXPECT_EQ(e.kind(), DynamixelError::Kind::kStatus);
    EXPECT_EQ(e.status_error(), 0x07);
    EXPECT_THAT(e.what(), HasSubstr("access error"));
  }
}

TEST(DynamixelBus, RetriesAfterATimeoutOrACorruptReply) {
  test::FakeDynamixel fake;
  DynamixelBus bus(open_serial_port(fake.port(), 57600), {200, 2});
  fake.drop_next(1);
  EXPECT_EQ(bus.ping(1).model_number, 311);
  EXPECT_EQ(bus.retried(), 1);
  fake.corrupt_next(2);
  EXPECT_EQ(bus.ping(1).model_number, 311);
  EXPECT_EQ(bus.retried(), 3);
}

TEST(DynamixelBus, GivesUpWithATimeoutErrorAfterTheRetries) {
  test::FakeDynamixel fake;
  DynamixelBus bus(open_serial_port(fake.port(), 57600), {15, 2});
  fake.drop_next(3);
  const auto start = std::chrono::steady_clock::now();
  try {
    (void)bus.ping(1);
    FAIL() << "expected a timeout";
  } catch (const DynamixelError& e) {
    EXPECT_EQ(e.kind(), DynamixelError::Kind::kTimeout);
    EXPECT_THAT(e.what(), HasSubstr("no reply within 15 ms after 3 attempts"));
    EXPECT_THAT(e.what(), HasSubstr(fake.port()));
  }
  EXPECT_GE(std::chrono::steady_clock::now() - start, std::chrono::milliseconds(45));
  EXPECT_EQ(fake.requests(), 3);
  // An id nobody has also times out (the fake answers id 1 only).
  fake.drop_next(0);
  EXPECT_THROW((void)bus.ping(9), DynamixelError);
}

TEST(DynamixelWinch, MissingPortIsAClearError) {
  DynamixelWinch::Options o;
  o.port = "/dev/ttyUSB_ferret_missing";
  try {
    DynamixelWinch winch(o);
    FAIL() << "expected SerialError";
  } catch (const SerialError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/dev/ttyUSB_ferret_missing"));
    EXPECT_THAT(e.what(), HasSubstr("not found"));
  }
}

TEST(DynamixelWinch, WrongModelIsRejectedByName) {
  test::FakeDynamixel fake(1030);  // an XM430-W210
  DynamixelWinch winch(options_for(fake));
  try {
    (void)winch.connect();
    FAIL() << "expected a wrong-device error";
  } catch (const DynamixelError& e) {
    EXPECT_EQ(e.kind(), DynamixelError::Kind::kWrongDevice);
    EXPECT_THAT(e.what(), HasSubstr("XM430-W210 (model number 1030)"));
    EXPECT_THAT(e.what(), HasSubstr("MX-64 (311)"));
  }
  EXPECT_EQ(fake.read_table(mx2::kTorqueEnable, 1), 0u);  // nothing was switched on
}

TEST(DynamixelWinch, ConnectSetsVelocityModeProfileAndTorque) {
  test::FakeDynamixel fake;
  DynamixelWinch::Options o = options_for(fake);
  o.max_acceleration_mps2 = 2.0;
  DynamixelWinch winch(o);
  const PingReply r = winch.connect();
  EXPECT_EQ(r.model_number, 311);
  EXPECT_EQ(fake.read_table(mx2::kOperatingMode, 1), 1u);
  EXPECT_EQ(fake.read_table(mx2::kTorqueEnable, 1), 1u);
  // 2 m/s^2 on a 5 cm spool = 6.366 rev/s^2 = 22918 rev/min^2 = 106.8 units of 214.577.
  EXPECT_EQ(fake.read_table(mx2::kProfileAcceleration, 4), 107u);
}

TEST(DynamixelWinch, VelocityCommandsBecomeGoalVelocityUnits) {
  test::FakeDynamixel fake;
  DynamixelWinch::Options o = options_for(fake);
  o.payout_direction = -1;
  DynamixelWinch winch(o);
  (void)winch.connect();
  // 0.3 m/s on a 5 cm spool: 57.30 rpm = 250.2 units; paying out is negative here.
  winch.command_velocity_mps(0.3);
  EXPECT_EQ(fake.goal_velocity(), -250);
  EXPECT_EQ(winch.velocity_units(0.3), -250);
  // Clamped to the speed limit (0.6 m/s -> 500 units).
  winch.command_velocity_mps(-5.0);
  EXPECT_EQ(fake.goal_velocity(), 500);
}

TEST(DynamixelWinch, StateFollowsThePositionVelocityAndCurrentRegisters) {
  test::FakeDynamixel fake;
  DynamixelWinch::Options o = options_for(fake);
  o.initial_released_m = 2.0;
  o.tension_n_per_current_unit = 0.02;
  DynamixelWinch winch(o);
  (void)winch.connect();
  fake.set_present_current(-150);
  const auto start = std::chrono::steady_clock::now();
  winch.command_velocity_mps(0.2);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const WinchState s = winch.read_state();
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  winch.command_velocity_mps(0.0);
  // 0.2 m/s -> 167 units -> 0.19996 m/s back; the fake moved for at most the elapsed
  // time and at least most of the 0.3 s sleep.
  const double speed = 167 * 0.229 / 60.0 * 2.0 * std::numbers::pi * 0.05;
  EXPECT_NEAR(s.speed_mps, speed, 1e-9);
  EXPECT_GT(s.released_m, 2.0 + speed * 0.25);
  EXPECT_LT(s.released_m, 2.0 + speed * (elapsed_s + 0.01));
  EXPECT_NEAR(s.tension_n, 3.0, 1e-9);
}

}  // namespace
}  // namespace ferret::tether
