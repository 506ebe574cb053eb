#include "ferret/tether_model/ugv_position_filter.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ferret::tether {

UgvPositionFilter::UgvPositionFilter(double gain, double velocity_lag_s,
                                     const UgvVelocityErrorOptions& velocity_error,
                                     double pose_noise_m, double period_s)
    : gain_(gain), lag_s_(velocity_lag_s), error_options_(velocity_error) {
  if (error_options_.sigma_mps > 0.0) {
    if (!std::isfinite(error_options_.sigma_mps) || !(error_options_.time_s > 0.0) ||
        !(pose_noise_m >= 0.0) || !(period_s > 0.0) || !(gain > 0.0) ||
        !(error_options_.window_s > 0.0) || !std::isfinite(error_options_.prior_log_odds) ||
        !std::isfinite(error_options_.prior_log_odds_with_lag) ||
        !(error_options_.long_window_s > 0.0))
      throw std::invalid_argument("UgvPositionFilter: bad velocity-error options");
    // The random-walk position noise whose steady-state Kalman gain is `gain` (a
    // cycle of period_s): P- = g r / (1 - g) = P+ + q with P+ = g r. Noise-free
    // positions are taken as 0.1 mm (the filter needs some measurement noise).
    const double g = std::min(gain, 0.999);
    r_m2_ = std::pow(std::max(pose_noise_m, 1e-4), 2);
    q_p_m2_per_s_ = g * g * r_m2_ / (1.0 - g) / period_s;
    P0_ << g * r_m2_, 0.0, 0.0, error_options_.sigma_mps * error_options_.sigma_mps;
  }
  reset();
}

void UgvPositionFilter::reset() {
  initialised_ = false;
  innovation_.setZero();
  forget_velocity_error();
}

void UgvPositionFilter::forget_velocity_error() {
  error_.setZero();
  P_ = P0_;
  log_odds_ = 0.0;
  long_log_odds_ = 0.0;
  weight_ = 0.0;
}

void UgvPositionFilter::advance_desired_path(double dt) {
  desired_p_WG_ += estimate_.v_WG * dt + 0.5 * estimate_.a_WG * dt * dt;
}

