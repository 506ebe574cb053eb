#include "ferret/tether_model/tether_controller.hpp"

#include <algorithm>
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
    initialised_ = true;
    t_s_ = t_msg_s;
    estimate_ = measured;
    return measured;
  }
  const double dt = t_msg_s - t_s_;
  // Predict with the previous desired motion, then correct with the measurement.
  Eigen::Vector2d predicted = estimate_.p_WG + estimate_.v_WG * dt + 0.5 * estimate_.a_WG * dt * dt;
  estimate_ = measured;
  estimate_.p_WG = predicted + gain_ * (measured.p_WG - predicted);
  t_s_ = t_msg_s;
  return estimate_;
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
