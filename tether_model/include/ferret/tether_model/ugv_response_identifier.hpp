#pragma once
// Which response model (velocity lag, path follower) the miniUGV follows, identified
// online from its messages.

#include <array>
#include <vector>

#include "ferret/tether_model/ugv_position_filter.hpp"

namespace ferret::tether {

/// Which response model the miniUGV follows, identified online from its messages: a
/// bank of fixed-gain filters, one a hypothesis (the obedient robot, and every pair of
/// a velocity lag and a path follower's time constant), each scored by the squared
/// innovations of its position predictions (normalised, capped at 25 per axis) with
/// exponential forgetting over `window_s`. A robot's response is a property of the
/// robot, not of a moment, so the memory is long; the obedient hypothesis wins ties by
/// `prior_log_odds`. Scoring starts after 3 / gain messages, when the filters have
/// forgotten their first position. Off by default (both controllers as published); the
/// MPC turns it on.
struct UgvResponseIdentificationOptions {
  bool enabled = false;
  std::array<double, 6> lags_s = {0.05, 0.1, 0.15, 0.2, 0.3, 0.5};
  /// Path follower time constants; 0: the robot does not steer back onto its path.
  std::array<double, 5> tracking_times_s = {0.0, 0.5, 1.0, 2.0, 4.0};
  double window_s = 20.0;
  double prior_log_odds = 4.0;
  /// The defaults, turned on (the MPC's and the mission's winch's).
  [[nodiscard]] static UgvResponseIdentificationOptions on() {
    UgvResponseIdentificationOptions o;
    o.enabled = true;
    return o;
  }
};

class UgvResponseIdentifier {
 public:
  struct Model {
    double velocity_lag_s = 0.0;  ///< 0: obedient
    double tracking_time_s = 0.0;
    bool operator==(const Model&) const = default;
  };
  /// Throws std::invalid_argument for negative or non-finite hypotheses, a window <= 0.
  UgvResponseIdentifier(const UgvResponseIdentificationOptions& options, double gain,
                        double pose_noise_m);
  /// Scores every hypothesis on one message; returns the most likely model.
  Model update(double t_msg_s, const UgvMotion& measured);
  void reset();
  [[nodiscard]] const Model& best() const { return models_[best_]; }
  /// Log-likelihood of the best model over the obedient one (without the prior).
  [[nodiscard]] double best_log_odds() const;
  /// Every hypothesis ([0] the obedient robot) and its log-likelihood (without the prior).
  [[nodiscard]] const std::vector<Model>& models() const { return models_; }
  [[nodiscard]] double log_likelihood(std::size_t i) const { return -0.5 * score_.at(i); }

 private:
  UgvResponseIdentificationOptions options_;
  double innovation_var_m2_;
  std::vector<Model> models_;  ///< [0] obedient
  std::vector<UgvPositionFilter> filters_;
  std::vector<double> score_;  ///< sum of normalised squared innovations, forgotten
  double t_s_ = 0.0;
  bool started_ = false;
  int messages_ = 0, settle_messages_ = 0;  ///< scored only after settle_messages_
  std::size_t best_ = 0;
};

}  // namespace ferret::tether
