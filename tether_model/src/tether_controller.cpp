#include "ferret/tether_model/tether_controller.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>


namespace ferret::tether {

double TensionModel::stiffness_npm(double length_m) const {
  return axial_stiffness_n / std::max(length_m, 0.1);  // a few cm of line is not a rigid rod
}

double TensionModel::tension_n(double length_m, double slack_m) const {
  return slack_m >= 0.0 ? 0.0 : stiffness_npm(length_m) * -slack_m;
}

double ReelInGuard::worst_loss_m(double u_mps, double rate_mps, const WinchLimits& limits) const {
  // Stepped: the two speed profiles are piecewise linear with a delay and saturation,
  // and the loss is the area where the miniUGV's runs ahead of the spool's.
  constexpr double kDt = 0.005;
  const double a_spool = spool_acceleration_fraction * limits.max_acceleration_mps2;
  // Beyond the spool's own speed no slack protects the line: that is the tension guard's.
  const double top = std::min(std::max(rate_mps, ugv_speed_mps), limits.max_speed_mps);
  double u = u_mps, r = rate_mps, loss = 0.0;
  for (double t = 0.0; t < 10.0; t += kDt) {
    if (r >= top && u >= r) break;  // caught up with a miniUGV at full speed
    loss += std::max(0.0, r - u) * kDt;
    r = std::min(top, r + ugv_acceleration_mps2 * kDt);
    if (t >= reaction_s) u = std::min(limits.max_speed_mps, u + a_spool * kDt);
  }
  return loss;
}

double ReelInGuard::limit(double command, double slack_m, double rate_mps, const WinchLimits& limits,
                          double lo, double hi) const {
  if (!on() || !std::isfinite(slack_m) || !std::isfinite(rate_mps)) return command;
  const double budget = slack_m - min_slack_m;
  if (command >= hi || worst_loss_m(command, rate_mps, limits) <= budget) return command;
  if (worst_loss_m(hi, rate_mps, limits) > budget) return std::max(command, hi);
  double a = std::max(command, lo), b = hi;  // the loss falls as the command rises
  for (int i = 0; i < 30; ++i) {
    const double m = 0.5 * (a + b);
    (worst_loss_m(m, rate_mps, limits) <= budget ? b : a) = m;
  }
  return std::max(command, b);
}

double SlackEstimator::estimate_m(double released_m, double required_m,
                                  double winch_tension_n) const {
  const double geometric = released_m - required_m;
  const double pull = winch_tension_n - tension.hanging_weight_n;
  if (pull <= guard_n) return geometric;
  return std::min(geometric, -pull / tension.stiffness_npm(released_m));
}

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

UgvResponseIdentifier::UgvResponseIdentifier(const UgvResponseIdentificationOptions& options,
                                             double gain, double pose_noise_m)
    : options_(options) {
  const auto bad = [](double x) { return !(x >= 0.0) || !std::isfinite(x); };
  if (!(options_.window_s > 0.0) || !std::isfinite(options_.window_s) ||
      !std::isfinite(options_.prior_log_odds) || !(gain > 0.0 && gain <= 1.0))
    throw std::invalid_argument("UgvResponseIdentifier: window must be > 0, prior finite");
  for (const double x : options_.lags_s)
    if (bad(x) || x == 0.0) throw std::invalid_argument("UgvResponseIdentifier: lags must be > 0");
  for (const double x : options_.tracking_times_s)
    if (bad(x)) throw std::invalid_argument("UgvResponseIdentifier: tracking times must be >= 0");
  // The fixed-gain filter's steady-state innovation variance, r / (1 - g).
  innovation_var_m2_ = std::pow(std::max(pose_noise_m, 1e-4), 2) / (1.0 - std::min(gain, 0.999));
  settle_messages_ = static_cast<int>(std::ceil(3.0 / gain));
  models_.push_back({});
  for (const double lag : options_.lags_s)
    for (const double tracking : options_.tracking_times_s) models_.push_back({lag, tracking});
  for (const auto& m : models_) {
    filters_.emplace_back(gain);
    filters_.back().set_response_model(m.velocity_lag_s, m.tracking_time_s);
  }
  reset();
}

void UgvResponseIdentifier::reset() {
  for (auto& f : filters_) f.reset();
  score_.assign(models_.size(), 0.0);
  started_ = false;
  messages_ = 0;
  best_ = 0;
}

UgvResponseIdentifier::Model UgvResponseIdentifier::update(double t_msg_s,
                                                           const UgvMotion& measured) {
  if (started_ && t_msg_s < t_s_) reset();  // time ran backwards: start again
  const double forget = started_ ? std::exp(-(t_msg_s - t_s_) / options_.window_s) : 1.0;
  started_ = true;
  t_s_ = t_msg_s;
  // Until the fixed-gain filters have forgotten their first, noisy position (a few of
  // their time constants), their innovations say more about that than about the model.
  const bool settled = messages_ >= settle_messages_;
  if (!settled) ++messages_;
  for (std::size_t i = 0; i < filters_.size(); ++i) {
    filters_[i].update(t_msg_s, measured);
    if (!settled) continue;
    const Eigen::Vector2d& nu = filters_[i].innovation_m();
    double s = 0.0;
    for (int a = 0; a < 2; ++a) s += std::min(nu[a] * nu[a] / innovation_var_m2_, 25.0);
    score_[i] = forget * score_[i] + s;
  }
  // Log-likelihood -score / 2; the obedient robot gets the prior.
  best_ = 0;
  double best_ll = -0.5 * score_[0] + options_.prior_log_odds;
  for (std::size_t i = 1; i < score_.size(); ++i)
    if (-0.5 * score_[i] > best_ll) {
      best_ll = -0.5 * score_[i];
      best_ = i;
    }
  return models_[best_];
}

double UgvResponseIdentifier::best_log_odds() const {
  return 0.5 * (score_[0] - score_[best_]);
}

TetherStateEstimator::TetherStateEstimator(const TautControlOptions& options)
    : pose_filter(options.pose_filter_gain, options.ugv_velocity_lag_s, options.ugv_velocity_error,
                  options.slack_observer.pose_noise_m, options.control_period_s),
      slack_observer(options.slack_estimator, options.slack_observer, options.pose_filter_gain,
                     options.control_period_s),
      fixed_model_{options.ugv_velocity_lag_s, options.ugv_tracking_time_s} {
  pose_filter.set_response_model(options.ugv_velocity_lag_s, options.ugv_tracking_time_s);
  if (options.ugv_response_identification.enabled)
    response_identifier.emplace(options.ugv_response_identification, options.pose_filter_gain,
                                options.slack_observer.pose_noise_m);
}

void TetherStateEstimator::reset() {
  pose_filter.reset();
  pose_filter.set_response_model(fixed_model_.velocity_lag_s, fixed_model_.tracking_time_s);
  slack_observer.reset();
  if (response_identifier) response_identifier->reset();
}

UgvMotion TetherStateEstimator::filter_pose(double t_msg_s, const UgvMotion& measured) {
  if (response_identifier) {
    const auto m = response_identifier->update(t_msg_s, measured);
    pose_filter.set_response_model(m.velocity_lag_s, m.tracking_time_s);
  }
  return pose_filter.update(t_msg_s, measured);
}

}  // namespace ferret::tether
