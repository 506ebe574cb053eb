#include "ferret/tether_model/qp_solver.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "ferret/core/random.hpp"

namespace ferret::tether {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Eigen::MatrixXd M(std::initializer_list<std::initializer_list<double>> rows) {
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows.size()),
                    static_cast<Eigen::Index>(rows.begin()->size()));
  Eigen::Index i = 0;
  for (const auto& r : rows) {
    Eigen::Index j = 0;
    for (const double v : r) m(i, j++) = v;
    ++i;
  }
  return m;
}
Eigen::VectorXd V(std::initializer_list<double> v) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (const double x : v) out[i++] = x;
  return out;
}

// KKT conditions of  min 1/2 x'Hx + g'x  s.t.  lo <= Cx <= hi  with multipliers y:
// Hx + g = C'y, lo <= Cx <= hi, y_i > 0 only at a lower bound, y_i < 0 only at an upper one.
void expect_kkt(const Eigen::MatrixXd& H, const Eigen::VectorXd& g, const Eigen::MatrixXd& C,
                const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, const QpResult& r,
                double tol = 1e-7) {
  ASSERT_EQ(r.status, QpResult::Status::kOptimal);
  EXPECT_LT((H * r.x + g - C.transpose() * r.multipliers).norm(), tol) << "stationarity";
  const Eigen::VectorXd Cx = C * r.x;
  for (Eigen::Index i = 0; i < C.rows(); ++i) {
    EXPECT_GE(Cx[i], lo[i] - tol) << "row " << i;
    EXPECT_LE(Cx[i], hi[i] + tol) << "row " << i;
    if (r.multipliers[i] > tol) {
      EXPECT_NEAR(Cx[i], lo[i], tol) << "complementarity, row " << i;
    }
    if (r.multipliers[i] < -tol) {
      EXPECT_NEAR(Cx[i], hi[i], tol) << "complementarity, row " << i;
    }
  }
}

TEST(DenseQpSolver, UnconstrainedMinimum) {
  const Eigen::MatrixXd H = M({{4, 1}, {1, 2}});
  const Eigen::VectorXd g = V({1, 1});
  DenseQpSolver qp;
  qp.setup(H, Eigen::MatrixXd::Identity(2, 2));
  const auto r = qp.solve(g, V({-kInf, -kInf}), V({kInf, kInf}));
  ASSERT_EQ(r.status, QpResult::Status::kOptimal);
  // H x = -g: x = (-1/7, -3/7).
  EXPECT_NEAR(r.x[0], -1.0 / 7.0, 1e-12);
  EXPECT_NEAR(r.x[1], -3.0 / 7.0, 1e-12);
  EXPECT_EQ(r.active_constraints, 0);
  EXPECT_NEAR(r.objective, 0.5 * r.x.dot(H * r.x) + g.dot(r.x), 1e-12);
}

TEST(DenseQpSolver, BoxConstraintsByHand) {
  // min (x1 - 1)^2 + (x2 - 2)^2 with x <= 0.5: x = (0.5, 0.5); H x + g = (-1, -3) = multipliers.
  const Eigen::MatrixXd H = 2.0 * Eigen::MatrixXd::Identity(2, 2);
  const Eigen::VectorXd g = V({-2, -4});
  DenseQpSolver qp;
  qp.setup(H, Eigen::MatrixXd::Identity(2, 2));
  const auto r = qp.solve(g, V({-kInf, -kInf}), V({0.5, 0.5}));
  ASSERT_EQ(r.status, QpResult::Status::kOptimal);
  EXPECT_NEAR(r.x[0], 0.5, 1e-12);
  EXPECT_NEAR(r.x[1], 0.5, 1e-12);
  EXPECT_NEAR(r.multipliers[0], -1.0, 1e-12);
  EXPECT_NEAR(r.multipliers[1], -3.0, 1e-12);
  EXPECT_EQ(r.active_constraints, 2);
  // Only the second bound binds when the first is loose.
  const auto r2 = qp.solve(g, V({-kInf, -kInf}), V({3.0, 0.5}));
  EXPECT_NEAR(r2.x[0], 1.0, 1e-12);
  EXPECT_NEAR(r2.x[1], 0.5, 1e-12);
  EXPECT_NEAR(r2.multipliers[0], 0.0, 1e-12);
  EXPECT_EQ(r2.active_constraints, 1);
}

TEST(DenseQpSolver, GeneralInequalityByHand) {
  // min x1^2 + x2^2 s.t. x1 + x2 >= 1: x = (0.5, 0.5), multiplier 1 (H x = (1, 1) = 1 * (1, 1)).
  const Eigen::MatrixXd H = 2.0 * Eigen::MatrixXd::Identity(2, 2);
  DenseQpSolver qp;
  qp.setup(H, M({{1, 1}}));
  const auto r = qp.solve(V({0, 0}), V({1}), V({kInf}));
  ASSERT_EQ(r.status, QpResult::Status::kOptimal);
  EXPECT_NEAR(r.x[0], 0.5, 1e-12);
  EXPECT_NEAR(r.x[1], 0.5, 1e-12);
  EXPECT_NEAR(r.multipliers[0], 1.0, 1e-12);
  EXPECT_NEAR(r.objective, 0.5, 1e-12);
}

