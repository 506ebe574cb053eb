#pragma once
// The winch controllers' required-length model on the planner's taut tether
// (taut_tether.hpp): the tether state follows the miniUGV as it drives (advance),
// and a query for another position drives a copy of it there, so predictions over
// the MPC horizon wrap and unwrap corners exactly as the real tether would.

#include "ferret/tether_model/required_length.hpp"
#include "ferret/tether_model/taut_tether.hpp"

namespace ferret::tether {

class TautTetherLengthModel final : public RequiredLengthModel {
 public:
  /// @param entry_offset_m l_0, tether from the winch to the entry point.
  TautTetherLengthModel(TautTether tether, double entry_offset_m)
      : tether_(std::move(tether)), entry_offset_m_(entry_offset_m) {}

  /// Moves the tracked tether with the miniUGV (call with each new pose).
  void advance(const Eigen::Vector2d& p_WG) { tether_.move_to(p_WG); }

  [[nodiscard]] double required_length_m(const Eigen::Vector2d& p_WG) const override {
    TautTether copy = tether_;
    copy.move_to(p_WG);
    return entry_offset_m_ + copy.length_m();
  }
  [[nodiscard]] const TautTether& tether() const { return tether_; }

 private:
  TautTether tether_;
  double entry_offset_m_;
};

}  // namespace ferret::tether
