#include "ferret/tether_model/ugv_response_identifier.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ferret::tether {

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

double UgvResponseIdentifier::best_log_odds() const { return 0.5 * (score_[0] - score_[best_]); }

}  // namespace ferret::tether