UgvMotion UgvPositionFilter::update(double t_msg_s, const UgvMotion& measured) {
  const bool kalman = error_options_.sigma_mps > 0.0;
  const bool restart = !initialised_ || t_msg_s < t_s_;
  if (restart || gain_ >= 1.0) {
    if (restart) {
      forget_velocity_error();
      velocity_ = measured.v_WG;
      desired_p_WG_ = measured.p_WG;
    } else {
      // A raw position still gets the lag model's velocity when it has one.
      if (lag_s_ == 0.0) velocity_ = measured.v_WG;
      advance_desired_path(t_msg_s - t_s_);
    }
    kalman_p_WG_ = obedient_p_WG_ = measured.p_WG;
    initialised_ = true;
    t_s_ = t_msg_s;
    estimate_ = measured;
    return output();
  }
  const double dt = t_msg_s - t_s_;
  // Predict with the previous desired motion, then correct with the measurement.
  Eigen::Vector2d plain;
  if (lag_s_ > 0.0) {
    // v' = (v_c - v) / lag, the command v_c the desired velocity less the path
    // follower's pull back onto the desired path, changing at the desired acceleration
    // less the follower's reaction to the velocity error.
    Eigen::Vector2d rate = estimate_.a_WG;
    if (tracking_time_s_ > 0.0) rate -= (velocity_ - estimate_.v_WG) / tracking_time_s_;
    plain = estimate_.p_WG;
    lagged_velocity_step(plain, velocity_, commanded_velocity(), rate, lag_s_, dt);
  } else {
    plain = estimate_.p_WG + estimate_.v_WG * dt + 0.5 * estimate_.a_WG * dt * dt;
  }
  const Eigen::Vector2d displacement = plain - estimate_.p_WG;  // the model's motion
  // The fixed-gain estimate, predicted with the velocity error as far as it is
  // believed (w e of the previous message; without the error filter w = 0 and this
  // is the filter as it always was, to the bit).
  const Eigen::Vector2d predicted = plain + weight_ * error_ * dt;
  innovation_ = measured.p_WG - predicted;
  if (kalman) {
    // Position and velocity error e per axis (both axes share the covariance P):
    // e' = -e / T + noise, p' = v_model + e, exact over dt. Its own position state, so
    // that the fixed-gain estimate above stays as smooth as without it.
    const double T = error_options_.time_s, phi = std::exp(-dt / T), c = T * (1.0 - phi);
    const Eigen::Vector2d kf_predicted = kalman_p_WG_ + displacement + error_ * c;
    error_ *= phi;
    Eigen::Matrix2d F;
    F << 1.0, c, 0.0, phi;
    Eigen::Matrix2d Q = Eigen::Matrix2d::Zero();
    Q(0, 0) = q_p_m2_per_s_ * dt;
    Q(1, 1) = error_options_.sigma_mps * error_options_.sigma_mps * (1.0 - phi * phi);
    P_ = F * P_ * F.transpose() + Q;
    const double S = P_(0, 0) + r_m2_;
    const Eigen::Vector2d K = P_.col(0) / S;
    const Eigen::Vector2d innovation = measured.p_WG - kf_predicted;
    // Log-likelihood ratio of this message, Kalman filter against the fixed-gain
    // filter of an obedient robot (its own state, without the error; steady-state
    // innovation variance r / (1 - g)), per axis capped.
    const double S_fixed = r_m2_ / (1.0 - std::min(gain_, 0.999));
    const Eigen::Vector2d obedient_predicted = obedient_p_WG_ + displacement;
    const Eigen::Vector2d fixed_innovation = measured.p_WG - obedient_predicted;
    obedient_p_WG_ = obedient_predicted + gain_ * fixed_innovation;
    double llr = 0.0;
    for (int i = 0; i < 2; ++i)
      llr += -0.5 * std::min(innovation[i] * innovation[i] / S, 25.0) - 0.5 * std::log(S) +
             0.5 * std::min(fixed_innovation[i] * fixed_innovation[i] / S_fixed, 25.0) +
             0.5 * std::log(S_fixed);
    log_odds_ = std::exp(-dt / error_options_.window_s) * log_odds_ + llr;
    // Over a long memory the same evidence says whether the robot keeps deviating.
    long_log_odds_ = std::exp(-dt / error_options_.long_window_s) * long_log_odds_ + llr;
    const bool disobedient = lag_s_ > 0.0 || long_log_odds_ > error_options_.prior_log_odds;
    const double prior =
        disobedient ? error_options_.prior_log_odds_with_lag : error_options_.prior_log_odds;
    weight_ = 1.0 / (1.0 + std::exp(prior - log_odds_));
    kalman_p_WG_ = kf_predicted + K[0] * innovation;
    error_ += K[1] * innovation;
    const Eigen::Matrix2d P = P_ - K * P_.row(0);
    P_ = 0.5 * (P + P.transpose());
  }
  // The desired path moves on with the previous message's desired motion.
  advance_desired_path(dt);
  estimate_ = measured;
  estimate_.p_WG = predicted + gain_ * (measured.p_WG - predicted);
  t_s_ = t_msg_s;
  return output();
}

UgvMotion UgvPositionFilter::desired_at_message() const {
  UgvMotion d = estimate_;
  d.p_WG = desired_p_WG_;
  return d;
}

Eigen::Vector2d UgvPositionFilter::commanded_velocity() const {
  Eigen::Vector2d v = estimate_.v_WG;
  if (tracking_time_s_ > 0.0) v -= (estimate_.p_WG - desired_p_WG_) / tracking_time_s_;
  return v;
}

void UgvPositionFilter::set_response_model(double velocity_lag_s, double tracking_time_s) {
  if (!(velocity_lag_s >= 0.0) || !(tracking_time_s >= 0.0) || !std::isfinite(velocity_lag_s) ||
      !std::isfinite(tracking_time_s))
    throw std::invalid_argument("UgvPositionFilter: lag and tracking time must be finite and >= 0");
  // A filter that starts to model a lag starts from the velocity the old model had.
  if (lag_s_ == 0.0 && velocity_lag_s > 0.0 && initialised_) velocity_ = estimate_.v_WG;
  lag_s_ = velocity_lag_s;
  tracking_time_s_ = tracking_time_s;
}

UgvMotion UgvPositionFilter::output() const {
  UgvMotion out = estimate_;
  if (lag_s_ > 0.0) {
    out.v_WG = velocity_;
    out.a_WG = (commanded_velocity() - velocity_) / lag_s_;
  }
  if (weight_ > 0.0) out.v_WG += weight_ * error_;
  return out;
}

}  // namespace ferret::tether
