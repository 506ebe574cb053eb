#include <gtest/gtest.h>

#include <cmath>

#include "ferret/core/random.hpp"
#include "ferret/tether_model/tether_controller.hpp"

namespace ferret::tether {
namespace {

TEST(UgvPositionFilter, FixedGainBlendsThePredictionAndTheMeasurement) {
  UgvPositionFilter filter(0.25);
  UgvMotion m;
  m.v_WG = {1.0, 0.0};
  (void)filter.update(0.0, m);  // the first message is taken as it is
  m.p_WG = {0.5, 0.2};          // predicted (0.1, 0) after 0.1 s at 1 m/s
  const UgvMotion e = filter.update(0.1, m);
  EXPECT_NEAR(e.p_WG.x(), 0.1 + 0.25 * 0.4, 1e-12);
  EXPECT_NEAR(e.p_WG.y(), 0.25 * 0.2, 1e-12);
  EXPECT_EQ(e.v_WG, m.v_WG);  // without a lag model: the desired motion, unchanged
}

// A robot at rest told to drive at 0.5 m/s whose velocity loop lags by tau: with the
// lag modelled, a filter that barely trusts the measurements (gain 1e-3) still
// tracks it; without, it runs ahead by tau * 0.5 m/s.
TEST(UgvPositionFilter, AVelocityLagModelTracksALaggingRobot) {
  const double tau = 0.15, dt = 0.02;
  UgvPositionFilter lagged(1e-3, tau), plain(1e-3);
  UgvMotion m;
  (void)lagged.update(0.0, m);
  (void)plain.update(0.0, m);
  m.v_WG = {0.5, 0.0};
  UgvMotion with_lag, without;
  const double s_end = 99 * dt;
  for (int k = 1; k <= 100; ++k) {
    // The command starts with the message at t = dt; s is the time since then.
    // True position: x = 0.5 (s - tau (1 - e^(-s/tau))).
    const double s = (k - 1) * dt;
    m.p_WG = {0.5 * (s - tau * (1.0 - std::exp(-s / tau))), 0.0};
    with_lag = lagged.update(k * dt, m);
    without = plain.update(k * dt, m);
  }
  EXPECT_NEAR(with_lag.p_WG.x(), m.p_WG.x(), 1e-9);
  EXPECT_NEAR(with_lag.v_WG.x(), 0.5 * (1.0 - std::exp(-s_end / tau)), 1e-9);
  EXPECT_NEAR(with_lag.a_WG.x(), 0.5 * std::exp(-s_end / tau) / tau, 1e-9);
  EXPECT_GT(without.p_WG.x() - m.p_WG.x(), 0.5 * 0.5 * tau);
}

// A robot told to drive 0.3 m/s that drives 0.4 m/s, its positions exact. The plain
// fixed-gain filter settles lambda behind it, lambda = (1 - g) (lambda + e dt): lambda =
// (1 - g) e dt / g = 3.8 mm... per cm/s of error, 38 mm here. The velocity-error
// Kalman filter settles where its prediction and correction balance: with its
// steady-state gains K (from the Riccati recursion below), the innovation nu keeps
// e_hat = phi e_hat + K1 nu and the position keeps up, e dt = c e_hat + K0 nu, so
// e_hat = e dt / (c + K0 (1 - phi) / K1), 80 % of e (the Gauss-Markov prior pulls it
// towards zero); the output filter, predicting with w e_hat, trails by
// (1 - g) (e - e_hat) dt / g.
TEST(UgvPositionFilter, TheVelocityErrorFilterConvergesToAConstantError) {
  const double g = 0.05, dt = 0.02, e = 0.1, sigma = 0.1, T = 0.5, r = 1e-4;
  UgvPositionFilter plain(g), robust(g, 0.0, {sigma, T, 0.5, 2.0}, 0.01, dt);
  UgvMotion m;
  m.v_WG = {0.3, 0.0};
  UgvMotion a, b;
  for (int k = 0; k <= 2000; ++k) {
    m.p_WG = {0.4 * k * dt, 0.0};
    a = plain.update(k * dt, m);
    b = robust.update(k * dt, m);
  }
  EXPECT_NEAR(m.p_WG.x() - a.p_WG.x(), (1.0 - g) * e * dt / g, 1e-9);
  // Steady-state gains by hand: the Riccati recursion of the 2-state filter.
  const double phi = std::exp(-dt / T), c = T * (1.0 - phi);
  double p00 = g * r, p01 = 0.0, p11 = sigma * sigma, k0 = 0.0, k1 = 0.0;
  for (int i = 0; i < 5000; ++i) {
    const double a00 = p00 + 2.0 * c * p01 + c * c * p11 + g * g * r / (1.0 - g);
    const double a01 = phi * (p01 + c * p11);
    const double a11 = phi * phi * p11 + sigma * sigma * (1.0 - phi * phi);
    k0 = a00 / (a00 + r);
    k1 = a01 / (a00 + r);
    p00 = a00 - k0 * a00;
    p01 = a01 - k0 * a01;
    p11 = a11 - k1 * a01;
  }
  const double e_hat = e * dt / (c + k0 * (1.0 - phi) / k1);
  EXPECT_NEAR(e_hat, 0.08, 0.005);  // the figure in the comment
  EXPECT_NEAR(robust.raw_velocity_error_mps().x(), e_hat, 1e-6);
  EXPECT_NEAR(robust.raw_velocity_error_mps().y(), 0.0, 1e-12);
  EXPECT_NEAR(robust.velocity_error_variance(), p11, 1e-9);
  EXPECT_GT(robust.velocity_error_weight(), 0.999);
  const double w = robust.velocity_error_weight();
  EXPECT_NEAR(b.v_WG.x(), 0.3 + w * e_hat, 1e-9);
  EXPECT_NEAR(m.p_WG.x() - b.p_WG.x(), (1.0 - g) * (e - w * e_hat) * dt / g, 1e-5);
  // Reset forgets the error and the evidence.
  robust.reset();
  EXPECT_EQ(robust.velocity_error_weight(), 0.0);
  EXPECT_EQ(robust.update(0.0, m).v_WG, m.v_WG);
}

// A robot that does what it says, reported with 1 cm noise: the likelihoods favour
// the smoother fixed-gain filter, the weight of the velocity-error filter stays low
// and the output stays within a fraction of a millimetre of the plain filter's.
TEST(UgvPositionFilter, AnObedientRobotKeepsThePlainFilter) {
  const double g = 0.05, dt = 0.02;
  UgvPositionFilter plain(g), robust(g, 0.0, {0.15, 0.5, 0.5, 4.0}, 0.01, dt);
  Rng rng(3);
  UgvMotion m;
  double worst = 0.0, weight = 0.0;
  for (int k = 0; k <= 3000; ++k) {
    const double t = k * dt;
    // Back and forth in x at up to 0.5 m/s, the desired motion exact.
    m.v_WG = {0.5 * std::cos(t), 0.0};
    m.a_WG = {-0.5 * std::sin(t), 0.0};
    const Eigen::Vector2d truth(0.5 * std::sin(t), 0.0);
    m.p_WG = truth + Eigen::Vector2d(rng.normal(0.0, 0.01), rng.normal(0.0, 0.01));
    const UgvMotion a = plain.update(t, m), b = robust.update(t, m);
    if (k > 50) worst = std::max(worst, (a.p_WG - b.p_WG).norm());
    weight = std::max(weight, k > 50 ? robust.velocity_error_weight() : 0.0);
  }
  EXPECT_LT(worst, 0.5e-3);
  EXPECT_LT(weight, 0.5);
}

}  // namespace
}  // namespace ferret::tether
