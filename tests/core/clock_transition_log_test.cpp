#include <gtest/gtest.h>

#include "ferret/core/clock.hpp"
#include "ferret/core/transition_log.hpp"

namespace ferret {
namespace {

TEST(SimClock, AdvancesAndNeverRunsBackwards) {
  SimClock c;
  EXPECT_EQ(c.now_s(), 0.0);
  c.advance(0.25);
  c.advance(-1.0);
  EXPECT_DOUBLE_EQ(c.now_s(), 0.25);
  c.set(0.1);
  EXPECT_DOUBLE_EQ(c.now_s(), 0.25);
  c.set(3 * 0.1);
  EXPECT_EQ(c.now_s(), 3 * 0.1);
}

TEST(TransitionLog, KeepsOrderTellsTheListenerAndFormatsOneLine) {
  TransitionLog log;
  int heard = 0;
  log.on_transition([&](const Transition& t) {
    ++heard;
    EXPECT_EQ(t.component, "ugv");
  });
  log.add({1.5, "ugv", "explore", "track", "lambda2"});
  log.add({2.0, "ugv", "track", "turn", ""});
  EXPECT_EQ(heard, 2);
  ASSERT_EQ(log.all().size(), 2u);
  EXPECT_EQ(log.all()[1].from, "track");
  EXPECT_EQ(TransitionLog::format(log.all()[0]), "    1.50 s  ugv  explore -> track  (lambda2)");
  EXPECT_EQ(TransitionLog::format(log.all()[1]), "    2.00 s  ugv  track -> turn");
}

}  // namespace
}  // namespace ferret
