#include "ferret/tether_model/slack_observer.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace ferret::tether {

SlackObserver::SlackObserver(const SlackEstimator& estimator, const Options& options,
                             double pose_filter_gain, double control_period_s)
    : estimator_(estimator), options_(options) {
  if (!(pose_filter_gain > 0.0 && pose_filter_gain <= 1.0) || !(control_period_s > 0.0) ||
      !(options.pose_noise_m >= 0.0) || !(options.tension_noise_n > 0.0) ||
      !(options.ugv_speed_noise_mps >= 0.0) || !(options.max_bias_sigmas > 0.0) ||
      !(options.model_offset_decay_mps >= 0.0) || !std::isfinite(options.model_offset_decay_mps))
    throw std::invalid_argument("SlackObserver: bad options");
  control_period_s_ = control_period_s;
  decay_ = 1.0 - pose_filter_gain;
  const double velocity_m = options.ugv_speed_noise_mps * control_period_s;
  process_m2_ = std::pow(pose_filter_gain * options.pose_noise_m, 2) + velocity_m * velocity_m;
  steady_m2_ = process_m2_ / (1.0 - decay_ * decay_);
  reset();
}

double SlackObserver::max_bias_m() const {
  return options_.max_bias_sigmas * std::sqrt(steady_m2_);
}

void SlackObserver::reset() {
  bias_m_ = 0.0;
  variance_m2_ = steady_m2_;
  offset_m_ = 0.0;
  give_back_mps_ = options_.model_offset_decay_mps;
  pulling_ = false;
}

double SlackObserver::estimate_m(double released_m, double required_m, double winch_tension_n) {
  const double geometric = released_m - required_m;
  if (!options_.tension_fusion || !(steady_m2_ > 0.0))
    return estimator_.estimate_m(released_m, required_m, winch_tension_n);
  bias_m_ *= decay_;
  variance_m2_ = decay_ * decay_ * variance_m2_ + process_m2_;
  const double pull = winch_tension_n - estimator_.tension.hanging_weight_n;
  pulling_ = pull > estimator_.guard_n;
  if (!pulling_) {
    // Stretch x = -s = b - g ~ N(m, P); the winch measures y = k max(0, x) + noise.
    const double k = estimator_.tension.stiffness_npm(released_m);
    const double m = bias_m_ - geometric, sd = std::sqrt(variance_m2_);
    const double z = m / sd;
    const double cdf = 0.5 * std::erfc(-z / std::sqrt(2.0));
    const double pdf = std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi);
    const double mean_plus = m * cdf + sd * pdf;
    const double var_plus =
        std::max(0.0, (m * m + variance_m2_) * cdf + m * sd * pdf - mean_plus * mean_plus);
    const double cov = variance_m2_ * cdf;  // Cov(b, max(0, x)) = P Phi(m / sd)
    const double innovation_var =
        k * k * var_plus + options_.tension_noise_n * options_.tension_noise_n;
    const double gain = k * cov / innovation_var;
    bias_m_ += gain * (pull - k * mean_plus);
    variance_m2_ = std::max(variance_m2_ - gain * k * cov, 1e-12);
    bias_m_ = std::clamp(bias_m_, -max_bias_m(), max_bias_m());
    offset_m_ = std::max(0.0, offset_m_ - give_back_mps_ * control_period_s_);
  } else {
    // Taut: the line is as long as it is stretched, x = pull / k past l_t, so the model
    // (with its bias) is short by g + x; the part the bias cannot hold is the offset.
    const double stretch_m = pull / estimator_.tension.stiffness_npm(released_m);
    offset_m_ = std::max(offset_m_, geometric + stretch_m - bias_m_);
  }
  // The guard still decides a snag: above it the measured stretch wins.
  return estimator_.estimate_m(released_m, required_m + bias_m_ + offset_m_, winch_tension_n);
}

}  // namespace ferret::tether
