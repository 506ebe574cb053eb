#pragma once
// Flies the UAV along planned paths: asks the flight planner for a collision-free path
// (from where the UAV comes to a stop), then commands the flight controller corner by
// corner, turning on the spot where a segment starts, and the final heading at the end.

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "ferret/uav/flight_controller.hpp"

namespace ferret {

/// A flight planner: a collision-free path from `from` to `to` (both included), with
/// the miniUGV hanging below when `carrying`; nullopt when there is none.
using FlightPlanner = std::function<std::optional<std::vector<Eigen::Vector3d>>(
    const Eigen::Vector3d& from, const Eigen::Vector3d& to, bool carrying)>;

class FlightPathFollower {
 public:
  struct Options {
    /// The deceleration the flight controller stops with: where a new path starts.
    double braking_accel_mps2 = 1.6;
    double waypoint_tolerance_m = 0.4;
  };
  FlightPathFollower(FlightController& flight, FlightPlanner planner, Options options);

  /// Plans to `goal` and starts following the path; false (and no path) when there is
  /// no plan. `yaw_rad`: the heading to turn to at the end.
  bool fly_to(const Eigen::Vector3d& goal, double speed_mps, bool carrying,
              std::optional<double> yaw_rad = std::nullopt);
  /// Flies straight to `goal` without a plan (the way it came is clear); the final
  /// heading stays what the last plan set.
  void fly_straight(const Eigen::Vector3d& goal, double speed_mps);
  /// Follows the current path; true when at its end (or when there is no path).
  bool follow(const FlightState& s);
  /// Drops the path: the next leg is planned anew.
  void clear() { path_.clear(); }
  [[nodiscard]] bool empty() const { return path_.empty(); }
  /// The heading the path ends on, when one was given.
  [[nodiscard]] const std::optional<double>& final_yaw_rad() const { return yaw_rad_; }
  [[nodiscard]] int plans_failed() const { return plans_failed_; }

 private:
  FlightController& flight_;
  FlightPlanner planner_;
  Options options_;
  std::vector<Eigen::Vector3d> path_;
  std::size_t next_ = 0;
  double speed_mps_ = 0.0;
  std::optional<double> yaw_rad_;
  int plans_failed_ = 0;
};

}  // namespace ferret
