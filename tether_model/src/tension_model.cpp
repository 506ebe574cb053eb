#include "ferret/tether_model/tension_model.hpp"

#include <algorithm>

namespace ferret::tether {

double TensionModel::stiffness_npm(double length_m) const {
  return axial_stiffness_n / std::max(length_m, 0.1);  // a few cm of line is not a rigid rod
}

double TensionModel::tension_n(double length_m, double slack_m) const {
  return slack_m >= 0.0 ? 0.0 : stiffness_npm(length_m) * -slack_m;
}

}  // namespace ferret::tether