TEST(DenseQpSolver, OnlyTheBindingConstraintIsActive) {
  // min (x1 - 2)^2 + (x2 - 1)^2 s.t. x1 + x2 <= 2, x1 - x2 >= 0.5, x2 <= 0.9. By hand:
  // on x1 + x2 = 2 the minimiser of the objective is (1.5, 0.5), where x1 - x2 = 1 >= 0.5
  // holds, so only the first constraint is active, with multiplier -1 (upper side).
  const Eigen::MatrixXd H = 2.0 * Eigen::MatrixXd::Identity(2, 2);
  const Eigen::VectorXd g = V({-4, -2});
  const Eigen::MatrixXd C = M({{1, 1}, {1, -1}, {0, 1}});
  const Eigen::VectorXd lo = V({-kInf, 0.5, -kInf}), hi = V({2, kInf, 0.9});
  DenseQpSolver qp;
  qp.setup(H, C);
  const auto r = qp.solve(g, lo, hi);
  EXPECT_NEAR(r.x[0], 1.5, 1e-10);
  EXPECT_NEAR(r.x[1], 0.5, 1e-10);
  EXPECT_NEAR(r.multipliers[0], -1.0, 1e-10);
  expect_kkt(H, g, C, lo, hi, r);
}

TEST(DenseQpSolver, EqualityAsEqualBoundsAndRedundantRows) {
  // min x1^2 + x2^2 + x3^2 s.t. x1 + x2 + x3 = 3 (twice): x = (1, 1, 1).
  const Eigen::MatrixXd H = 2.0 * Eigen::MatrixXd::Identity(3, 3);
  const Eigen::MatrixXd C = M({{1, 1, 1}, {1, 1, 1}});
  DenseQpSolver qp;
  qp.setup(H, C);
  const auto r = qp.solve(Eigen::VectorXd::Zero(3), V({3, 3}), V({3, 3}));
  ASSERT_EQ(r.status, QpResult::Status::kOptimal);
  EXPECT_LT((r.x - Eigen::Vector3d(1, 1, 1)).norm(), 1e-10);
  EXPECT_NEAR(r.multipliers.sum(), 2.0, 1e-10);  // the two rows share the multiplier
}

TEST(DenseQpSolver, ReportsInfeasibleProblems) {
  // x >= 1 and x <= 0 on the same variable through two rows.
  DenseQpSolver qp;
  qp.setup(Eigen::MatrixXd::Identity(1, 1), M({{1}, {1}}));
  const auto r = qp.solve(V({0}), V({1, -kInf}), V({kInf, 0}));
  EXPECT_EQ(r.status, QpResult::Status::kInfeasible);
}

TEST(DenseQpSolver, RandomProblemsSatisfyKkt) {
  Rng rng(42);
  int drops = 0;  // partial steps that removed a constraint from the active set
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 3 + trial % 8, m = 2 * n + 3;
    Eigen::MatrixXd A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = rng.normal(0, 1);
    const Eigen::MatrixXd H = A * A.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
    Eigen::MatrixXd C(m, n);
    Eigen::VectorXd g(n), lo(m), hi(m);
    for (int j = 0; j < n; ++j) g[j] = rng.normal(0, 5);
    for (int i = 0; i < m; ++i) {
      for (int j = 0; j < n; ++j) C(i, j) = rng.normal(0, 1);
      // Bounds around zero keep x = 0 feasible, so every problem has a solution.
      lo[i] = rng.bernoulli(0.3) ? -kInf : -rng.uniform(0.1, 2.0);
      hi[i] = rng.bernoulli(0.3) ? kInf : rng.uniform(0.1, 2.0);
    }
    DenseQpSolver qp;
    qp.setup(H, C);
    const auto r = qp.solve(g, lo, hi);
    SCOPED_TRACE("trial " + std::to_string(trial));
    expect_kkt(H, g, C, lo, hi, r, 1e-6);
    drops += r.iterations - r.active_constraints;
  }
  EXPECT_GT(drops, 0) << "the random problems should exercise constraint removal";
}

TEST(DenseQpSolver, RejectsBadInput) {
  DenseQpSolver qp;
  EXPECT_THROW(qp.setup(M({{1, 0}, {0, -1}}), Eigen::MatrixXd::Identity(2, 2)),
               std::invalid_argument);
  EXPECT_THROW(qp.setup(M({{1, 2}, {0, 1}}), Eigen::MatrixXd::Identity(2, 2)),
               std::invalid_argument);
  EXPECT_THROW(qp.setup(Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Identity(3, 3)),
               std::invalid_argument);
  qp.setup(Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Identity(2, 2));
  EXPECT_THROW((void)qp.solve(V({0, 0}), V({1, 0}), V({0, 1})), std::invalid_argument);  // lo > hi
  EXPECT_THROW((void)qp.solve(V({0}), V({0, 0}), V({1, 1})), std::invalid_argument);
}

}  // namespace
}  // namespace ferret::tether
