#include "ferret/tether_model/qp_solver.hpp"

#include <Eigen/QR>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace ferret::tether {

std::string_view to_string(QpResult::Status status) {
  switch (status) {
    case QpResult::Status::kOptimal:
      return "optimal";
    case QpResult::Status::kInfeasible:
      return "infeasible";
    case QpResult::Status::kIterationLimit:
      return "iteration limit";
  }
  return "?";
}

void DenseQpSolver::setup(const Eigen::MatrixXd& H, const Eigen::MatrixXd& C) {
  if (H.rows() != H.cols() || H.rows() == 0)
    throw std::invalid_argument("QP: H must be square and non-empty");
  if (C.cols() != H.rows()) throw std::invalid_argument("QP: C must have as many columns as H");
  if (!H.isApprox(H.transpose(), 1e-12)) throw std::invalid_argument("QP: H must be symmetric");
  llt_.compute(H);
  if (llt_.info() != Eigen::Success) throw std::invalid_argument("QP: H must be positive definite");
  H_ = H;
  C_ = C;
  W_ = llt_.matrixL().solve(C.transpose());
  row_norms_ = W_.colwise().norm().transpose();
}

namespace {

// One inequality n' x >= b taken from row `row` of C: side +1 is C_i x >= lower_i,
// side -1 is -C_i x >= -upper_i.
struct Side {
  int row = 0;
  double sign = 1.0;
};

}  // namespace

QpResult DenseQpSolver::solve(const Eigen::VectorXd& g, const Eigen::VectorXd& lower,
                              const Eigen::VectorXd& upper) const {
  const Eigen::Index n = H_.rows(), m = C_.rows();
  if (n == 0) throw std::invalid_argument("QP: setup() was not called");
  if (g.size() != n || lower.size() != m || upper.size() != m)
    throw std::invalid_argument("QP: g, lower or upper has the wrong size");
  for (Eigen::Index i = 0; i < m; ++i)
    if (lower[i] > upper[i])
      throw std::invalid_argument("QP: lower bound above upper bound in row " + std::to_string(i));

  const auto U = llt_.matrixU();
  QpResult result;
  // Unconstrained minimum x = -H^-1 g.
  Eigen::VectorXd x = -llt_.solve(g);

  std::vector<Side> active;
  Eigen::VectorXd u(0);     // multipliers of the active set
  Eigen::MatrixXd B(n, 0);  // columns sign * W_i of the active constraints
  Eigen::HouseholderQR<Eigen::MatrixXd> qr;
  auto rebuild = [&] {
    B.resize(n, static_cast<Eigen::Index>(active.size()));
    for (std::size_t j = 0; j < active.size(); ++j)
      B.col(static_cast<Eigen::Index>(j)) = active[j].sign * W_.col(active[j].row);
    if (B.cols() > 0) qr.compute(B);
  };
  auto slack = [&](const Side& s, const Eigen::VectorXd& Cx) {
    return s.sign > 0 ? Cx[s.row] - lower[s.row] : upper[s.row] - Cx[s.row];
  };
  std::vector<char> is_active(static_cast<std::size_t>(2 * m), 0);
  auto flag = [&](const Side& s) -> char& {
    return is_active[static_cast<std::size_t>(2 * s.row + (s.sign > 0 ? 0 : 1))];
  };

  const int max_iterations = static_cast<int>(10 * (n + m) + 50);
  const double inf = std::numeric_limits<double>::infinity();
  result.status = QpResult::Status::kIterationLimit;
  while (result.iterations < max_iterations) {
    // Step 1: the most violated constraint (violation relative to |L^-1 n|).
    const Eigen::VectorXd Cx = C_ * x;
    Side p;
    double worst = 0.0;
    for (Eigen::Index i = 0; i < m; ++i) {
      const double scale = std::max(row_norms_[i], 1e-300);
      for (const double sign : {1.0, -1.0}) {
        const Side s{static_cast<int>(i), sign};
        const double bound = sign > 0 ? lower[i] : upper[i];
        if (!std::isfinite(bound) || flag(s)) continue;
        const double v = slack(s, Cx);
        if (v < -feasibility_tolerance && v / scale < worst) {
          worst = v / scale;
          p = s;
        }
      }
    }
    if (worst == 0.0) {
      result.status = QpResult::Status::kOptimal;
      break;
    }

    // Step 2: move towards satisfying p, dropping active constraints whose
    // multipliers would turn negative.
    Eigen::VectorXd u_plus(u.size() + 1);
    u_plus << u, 0.0;
    bool added = false;
    while (!added && result.iterations < max_iterations) {
      ++result.iterations;
      const Eigen::VectorXd w = p.sign * W_.col(p.row);
      Eigen::VectorXd r(static_cast<Eigen::Index>(active.size()));
      Eigen::VectorXd z_hat = w;
      if (!active.empty()) {
        r = qr.solve(w);
        z_hat = w - B * r;
      }
      const double z_norm2 = z_hat.squaredNorm();
      // Partial step: the first active multiplier to reach zero.
      double t1 = inf;
      Eigen::Index k = -1;
      for (Eigen::Index j = 0; j < r.size(); ++j) {
        if (r[j] > 1e-12 && u_plus[j] / r[j] < t1) {
          t1 = u_plus[j] / r[j];
          k = j;
        }
      }
      const double cx_p = C_.row(p.row).dot(x);
      const double s_p = p.sign > 0 ? cx_p - lower[p.row] : upper[p.row] - cx_p;
      const double t2 = z_norm2 > 1e-14 ? -s_p / z_norm2 : inf;
      const double t = std::min(t1, t2);
      if (!std::isfinite(t)) {
        result.status = QpResult::Status::kInfeasible;
        break;
      }
      if (z_norm2 > 1e-14) x += t * U.solve(z_hat);  // primal direction H^-1 (I - N N*) n_p
      u_plus.head(r.size()) -= t * r;
      u_plus[u_plus.size() - 1] += t;
      if (t2 <= t1) {
        flag(p) = 1;
        active.push_back(p);
        u = u_plus;
        rebuild();
        added = true;
      } else {
        flag(active[static_cast<std::size_t>(k)]) = 0;
        active.erase(active.begin() + k);
        Eigen::VectorXd shrunk(u_plus.size() - 1);
        shrunk << u_plus.head(k), u_plus.tail(u_plus.size() - 1 - k);
        u_plus = shrunk;
        rebuild();
      }
    }
    if (!added) u = u_plus.head(static_cast<Eigen::Index>(active.size()));
    if (result.status == QpResult::Status::kInfeasible) break;
  }

  result.x = x;
  result.multipliers = Eigen::VectorXd::Zero(m);
  for (std::size_t j = 0; j < active.size(); ++j)
    result.multipliers[active[j].row] += active[j].sign * u[static_cast<Eigen::Index>(j)];
  result.objective = 0.5 * x.dot(H_ * x) + g.dot(x);
  result.active_constraints = static_cast<int>(active.size());
  return result;
}

}  // namespace ferret::tether
