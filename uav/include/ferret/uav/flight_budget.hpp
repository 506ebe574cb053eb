#pragma once
// The UAV's flight budget: what the battery has left against what the way home costs at
// cruise speed, with a reserve kept over it. It decides when the search must end, and,
// while the UAV hovers with the miniUGV out, when to call the miniUGV back and when to
// lift it out at once.

#include <Eigen/Core>
#include <deque>
#include <utility>

#include "ferret/uav/flight_controller.hpp"

namespace ferret {

class FlightBudget {
 public:
  struct Options {
    double cruise_speed_mps = 5.0;
    /// Flight endurance of a full battery, and the reserve kept over the way home.
    double flight_endurance_s = 20.0 * 60.0;
    double battery_reserve_fraction = 0.10;
    double retract_speed_mps = 0.4;     ///< the reel-in
    double ugv_return_speed_mps = 0.2;  ///< the miniUGV coming back along its tether
    /// A healthy battery drains at most this many times as fast as hovering does (at full
    /// speed); a faster drain, measured over the last minute, scales every cost.
    double max_healthy_drain_factor = 1.15;
  };
  explicit FlightBudget(Options options) : options_(options) {}

  /// Where the mission started: the way home leads there.
  void set_home(const Eigen::Vector3d& home_W) { home_W_ = home_W; }
  [[nodiscard]] const Eigen::Vector3d& home_W() const { return home_W_; }

  /// Whether the battery left covers no more than `before_s` of hovering (the miniUGV's
  /// return, the reel-in), the way home at cruise speed, 30 s and the reserve.
  [[nodiscard]] bool calls_home(const FlightState& s, double before_s = 0.0) const;

  /// What the budget asks of a hover with the miniUGV out.
  enum class HoverCall {
    kGoOn,     ///< the battery covers the miniUGV's work for now
    kRecall,   ///< call the miniUGV back (once a release)
    kLiftOut,  ///< the battery covers only the lift and the way home: reel it in now
  };
  /// One hover step with the miniUGV out, `released_m` of tether paid out.
  [[nodiscard]] HoverCall while_hovering(const FlightState& s, const UgvReport& r,
                                         double released_m);
  /// A new release: the miniUGV has not been called back yet.
  void miniugv_released() { recalled_ = false; }

  /// The battery as measured at `now_s` (every tick): the budget learns how much faster
  /// than the endurance says the battery drains over the last minute (a failing or cold
  /// battery, a sag), and keeps that much more for the way home.
  void observe(double now_s, double battery_fraction);
  /// 1 for a healthy battery, else the measured drain over a healthy one's.
  [[nodiscard]] double drain_factor() const { return drain_factor_; }

 private:
  Options options_;
  Eigen::Vector3d home_W_ = Eigen::Vector3d::Zero();
  bool recalled_ = false;  ///< the miniUGV in this hidden space was called back
  std::deque<std::pair<double, double>> battery_;  ///< (t_s, fraction), a second apart
  double drain_factor_ = 1.0;
};

}  // namespace ferret
