#include "ferret/tether_model/slack_observer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace ferret::tether {
namespace {

// Defaults: EA 1500 N, hanging weight 0.5 N, guard 1.5 N; pose noise 1 cm through
// a 0.05 filter, speed noise 2 cm/s, 50 Hz: the error of the geometric slack has a
// steady-state variance of ((0.05 * 0.01)^2 + (0.02 * 0.02)^2) / (1 - 0.95^2)
// = 4.2051e-6 m^2 (2.05 mm).
SlackObserver make_observer(bool fusion = true) {
  SlackObserver::Options o;
  o.tension_fusion = fusion;
  return SlackObserver(SlackEstimator{}, o, 0.05, 0.02);
}

TEST(SlackObserver, PriorIsTheGeometricErrorsSteadyState) {
  const SlackObserver obs = make_observer();
  EXPECT_NEAR(obs.bias_variance_m2(), 4.2051282e-6, 1e-12);
  EXPECT_EQ(obs.bias_m(), 0.0);
}

// Hand-computed censored update at g = 0 (the estimate says "just taut") on 5 m
// of line (k = 300 N/m): with x ~ N(0, P), E[max(0, x)] = sd / sqrt(2 pi),
// Var = P / 2 - E^2, Cov(b, max(0, x)) = P / 2.
TEST(SlackObserver, TensionUpdateMatchesTheCensoredGaussianByHand) {
  {
    SlackObserver obs = make_observer();
    // 0.9 N of pull: the line is stretched about 3 mm; one update moves 2.443 mm.
    EXPECT_NEAR(obs.estimate_m(5.0, 5.0, 0.5 + 0.9), -0.0024431536, 1e-9);
    EXPECT_NEAR(obs.bias_variance_m2(), 1.8508236e-6, 1e-12);
  }
  {
    SlackObserver obs = make_observer();
    // No pull at all: "not stretched", so the line is probably a little loose.
    EXPECT_NEAR(obs.estimate_m(5.0, 5.0, 0.5), 0.0009160372, 1e-9);
  }
  {
    SlackObserver obs = make_observer();
    // Geometry says 4 mm stretched (on 4.996 m), the winch feels nothing: nearly
    // back to taut.
    EXPECT_NEAR(obs.estimate_m(4.996, 5.0, 0.5), -0.0003080321, 1e-9);
    EXPECT_NEAR(obs.bias_variance_m2(), 4.4168352e-7, 1e-12);
  }
  {
    SlackObserver obs = make_observer();
    // 1 cm loose and no pull: the tension has nothing to add.
    EXPECT_NEAR(obs.estimate_m(5.01, 5.0, 0.5), 0.01, 1e-12);
    EXPECT_NEAR(obs.bias_variance_m2(), 4.2051282e-6, 1e-12);
  }
}

// A pose estimate off by 3 mm along the line (it says +1 mm, the line is 2 mm
// stretched): noisy tension readings bring the estimate to the truth.
TEST(SlackObserver, NoisyTensionCorrectsABiasedPoseEstimate) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.2);
  SlackObserver obs = make_observer();
  const double k = 1500.0 / 5.0;
  double estimate = 0.0, sum = 0.0;
  for (int i = 0; i < 400; ++i) {
    estimate = obs.estimate_m(5.0 + 0.001, 5.0, 0.5 + k * 0.002 + noise(rng));
    if (i >= 200) sum += estimate;
  }
  EXPECT_NEAR(sum / 200.0, -0.002, 0.0005);
  // Without fusion it is the geometric +1 mm.
  SlackObserver geometric = make_observer(false);
  EXPECT_NEAR(geometric.estimate_m(5.001, 5.0, 0.5 + k * 0.002), 0.001, 1e-12);
}

// |b| is capped (4 steady-state sd = 8.2 mm): a pull the geometry cannot explain
// is not pose noise. Above the guard (a snag) the measured stretch wins as before
// and the bias is left alone.
TEST(SlackObserver, SnagsAreTheGuardsAndTheBiasIsCapped) {
  SlackObserver obs = make_observer();
  // 3 N on 5.2 m (288.5 N/m): 10.4 mm stretch, geometry says 20 cm slack.
  EXPECT_NEAR(obs.estimate_m(5.2, 5.0, 0.5 + 3.0), -0.0104, 1e-12);
  EXPECT_EQ(obs.bias_m(), 0.0);
  // 1.4 N (below the guard) on 12 m (125 N/m) is 11.2 mm of stretch where the
  // geometry says taut, many times over: the bias stops at the cap.
  for (int i = 0; i < 100; ++i) (void)obs.estimate_m(12.0, 12.0, 0.5 + 1.4);
  EXPECT_NEAR(obs.bias_m(), 4.0 * std::sqrt(4.2051282e-6), 1e-9);
  obs.reset();
  EXPECT_EQ(obs.bias_m(), 0.0);
}

