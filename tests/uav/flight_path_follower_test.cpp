// The flight path follower against a flight controller that only records its commands.

#include "ferret/uav/flight_path_follower.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace ferret {
namespace {

class RecordingFlight final : public FlightController {
 public:
  struct Setpoint {
    Eigen::Vector3d p_W;
    double yaw_rad;
    double speed_mps;
  };
  [[nodiscard]] std::string backend() const override { return "fake"; }
  [[nodiscard]] FlightState state() const override { return s; }
  void command_takeoff(double) override {}
  void command_position(const Eigen::Vector3d& p, double yaw, double speed) override {
    setpoints.push_back({p, yaw, speed});
  }
  void command_land() override {}
  FlightState s;
  std::vector<Setpoint> setpoints;
};

// A planner that goes through (5, 0, 4) on the way, or finds nothing when `none`.
struct Planner {
  bool none = false;
  int calls = 0;
  FlightPlanner function() {
    return [this](const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                  bool) -> std::optional<std::vector<Eigen::Vector3d>> {
      ++calls;
      if (none) return std::nullopt;
      return std::vector<Eigen::Vector3d>{a, Eigen::Vector3d(5, 0, 4), b};
    };
  }
};

TEST(FlightPathFollower, CornersAreReachedOneByOneThenTheFinalHeadingIsTurnedTo) {
  RecordingFlight flight;
  flight.s.p_W = {0, 0, 4};
  Planner planner;
  FlightPathFollower f(flight, planner.function(), {});
  ASSERT_TRUE(f.fly_to({5, 5, 4}, 2.0, false, 1.0));
  // At the start, facing along the first segment already: on to the corner.
  EXPECT_FALSE(f.follow(flight.s));
  EXPECT_EQ(flight.setpoints.back().p_W, Eigen::Vector3d(5, 0, 4));
  EXPECT_DOUBLE_EQ(flight.setpoints.back().speed_mps, 2.0);
  // On the corner, facing +x: it turns on the spot to face the last segment (+y) first.
  flight.s.p_W = {5, 0, 4};
  EXPECT_FALSE(f.follow(flight.s));
  EXPECT_EQ(flight.setpoints.back().p_W, Eigen::Vector3d(5, 0, 4));
  EXPECT_NEAR(flight.setpoints.back().yaw_rad, std::numbers::pi / 2, 1e-12);
  flight.s.yaw_rad = std::numbers::pi / 2;
  EXPECT_FALSE(f.follow(flight.s));
  EXPECT_EQ(flight.setpoints.back().p_W, Eigen::Vector3d(5, 5, 4));
  // At the end: the final heading, and arrived.
  flight.s.p_W = {5, 5, 4};
  EXPECT_TRUE(f.follow(flight.s));
  EXPECT_DOUBLE_EQ(flight.setpoints.back().yaw_rad, 1.0);
  EXPECT_EQ(f.plans_failed(), 0);
}

TEST(FlightPathFollower, NoPlanIsCountedAndLeavesNoPath) {
  RecordingFlight flight;
  Planner planner;
  planner.none = true;
  FlightPathFollower f(flight, planner.function(), {});
  EXPECT_FALSE(f.fly_to({5, 5, 4}, 2.0, false));
  EXPECT_EQ(f.plans_failed(), 1);
  EXPECT_TRUE(f.empty());
  EXPECT_TRUE(f.follow(flight.s));  // nothing to follow: there
  EXPECT_TRUE(flight.setpoints.empty());
  f.fly_straight({1, 2, 3}, 4.0);
  EXPECT_FALSE(f.empty());
  EXPECT_FALSE(f.follow(flight.s));
  EXPECT_EQ(flight.setpoints.back().p_W, Eigen::Vector3d(1, 2, 3));
  EXPECT_DOUBLE_EQ(flight.setpoints.back().speed_mps, 4.0);
}

TEST(FlightPathFollower, AMovingUavPlansFromWhereItStops) {
  RecordingFlight flight;
  flight.s.p_W = {0, 0, 4};
  flight.s.v_W = {3.2, 0, 0};  // stops 3.2 m on at 1.6 m/s^2
  std::vector<Eigen::Vector3d> froms;
  FlightPathFollower f(flight,
                       [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           bool) -> std::optional<std::vector<Eigen::Vector3d>> {
                         froms.push_back(a);
                         return std::vector<Eigen::Vector3d>{a, b};
                       },
                       {});
  ASSERT_TRUE(f.fly_to({0, 9, 4}, 2.0, false));
  ASSERT_EQ(froms.size(), 2u);  // the braking line, then the leg
  EXPECT_EQ(froms[1], Eigen::Vector3d(3.2, 0, 4));
}

}  // namespace
}  // namespace ferret
