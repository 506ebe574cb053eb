#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "support/cli_runner.hpp"
#include "tether_model/fake_dynamixel.hpp"

namespace ferret::test {
namespace {

using ::testing::HasSubstr;

TEST(WinchCli, PingsAFakeServo) {
  FakeDynamixel fake(311);
  const auto r = run_cli("winch ping --port " + fake.port() + " --timeout-ms 300");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out,
              HasSubstr("id 1 on " + fake.port() + ": MX-64 (model number 311), firmware 41"));
}

TEST(WinchCli, SpinsAndReportsTheState) {
  FakeDynamixel fake(311);
  const auto r = run_cli("winch spin --port " + fake.port() +
                         " --timeout-ms 300 --speed 0.1 --seconds 0.3 --spool-radius 0.05");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("speed_mps: 0.09"));  // 0.1 m/s -> 83 units -> 0.0995 m/s
  EXPECT_EQ(fake.goal_velocity(), 0);                // stopped again
  EXPECT_EQ(fake.read_table(11, 1), 1u);             // velocity mode
}

TEST(WinchCli, MissingPortExitsTwoAndSilentOrWrongServoExitsOne) {
  auto r = run_cli("winch ping --port /dev/ttyUSB_ferret_missing");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("/dev/ttyUSB_ferret_missing"));
  FakeDynamixel fake(1030);
  r = run_cli("winch ping --port " + fake.port() + " --id 7 --timeout-ms 20 --retries 1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("no reply within 20 ms after 2 attempts"));
  r = run_cli("winch state --port " + fake.port() + " --timeout-ms 300");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.err, HasSubstr("XM430-W210"));
}

}  // namespace
}  // namespace ferret::test
