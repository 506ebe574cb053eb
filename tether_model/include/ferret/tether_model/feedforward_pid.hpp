#pragma once
// The comparison baseline: velocity feed-forward from the miniUGV's desired velocity
// (the rate of the required length), plus a PID on the slack error, saturated to the
// servo's speed and acceleration limits with conditional-integration anti-windup.
// The miniUGV position is latency-compensated with its velocity like the MPC does
// (without the acceleration): a fair, tuned baseline, not a straw man. Gains: see
// docs/tether.md (tuned by a grid search over the shipped trajectories).

#include <memory>

#include "ferret/tether_model/taut_control_options.hpp"
#include "ferret/tether_model/tether_controller.hpp"
#include "ferret/tether_model/tether_state_estimator.hpp"

namespace ferret::tether {

class FeedForwardPid final : public TetherController {
 public:
  struct Options {
    TautControlOptions control;
    double kp_per_s = 16.0;    ///< m/s of command per m of slack error
    double ki_per_s2 = 128.0;  ///< m/s of command per m*s of integrated error
    double kd = 0.05;          ///< m/s of command per m/s of error rate
    double feedforward_gain = 1.0;
    double integral_limit_m_s = 0.2;
    /// Latency-compensate with the miniUGV's planned motion when sent (an ablation:
    /// off by default, the classic feed-forward uses the desired velocity).
    bool use_preview = false;
  };

  FeedForwardPid(Options options, std::shared_ptr<const RequiredLengthModel> model);

  [[nodiscard]] std::string_view name() const override { return "baseline"; }
  void reset() override;
  [[nodiscard]] double step(const TetherObservation& obs) override;
  [[nodiscard]] const Options& options() const { return options_; }

 private:
  Options options_;
  std::shared_ptr<const RequiredLengthModel> model_;
  TetherStateEstimator estimator_;
  double integral_m_s_ = 0.0;
  double last_error_m_ = 0.0;
  bool has_last_ = false;
  double last_command_mps_ = 0.0;
};

}  // namespace ferret::tether