TEST(SlackObserver, APullTheModelCannotExplainIsKeptAsAnOffsetAndForgottenSlowly) {
  SlackObserver obs = make_observer();
  // The model says 70 cm of slack on 8 m, the winch feels 5 N: k = 187.5 N/m, so the
  // line is stretched 26.7 mm and the model is short by 0.7267 m.
  const double k = 1500.0 / 8.0, stretch = 5.0 / k;
  EXPECT_NEAR(obs.estimate_m(8.0, 7.3, 0.5 + 5.0), -stretch, 1e-12);
  EXPECT_NEAR(obs.model_offset_m(), 0.7 + stretch, 1e-12);
  // The pull relieved: the line is not 70 cm slack but about taut (the offset less one
  // cycle's 2 mm of decay at 0.1 m/s, and the bias a millimetre at most).
  const double next = obs.estimate_m(8.0, 7.3, 0.5);
  EXPECT_NEAR(obs.model_offset_m(), 0.7 + stretch - 0.1 * 0.02, 1e-12);
  EXPECT_NEAR(next, 0.7 - obs.model_offset_m(), 2e-3);
  // 40 s without a pull: forgotten, the geometry again.
  for (int i = 0; i < 2000; ++i) (void)obs.estimate_m(8.0, 7.3, 0.5);
  EXPECT_EQ(obs.model_offset_m(), 0.0);
  EXPECT_NEAR(obs.estimate_m(8.0, 7.3, 0.5), 0.7, 2e-3);
  (void)obs.estimate_m(8.0, 7.3, 0.5 + 5.0);
  obs.reset();
  EXPECT_EQ(obs.model_offset_m(), 0.0);
}

TEST(SlackObserver, AControllerMayGiveTheOffsetBackFasterButNeverSlowerThanItsOptions) {
  SlackObserver obs = make_observer();
  const double k = 1500.0 / 8.0, stretch = 5.0 / k;
  (void)obs.estimate_m(8.0, 7.3, 0.5 + 5.0);
  ASSERT_NEAR(obs.model_offset_m(), 0.7 + stretch, 1e-12);
  // At 0.3 m/s: 6 mm a 20 ms cycle, and the prediction knows the rate.
  obs.set_give_back_mps(0.3);
  EXPECT_EQ(obs.give_back_mps(), 0.3);
  (void)obs.estimate_m(8.0, 7.3, 0.5);
  EXPECT_NEAR(obs.model_offset_m(), 0.7 + stretch - 0.006, 1e-12);
  EXPECT_NEAR(obs.model_offset_after_m(0.1), obs.model_offset_m() - 0.03, 1e-12);
  EXPECT_EQ(obs.model_offset_rate_mps(0.1), -0.3);
  // Slower than the options', NaN or negative: the options' 0.1 m/s.
  for (const double slow : {0.05, 0.0, -1.0, std::nan("")}) {
    obs.set_give_back_mps(slow);
    EXPECT_EQ(obs.give_back_mps(), 0.1) << slow;
  }
  const double before = obs.model_offset_m();
  (void)obs.estimate_m(8.0, 7.3, 0.5);
  EXPECT_NEAR(obs.model_offset_m(), before - 0.002, 1e-12);
  // A pull holds it whatever the rate.
  obs.set_give_back_mps(0.3);
  (void)obs.estimate_m(8.0, 7.3, 0.5 + 5.0);
  EXPECT_EQ(obs.model_offset_after_m(1.0), obs.model_offset_m());
  // reset() forgets the faster rate.
  obs.reset();
  EXPECT_EQ(obs.give_back_mps(), 0.1);
  // Options that never forget the offset are not overruled.
  SlackObserver::Options never;
  never.model_offset_decay_mps = 0.0;
  SlackObserver keeps(SlackEstimator{}, never, 0.05, 0.02);
  keeps.set_give_back_mps(0.3);
  EXPECT_EQ(keeps.give_back_mps(), 0.0);
}

TEST(SlackObserver, RejectsBadOptions) {
  SlackObserver::Options o;
  EXPECT_THROW(SlackObserver(SlackEstimator{}, o, 0.0, 0.02), std::invalid_argument);
  EXPECT_THROW(SlackObserver(SlackEstimator{}, o, 0.05, 0.0), std::invalid_argument);
  o.tension_noise_n = 0.0;
  EXPECT_THROW(SlackObserver(SlackEstimator{}, o, 0.05, 0.02), std::invalid_argument);
  o = {};
  for (const double bad : {-0.01, std::nan(""), std::numeric_limits<double>::infinity()}) {
    o.model_offset_decay_mps = bad;
    EXPECT_THROW(SlackObserver(SlackEstimator{}, o, 0.05, 0.02), std::invalid_argument) << bad;
  }
}

}  // namespace
}  // namespace ferret::tether
