#include "ferret/link/watchdog.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "ferret/core/clock.hpp"

namespace ferret::link {
namespace {

TEST(LinkWatchdog, APeerNeverHeardIsSilent) {
  SimClock clock;
  const Watchdog w(clock, 0.3);
  EXPECT_TRUE(w.expired());
  EXPECT_FALSE(w.ever_heard());
  EXPECT_TRUE(std::isinf(w.since_heard_s()));
}

TEST(LinkWatchdog, ExpiresWithinOneTickOfItsTimeout) {
  // Ticks that do not divide the timeout, and ones that do: at the first tick at which it
  // has expired, the time since it was heard lies in (timeout, timeout + dt].
  for (const double dt : {0.05, 0.01, 0.033, 0.1, 0.07}) {
    for (const double timeout : {0.3, 0.5}) {
      SimClock clock;
      Watchdog w(clock, timeout);
      int k = 7;
      clock.set(k * dt);
      w.heard();
      const double heard_at = clock.now_s();
      EXPECT_FALSE(w.expired());
      while (!w.expired()) {
        clock.set(++k * dt);
        ASSERT_LT(k, 10'000);
      }
      // The tick before did not expire it (the loop), this one did.
      EXPECT_GT(w.since_heard_s(), timeout) << "dt " << dt << " timeout " << timeout;
      EXPECT_LE(w.since_heard_s(), timeout + dt + 1e-12) << "dt " << dt << " timeout " << timeout;
      EXPECT_EQ(w.since_heard_s(), clock.now_s() - heard_at);
    }
  }
}

TEST(LinkWatchdog, HearingAgainRearmsItAndResetForgets) {
  SimClock clock;
  Watchdog w(clock, 0.5);
  w.heard();
  clock.advance(0.4);
  w.heard();
  clock.advance(0.4);  // 0.8 s since the first, 0.4 s since the last
  EXPECT_FALSE(w.expired());
  clock.advance(0.2);
  EXPECT_TRUE(w.expired());
  w.heard();
  EXPECT_FALSE(w.expired());
  w.reset();
  EXPECT_TRUE(w.expired());
  EXPECT_FALSE(w.ever_heard());
}

TEST(LinkWatchdog, RefusesATimeoutThatIsNotPositive) {
  SimClock clock;
  EXPECT_THROW(Watchdog(clock, 0.0), std::invalid_argument);
  EXPECT_THROW(Watchdog(clock, -1.0), std::invalid_argument);
  EXPECT_THROW(Watchdog(clock, std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace ferret::link
