#pragma once
// A small dense QP solver for the winch MPC (no QP solver is packaged in Debian
// bookworm). Goldfarb-Idnani dual active-set method (Math. Programming 27, 1983):
// start from the unconstrained minimum and add the most violated constraint while
// keeping the active set dual feasible, so no feasible starting point is needed and
// the result is exact up to round-off. Suited to strictly convex problems with tens
// of variables and a few hundred constraint rows.
//
//   minimise  1/2 x' H x + g' x   subject to   lower <= C x <= upper
//
// Box constraints are rows of the identity in C; an infinite bound is ignored.

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <string_view>

namespace ferret::tether {

struct QpResult {
  enum class Status { kOptimal, kInfeasible, kIterationLimit };
  Status status = Status::kInfeasible;
  Eigen::VectorXd x;  ///< the minimiser (last iterate if not optimal)
  Eigen::VectorXd
      multipliers;  ///< per row of C: > 0 lower bound active, < 0 upper; H x + g = C' multipliers
  double objective = 0.0;  ///< 1/2 x' H x + g' x
  int iterations = 0;      ///< constraint additions and removals
  int active_constraints = 0;
};

[[nodiscard]] std::string_view to_string(QpResult::Status status);

/// Factorises H and pre-transforms C once (setup), so repeated solves with new g and
/// bounds (one MPC cycle each) cost only the active-set iterations.
class DenseQpSolver {
 public:
  /// @pre H symmetric positive definite (throws std::invalid_argument otherwise),
  ///      C has H.rows() columns.
  void setup(const Eigen::MatrixXd& H, const Eigen::MatrixXd& C);

  /// Solves for the given linear term and bounds (sizes: n, m, m; lower <= upper).
  /// Throws std::invalid_argument on size mismatch or lower > upper.
  [[nodiscard]] QpResult solve(const Eigen::VectorXd& g, const Eigen::VectorXd& lower,
                               const Eigen::VectorXd& upper) const;

  [[nodiscard]] int num_variables() const { return static_cast<int>(H_.rows()); }
  [[nodiscard]] int num_constraints() const { return static_cast<int>(C_.rows()); }

  /// Constraint violations below this (in the units of C x) count as satisfied.
  double feasibility_tolerance = 1e-9;

 private:
  Eigen::MatrixXd H_;
  Eigen::MatrixXd C_;
  Eigen::LLT<Eigen::MatrixXd> llt_;
  Eigen::MatrixXd W_;          ///< L^-1 C' (n x m), L the Cholesky factor of H
  Eigen::VectorXd row_norms_;  ///< |W_i|, to pick the most violated constraint scale-free
};

}  // namespace ferret::tether
