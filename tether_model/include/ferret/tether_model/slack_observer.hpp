#pragma once
// The slack with the winch tension fused in (a censored Kalman filter).

#include <algorithm>

#include "ferret/tether_model/slack_estimator.hpp"

namespace ferret::tether {

/// The slack the controllers act on, with the winch tension fused in: a one-state
/// censored (Tobit) Kalman filter on the error b of the geometric slack, s = g - b.
/// b comes from the pose estimate (UgvPositionFilter's error projected on the tether,
/// an AR(1) process with the filter's time constant) and from the latency
/// extrapolation (the miniUGV's velocity error). The tension measures the stretch
/// k * max(0, -s) now, without the link's latency, and says nothing more than "not
/// stretched" while the line is slack; the update uses the exact mean and covariance
/// of that rectified measurement under the Gaussian prior, so it is informative on
/// both sides of taut and never pulls the estimate past what the tension allows.
/// A pull above the SlackEstimator guard (a snag) is left to the guard, and |b| is
/// capped at a few standard deviations: larger errors are not pose noise.
class SlackObserver {
 public:
  struct Options {
    bool tension_fusion = true;         ///< false: the geometric SlackEstimator alone
    double pose_noise_m = 0.01;         ///< assumed std of a reported position, per axis
    double tension_noise_n = 0.2;       ///< assumed std of the current-based tension
    double ugv_speed_noise_mps = 0.02;  ///< assumed miniUGV velocity error (process noise)
    double max_bias_sigmas = 4.0;       ///< cap of |b| in steady-state standard deviations
    /// A pull above the guard that the pose error cannot explain is the required-length
    /// model falling short (a corner the miniUGV's map has not seen): the shortfall is
    /// kept as a model offset, so the winch does not reel the line taut again, and
    /// forgotten at this rate (m/s) while the line is not pulling (0: never).
    double model_offset_decay_mps = 0.1;
  };

  SlackObserver(const SlackEstimator& estimator, const Options& options, double pose_filter_gain,
                double control_period_s);
  /// One control cycle: the estimate of s = l_t - l_req (call once a cycle).
  [[nodiscard]] double estimate_m(double released_m, double required_m, double winch_tension_n);
  void reset();
  [[nodiscard]] double bias_m() const { return bias_m_; }
  /// How much longer than the model the tether was found to be (>= 0).
  [[nodiscard]] double model_offset_m() const { return offset_m_; }
  /// The model offset `ahead_s` after the last cycle, and its rate then: given back at
  /// give_back_mps() unless the last cycle's line was pulling (then held).
  [[nodiscard]] double model_offset_after_m(double ahead_s) const {
    return pulling_ ? offset_m_ : std::max(0.0, offset_m_ - give_back_mps_ * ahead_s);
  }
  [[nodiscard]] double model_offset_rate_mps(double ahead_s) const {
    return model_offset_after_m(ahead_s) > 0.0 && !pulling_ ? -give_back_mps_ : 0.0;
  }
  /// The rate the model offset is given back at from the next cycle on: never below
  /// model_offset_decay_mps (NaN or less: that rate), and not at all when that is 0. A
  /// controller that knows the offset cannot be a corner its model lacks gives it back
  /// faster (TautTetherMpc).
  void set_give_back_mps(double rate_mps) {
    const double base = options_.model_offset_decay_mps;
    give_back_mps_ = base > 0.0 && rate_mps > base ? rate_mps : base;
  }
  [[nodiscard]] double give_back_mps() const { return give_back_mps_; }
  [[nodiscard]] double bias_variance_m2() const { return variance_m2_; }
  /// Largest |b| the observer accepts as pose error (larger: not pose noise).
  [[nodiscard]] double max_bias_m() const;

 private:
  SlackEstimator estimator_;
  Options options_;
  double decay_ = 0.0;       ///< AR(1) factor of b a cycle: 1 - pose filter gain
  double process_m2_ = 0.0;  ///< variance b gains a cycle
  double steady_m2_ = 0.0;   ///< variance of b without tension information
  double bias_m_ = 0.0, variance_m2_ = 0.0;
  double offset_m_ = 0.0;
  double give_back_mps_ = 0.0;  ///< the model offset's rate of decay (set_give_back_mps)
  bool pulling_ = false;        ///< the last cycle's pull was above the guard
  double control_period_s_ = 0.02;
};

}  // namespace ferret::tether
