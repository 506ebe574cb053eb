#pragma once
// Taut-tether MPC for the winch (paper sect. III, tether mechanism; after Glick et
// al.'s unified tether model): from the miniUGV's pose, desired velocity and desired
// acceleration it predicts the required length over the horizon and chooses spool
// velocity commands that keep the slack in [0, s_max] within the servo's speed and
// acceleration limits and 0 <= l_t <= L. Condensed QP (only the commands are
// variables), solved by DenseQpSolver each cycle; docs/tether.md has the formulation.

#include <Eigen/Core>
#include <memory>

#include "ferret/tether_model/qp_solver.hpp"
#include "ferret/tether_model/taut_control_options.hpp"
#include "ferret/tether_model/tether_controller.hpp"
#include "ferret/tether_model/tether_state_estimator.hpp"

namespace ferret::tether {

class TautTetherMpc final : public TetherController {
 public:
  struct Options {
    TautControlOptions control;
    int horizon = 20;               ///< N prediction steps
    double prediction_dt_s = 0.02;  ///< N * dt = 0.4 s look-ahead by default
    double acceleration_time_s =
        0.1;  ///< how long the miniUGV's desired acceleration is assumed to last
    /// Predict along the miniUGV's planned motion when its messages carry it
    /// (TetherObservation::ugv_preview); false: from the desired velocity and
    /// acceleration alone, as the paper's interface has it.
    bool use_preview = true;
    /// The miniUGV's velocity error, estimated from its reported positions and added to
    /// the velocity the MPC predicts with (over the latency and the horizon; with a
    /// preview, to the planned velocity): the MPC's own pose filter replaces
    /// control.ugv_velocity_error with this. sigma_mps 0 turns it off.
    UgvVelocityErrorOptions ugv_velocity_error = UgvVelocityErrorOptions::estimated();
    /// The miniUGV's response model (velocity lag, path follower) identified online
    /// from its messages; the prediction then simulates it. Replaces
    /// control.ugv_response_identification.
    UgvResponseIdentificationOptions ugv_response_identification =
        UgvResponseIdentificationOptions::on();
    /// A snag's length held as the observer's model offset is given back at the speed
    /// from which the spool stops before the tension limit should the offset be real
    /// (LineCatchLimit::for_winch, for a line `give_back_stiffness_factor` times as
    /// stiff as modelled), while the miniUGV reports that its line cannot be longer than
    /// its model by more than that limit's stretch (TetherObservation::slack_margin_m):
    /// then the offset is a pin that has let go or holds still, not a corner the
    /// model lacks. Otherwise, and with false, at the observer's own rate.
    bool give_back_at_stopping_speed = true;
    double give_back_stiffness_factor = 2.0;
    double weight_slack = 100.0;       ///< on (slack - reference)^2 per step, 1/m^2
    double weight_command_rate = 2.0;  ///< on (delta command)^2, (s/m)^2
    /// Along the miniUGV's plan (a preview), the command-rate penalty is on the
    /// command's change less that of the command tracking the prediction exactly:
    /// corrections are damped, the feed-forward is not smoothed (docs/tether.md, the
    /// MPC's cost). false: on the command's change alone, as before 2026-12-06.
    bool rate_penalty_about_tracking_command = true;
    double weight_feedforward = 0.05;    ///< on (command - required-length rate)^2
    double weight_terminal = 5.0;        ///< extra slack weight on the last step (multiplier)
    double soft_linear_weight = 2000.0;  ///< exact-penalty weight of the soft slack bounds
    /// Exact-penalty weight of the lower slack bound (slack >= 0) alone. 0 by default:
    /// the bound sits at the slack reference, where the estimate's noise crosses it
    /// every cycle, and an exact penalty there makes the controller answer a noisy
    /// "stretched" harder than a noisy "slack": a biased, larger slack RMS for no
    /// gain in peak tension (docs/results.md, Tether control).
    double stretch_linear_weight = 0.0;
    double soft_quadratic_weight = 2000.0;
    double length_linear_weight =
        1e5;  ///< penalty of l_t outside [0, L] (soft only to stay solvable)
    double length_quadratic_weight = 1e6;
  };

  TautTetherMpc(Options options, std::shared_ptr<const RequiredLengthModel> model);

  [[nodiscard]] std::string_view name() const override { return "mpc"; }
  void reset() override;
  [[nodiscard]] double step(const TetherObservation& obs) override;

  /// The QP of the last step, for tests and the benchmark.
  [[nodiscard]] const QpResult& last_solution() const { return last_; }
  /// Predicted l_t over the horizon for the last solution (N values).
  [[nodiscard]] Eigen::VectorXd predicted_released_m() const;
  /// Required lengths the last step predicted (N values, k = 1..N).
  [[nodiscard]] const Eigen::VectorXd& predicted_required_m() const { return required_; }
  /// Cycles where the QP failed (iteration limit) and the fallback (brake) was used.
  [[nodiscard]] int fallback_count() const { return fallbacks_; }
  /// The pose filter, slack observer and (when on) the response identification.
  [[nodiscard]] const TetherStateEstimator& estimator() const { return estimator_; }
  [[nodiscard]] const Options& options() const { return options_; }

 private:
  void build();

  Options options_;
  std::shared_ptr<const RequiredLengthModel> model_;
  TetherStateEstimator estimator_;
  DenseQpSolver solver_;
  int n_ = 0;  ///< QP variables: N commands + 3 soft-constraint slacks (e_lo, e_hi, e_len)
  // l_k = l_free_k + Phi_l.row(k) u and v_k likewise: the condensed dynamics.
  Eigen::MatrixXd Phi_l_;
  Eigen::VectorXd free_l_from_l_, free_l_from_v_;
  Eigen::MatrixXd H_;
  // Constraint row blocks of C (see build()).
  int row_rate_ = 0, row_length_ = 0, row_length_lo_ = 0, row_slack_lo_ = 0, row_slack_hi_ = 0,
      row_box_ = 0, row_soft_ = 0, rows_ = 0;
  Eigen::VectorXd required_;
  Eigen::VectorXd required_rate_;
  /// Along the plan: the required length's rate over each step, and the command that
  /// tracks it exactly (N + 1 values from now; scratch of step()).
  Eigen::VectorXd tracking_rate_, tracking_command_;
  QpResult last_;
  double last_command_mps_ = 0.0;
  Eigen::VectorXd last_free_l_;  ///< free response of l_t in the last step
  int fallbacks_ = 0;
};

}  // namespace ferret::tether
