#include <gtest/gtest.h>

#include <cmath>

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

}  // namespace
}  // namespace ferret::tether
