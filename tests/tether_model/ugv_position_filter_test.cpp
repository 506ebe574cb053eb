#include "ferret/tether_model/ugv_position_filter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "ferret/core/random.hpp"
#include "ferret/tether_model/ugv_response_identifier.hpp"

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

// The response model's prediction against the robot's equations integrated finely: a
// robot at rest on its path told to drive 0.5 m/s, velocity lag lambda, path follower T
// (v' = (v_d - (p - p_d) / T - v) / lambda). Without a path follower the prediction is
// exact: p = 0.5 (t - lambda (1 - e^(-t / lambda))).
TEST(UgvPositionFilter, TheResponseModelPredictsALaggingPathFollower) {
  const double lambda = 0.15, T = 0.5;
  const std::vector<double> times = {0.0, 0.1, 0.23, 0.4, 0.6};
  const auto desired = [](double t) {
    UgvMotion d;
    d.p_WG = {0.5 * t, 0.0};
    d.v_WG = {0.5, 0.0};
    return d;
  };
  UgvPositionFilter lag_only(0.05), follower(0.05);
  lag_only.set_response_model(lambda, 0.0);
  follower.set_response_model(lambda, T);
  EXPECT_TRUE(follower.models_response());
  (void)lag_only.update(0.0, UgvMotion{});
  (void)follower.update(0.0, UgvMotion{});
  const auto a = lag_only.response(times, desired), b = follower.response(times, desired);
  ASSERT_EQ(a.size(), times.size());
  ASSERT_EQ(b.size(), times.size());
  double p = 0.0, v = 0.0, t = 0.0;
  const double h = 1e-6;
  for (std::size_t i = 0; i < times.size(); ++i) {
    const double s = times[i];
    EXPECT_NEAR(a[i].p_WG.x(), 0.5 * (s - lambda * (1.0 - std::exp(-s / lambda))), 1e-12) << s;
    EXPECT_NEAR(a[i].v_WG.x(), 0.5 * (1.0 - std::exp(-s / lambda)), 1e-12) << s;
    while (t < s - 1e-12) {  // the path follower, integrated finely
      const double a_t = (0.5 - (p - 0.5 * t) / T - v) / lambda;
      p += v * h;
      v += a_t * h;
      t += h;
    }
    EXPECT_NEAR(b[i].p_WG.x(), p, 2e-5) << s;
    EXPECT_NEAR(b[i].v_WG.x(), v, 2e-4) << s;
    EXPECT_EQ(b[i].p_WG.y(), 0.0);
  }
  // The follower steers back: it has caught up more than the lag alone by then.
  EXPECT_GT(b.back().p_WG.x(), a.back().p_WG.x() + 1e-3);
  EXPECT_THROW(follower.set_response_model(-0.1, 0.0), std::invalid_argument);
  EXPECT_THROW(follower.set_response_model(0.1, std::nan("")), std::invalid_argument);
}

// Messages of a robot driving rest-to-rest legs (0.4 m/s, 1 m/s^2, 1 s dwell) for 60 s
// through the equations above, integrated at 1 ms, its positions reported at 50 Hz with
// `noise_m`; returns the identifier after the last message.
UgvResponseIdentifier identify(double lambda, double T, std::uint64_t seed, double noise_m) {
  UgvResponseIdentificationOptions options;
  options.enabled = true;
  UgvResponseIdentifier identifier(options, 0.05, noise_m);
  Rng rng(seed);
  const double h = 1e-3, cruise = 0.4, accel = 1.0;
  // Along x, out and back: trapezoids of 1.2 m (accelerate, cruise, decelerate), 1 s dwell.
  const double ramp = cruise / accel, drive = 1.2 / cruise + ramp, period = 2.0 * (drive + 1.0);
  const auto desired_v = [&](double t, double* a) {
    const double u = std::fmod(t, period);
    const double half = period / 2.0, sign = u < half ? 1.0 : -1.0, w = std::fmod(u, half);
    *a = 0.0;
    if (w >= drive) return 0.0;
    if (w < ramp) {
      *a = sign * accel;
      return sign * accel * w;
    }
    if (w > drive - ramp) {
      *a = -sign * accel;
      return sign * accel * (drive - w);
    }
    return sign * cruise;
  };
  double p = 0.0, v = 0.0, pd = 0.0;
  const int per_message = 20;
  for (int k = 0; k <= 60000; ++k) {
    const double t = k * h;
    double a = 0.0;
    const double vd = desired_v(t, &a);
    if (k % per_message == 0) {
      UgvMotion m;
      m.p_WG = {p + rng.normal(0.0, noise_m), rng.normal(0.0, noise_m)};
      m.v_WG = {vd, 0.0};
      m.a_WG = {a, 0.0};
      (void)identifier.update(t, m);
    }
    if (lambda > 0.0) {
      const double command = vd - (T > 0.0 ? (p - pd) / T : 0.0);
      const double decay = std::exp(-h / lambda);
      p += command * h + (v - command) * lambda * (1.0 - decay);
      v = command + (v - command) * decay;
    } else {
      p += vd * h + 0.5 * a * h * h;  // exactly on its path
      v = vd + a * h;
    }
    pd += vd * h + 0.5 * a * h * h;
  }
  return identifier;
}

// With a precise localiser (2 mm) the identifier names the model the robot was built
// with. With the 1 cm of the tether study, neighbouring hypotheses predict alike on these
// gentle legs (their log-likelihoods over the 20 s window differ by about as much as
// the statistic's own spread, ~30), but it still tells an obedient robot from a
// lagging one by hundreds.
TEST(UgvResponseIdentifier, NamesTheLagAndPathFollowerARobotWasBuiltWith) {
  using Model = UgvResponseIdentifier::Model;
  EXPECT_EQ(identify(0.0, 0.0, 1, 0.002).best(), (Model{0.0, 0.0}));
  EXPECT_EQ(identify(0.15, 1.0, 2, 0.002).best(), (Model{0.15, 1.0}));
  EXPECT_EQ(identify(0.3, 0.0, 3, 0.002).best(), (Model{0.3, 0.0}));
  EXPECT_EQ(identify(0.1, 2.0, 4, 0.002).best(), (Model{0.1, 2.0}));
  EXPECT_EQ(identify(0.0, 0.0, 5, 0.01).best(), (Model{0.0, 0.0}));
  const auto lagging = identify(0.15, 1.0, 6, 0.01);
  EXPECT_GT(lagging.best().velocity_lag_s, 0.0);
  EXPECT_GT(lagging.best_log_odds(), 100.0);
}

TEST(UgvResponseIdentifier, RefusesHypothesesThatAreNotTimes) {
  UgvResponseIdentificationOptions o;
  EXPECT_NO_THROW(UgvResponseIdentifier(o, 0.05, 0.01));
  auto bad = o;
  bad.lags_s[2] = 0.0;
  EXPECT_THROW(UgvResponseIdentifier(bad, 0.05, 0.01), std::invalid_argument);
  bad = o;
  bad.tracking_times_s[1] = -1.0;
  EXPECT_THROW(UgvResponseIdentifier(bad, 0.05, 0.01), std::invalid_argument);
  bad = o;
  bad.window_s = 0.0;
  EXPECT_THROW(UgvResponseIdentifier(bad, 0.05, 0.01), std::invalid_argument);
  bad = o;
  bad.lags_s[0] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(UgvResponseIdentifier(bad, 0.05, 0.01), std::invalid_argument);
  EXPECT_THROW(UgvResponseIdentifier(o, 0.0, 0.01), std::invalid_argument);
}

}  // namespace
}  // namespace ferret::tether
