#include "ferret/tether_model/tether_controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ferret/tether_model/feedforward_pid.hpp"
#include "ferret/tether_model/taut_mpc.hpp"

namespace ferret::tether {

double TensionModel::stiffness_npm(double length_m) const {
  return axial_stiffness_n / std::max(length_m, 0.1);  // a few cm of line is not a rigid rod
}

double TensionModel::tension_n(double length_m, double slack_m) const {
  return slack_m >= 0.0 ? 0.0 : stiffness_npm(length_m) * -slack_m;
}

double SlackEstimator::estimate_m(double released_m, double required_m,
                                  double winch_tension_n) const {
  const double geometric = released_m - required_m;
  const double pull = winch_tension_n - tension.hanging_weight_n;
  if (pull <= guard_n) return geometric;
  return std::min(geometric, -pull / tension.stiffness_npm(released_m));
}

UgvMotion UgvPositionFilter::update(double t_msg_s, const UgvMotion& measured) {
  if (!initialised_ || gain_ >= 1.0 || t_msg_s < t_s_) {
    // A raw position still gets the lag model's velocity when it has one.
    const bool keep_velocity = initialised_ && lag_s_ > 0.0 && t_msg_s >= t_s_;
    if (!keep_velocity) velocity_ = measured.v_WG;
    initialised_ = true;
    t_s_ = t_msg_s;
    estimate_ = measured;
    return output();
  }
  const double dt = t_msg_s - t_s_;
  // Predict with the previous desired motion, then correct with the measurement.
  Eigen::Vector2d predicted;
  if (lag_s_ > 0.0) {
    // v' = (v_d - v) / lag with v_d held: exact over dt.
    const double decay = std::exp(-dt / lag_s_);
    predicted = estimate_.p_WG + estimate_.v_WG * dt +
                (velocity_ - estimate_.v_WG) * lag_s_ * (1.0 - decay);
    velocity_ = estimate_.v_WG + (velocity_ - estimate_.v_WG) * decay;
  } else {
    predicted = estimate_.p_WG + estimate_.v_WG * dt + 0.5 * estimate_.a_WG * dt * dt;
  }
  estimate_ = measured;
  estimate_.p_WG = predicted + gain_ * (measured.p_WG - predicted);
  t_s_ = t_msg_s;
  return output();
}

UgvMotion UgvPositionFilter::output() const {
  if (!(lag_s_ > 0.0)) return estimate_;
  UgvMotion out = estimate_;
  out.v_WG = velocity_;
  out.a_WG = (estimate_.v_WG - velocity_) / lag_s_;
  return out;
}

std::unique_ptr<TetherController> make_tether_controller(
    std::string_view name, const TautControlOptions& options,
    std::shared_ptr<const RequiredLengthModel> model) {
  if (name == "mpc") {
    TautTetherMpc::Options o;
    o.control = options;
    return std::make_unique<TautTetherMpc>(o, std::move(model));
  }
  if (name == "baseline") {
    FeedForwardPid::Options o;
    o.control = options;
    return std::make_unique<FeedForwardPid>(o, std::move(model));
  }
  throw std::invalid_argument("unknown tether controller '" + std::string(name) +
                              "' (expected mpc or baseline)");
}

std::vector<std::string> tether_controller_names() { return {"mpc", "baseline"}; }

}  // namespace ferret::tether
