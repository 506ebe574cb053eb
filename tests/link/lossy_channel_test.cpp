#include "ferret/link/lossy_channel.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace ferret::link {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes numbered(std::uint32_t i) {
  return {static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(i >> 8), 0xAA};
}
std::uint32_t number_of(const Bytes& b) { return b[0] | (b[1] << 8); }

// Sends one datagram a step, n steps, then drains; returns what arrived, in order.
std::vector<Bytes> run(LossyChannel& channel, std::uint32_t n) {
  std::vector<Bytes> out;
  for (std::uint32_t i = 0; i < n; ++i) {
    channel.send(numbered(i));
    for (auto& d : channel.deliver()) out.push_back(std::move(d));
  }
  while (channel.in_flight() > 0)
    for (auto& d : channel.deliver()) out.push_back(std::move(d));
  return out;
}

TEST(LinkLossyChannel, APerfectChannelDeliversEverythingInOrderOneStepLater) {
  LossyChannel channel;
  channel.send(numbered(1));
  channel.send(numbered(2));
  const auto first = channel.deliver();
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(number_of(first[0]), 1u);
  EXPECT_EQ(number_of(first[1]), 2u);
  EXPECT_TRUE(channel.deliver().empty());
  const auto all = run(channel, 500);
  ASSERT_EQ(all.size(), 500u);
  for (std::uint32_t i = 0; i < 500; ++i) EXPECT_EQ(all[i], numbered(i));
}

TEST(LinkLossyChannel, TheSameSeedGivesTheSameDeliveriesAndAnotherSeedOthers) {
  LossyChannelOptions o;
  o.drop_fraction = 0.2;
  o.duplicate_fraction = 0.1;
  o.reorder_fraction = 0.2;
  o.corrupt_fraction = 0.1;
  o.seed = 7;
  LossyChannel a(o), b(o);
  const auto run_a = run(a, 2000);
  EXPECT_EQ(run_a, run(b, 2000));
  o.seed = 8;
  LossyChannel c(o);
  EXPECT_NE(run_a, run(c, 2000));
}

TEST(LinkLossyChannel, DropsDuplicatesAndDamagesTheFractionsAskedFor) {
  LossyChannelOptions o;
  o.drop_fraction = 0.3;
  o.duplicate_fraction = 0.2;
  o.corrupt_fraction = 0.1;
  LossyChannel channel(o);
  const std::uint32_t n = 20'000;
  const auto out = run(channel, n);
  const auto& k = channel.counters();
  // Binomial counts: 5 standard deviations of n = 20000 are under 0.02 of n.
  EXPECT_NEAR(static_cast<double>(k.dropped) / n, 0.3, 0.02);
  EXPECT_NEAR(static_cast<double>(k.duplicated) / (n - k.dropped), 0.2, 0.02);
  EXPECT_NEAR(static_cast<double>(k.corrupted) / (n - k.dropped + k.duplicated), 0.1, 0.02);
  EXPECT_EQ(out.size(), n - k.dropped + k.duplicated);
  EXPECT_EQ(k.delivered, out.size());
  std::uint64_t damaged = 0;
  for (const auto& d : out)
    if (d.size() != 3 || d[2] != 0xAA || number_of(d) >= n) ++damaged;
  EXPECT_LE(damaged, k.corrupted);  // a damage may leave a datagram that looks intact
  EXPECT_GT(damaged, k.corrupted / 2);
}

TEST(LinkLossyChannel, AHeldBackDatagramArrivesAfterLaterOnes) {
  LossyChannelOptions o;
  o.reorder_fraction = 0.3;
  o.max_reorder_delay = 4;
  LossyChannel channel(o);
  const auto out = run(channel, 5000);
  ASSERT_EQ(out.size(), 5000u);  // nothing lost
  std::size_t out_of_order = 0;
  std::uint32_t newest = 0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const std::uint32_t number = number_of(out[i]);
    if (i > 0 && number < newest) {
      ++out_of_order;
      EXPECT_LE(newest - number, 4u);  // never later than max_reorder_delay steps
    }
    newest = std::max(newest, number);
  }
  // Only held-back datagrams come out of order; one held back while the datagrams
  // after it were held back longer arrives in order.
  EXPECT_LE(out_of_order, channel.counters().reordered);
  EXPECT_GT(out_of_order, channel.counters().reordered * 7 / 10);
  EXPECT_GT(out_of_order, 1000u);
}

TEST(LinkLossyChannel, CorruptAlwaysChangesTheBytes) {
  Rng rng(3);
  for (int i = 0; i < 20'000; ++i) {
    const Bytes original = numbered(static_cast<std::uint32_t>(i));
    Bytes d = original;
    const Corruption kind = corrupt(d, rng);
    ASSERT_NE(d, original) << to_string(kind);
  }
  Bytes empty;
  corrupt(empty, Corruption::kTruncate, rng);
  EXPECT_FALSE(empty.empty());  // nothing to cut: it grows instead
}

TEST(LinkLossyChannel, RefusesFractionsOutsideZeroToOne) {
  LossyChannelOptions o;
  o.drop_fraction = 1.5;
  EXPECT_THROW(LossyChannel{o}, std::invalid_argument);
  o = {};
  o.reorder_fraction = -0.1;
  EXPECT_THROW(LossyChannel{o}, std::invalid_argument);
  o = {};
  o.max_reorder_delay = 0;
  EXPECT_THROW(LossyChannel{o}, std::invalid_argument);
}

// -- Impairments: a fault plan's link faults, on top of the options.

// Sends one datagram a step for n steps (no drain); for each, the delivery it arrived in
// (none: lost), with the impairment set by `impaired(step)` before the step.
template <class Impaired>
std::vector<std::optional<std::uint32_t>> arrivals(LossyChannel& channel, std::uint32_t n,
                                                   Impaired impaired) {
  std::vector<std::optional<std::uint32_t>> at(n);
  for (std::uint32_t step = 0; step < n + 64; ++step) {
    channel.set_impairment(impaired(step));
    if (step < n) channel.send(numbered(step));
    for (const auto& d : channel.deliver())
      if (number_of(d) < n && !at[number_of(d)]) at[number_of(d)] = step;
  }
  return at;
}

TEST(LinkLossyChannel, NoImpairmentKeepsEveryDrawOfTheOptions) {
  LossyChannelOptions o;
  o.drop_fraction = 0.2;
  o.duplicate_fraction = 0.1;
  o.reorder_fraction = 0.2;
  o.corrupt_fraction = 0.1;
  o.seed = 11;
  LossyChannel plain(o), cleared(o), delayed(o);
  cleared.set_impairment({});
  LinkImpairment late;
  late.latency_deliveries = 3;
  delayed.set_impairment(late);
  const auto a = run(plain, 2000);
  EXPECT_EQ(a, run(cleared, 2000));
  // Delayed, the same datagrams arrive with the same damage: the options' draws are
  // the same, only later.
  const auto sorted = [](const std::vector<Bytes>& datagrams) {
    std::vector<std::string> out;
    for (const Bytes& d : datagrams) out.emplace_back(d.begin(), d.end());
    std::sort(out.begin(), out.end());
    return out;
  };
  EXPECT_EQ(sorted(a), sorted(run(delayed, 2000)));
  EXPECT_EQ(delayed.counters().impaired, 0u);
}

TEST(LinkLossyChannel, AnOutageLetsNothingThroughWhileItLasts) {
  LossyChannel c;
  const auto at = arrivals(c, 300, [](std::uint32_t step) {
    LinkImpairment i;
    i.outage = step >= 100 && step < 160;
    return i;
  });
  for (std::uint32_t k = 0; k < 300; ++k) {
    if (k >= 100 && k < 160) {
      EXPECT_FALSE(at[k]) << k;
    } else {
      ASSERT_TRUE(at[k]) << k;
      EXPECT_EQ(*at[k], k) << k;  // one step later, as always
    }
  }
  EXPECT_EQ(c.counters().impaired, 60u);
  EXPECT_EQ(c.counters().dropped, 60u);
}

TEST(LinkLossyChannel, ImpairedLossIsTheFractionAskedForWithOrWithoutBursts) {
  for (const double burst : {0.0, 20.0}) {
    LinkImpairment i;
    i.drop_fraction = 0.3;
    i.burst_deliveries = burst;
    LossyChannel c;
    const auto at = arrivals(c, 40000, [&](std::uint32_t) { return i; });
    int lost = 0, runs = 0;
    for (std::size_t k = 0; k < at.size(); ++k)
      if (!at[k]) {
        ++lost;
        if (k == 0 || at[k - 1]) ++runs;
      }
    EXPECT_NEAR(lost / 40000.0, 0.3, 0.03) << burst;
    const double mean_run = static_cast<double>(lost) / runs;
    if (burst > 0.0) {
      EXPECT_NEAR(mean_run, 20.0, 4.0);  // the mean burst
    } else {
      EXPECT_LT(mean_run, 2.0);  // independent: runs of 1/(1 - 0.3) on average
    }
  }
  LinkImpairment all;
  all.drop_fraction = 1.0;
  all.burst_deliveries = 5.0;
  LossyChannel c;
  for (const auto& a : arrivals(c, 500, [&](std::uint32_t) { return all; })) EXPECT_FALSE(a);
}

TEST(LinkLossyChannel, LatencyAndJitterDelayEachDatagram) {
  LinkImpairment i;
  i.latency_deliveries = 5;
  LossyChannel fixed;
  const auto at = arrivals(fixed, 200, [&](std::uint32_t) { return i; });
  for (std::uint32_t k = 0; k < 200; ++k) {
    ASSERT_TRUE(at[k]);
    EXPECT_EQ(*at[k], k + 5);
  }
  i.jitter_deliveries = 4;
  LossyChannel jittery;
  const auto j = arrivals(jittery, 2000, [&](std::uint32_t) { return i; });
  std::set<std::uint32_t> delays;
  bool reordered = false;
  for (std::uint32_t k = 0; k < 2000; ++k) {
    ASSERT_TRUE(j[k]);
    delays.insert(*j[k] - k);
    if (k > 0 && *j[k] < *j[k - 1]) reordered = true;
  }
  EXPECT_EQ(delays, (std::set<std::uint32_t>{5, 6, 7, 8, 9}));
  EXPECT_TRUE(reordered);
}

TEST(LinkLossyChannel, ImpairedDuplicatesAreTheFractionAskedFor) {
  LinkImpairment i;
  i.duplicate_fraction = 0.25;
  LossyChannel c;
  c.set_impairment(i);
  const auto out = run(c, 20000);
  EXPECT_NEAR((out.size() - 20000.0) / 20000.0, 0.25, 0.02);
  EXPECT_EQ(c.counters().duplicated, out.size() - 20000);
}

TEST(LinkLossyChannel, RefusesABadImpairment) {
  LossyChannel c;
  LinkImpairment i;
  i.drop_fraction = 1.5;
  EXPECT_THROW(c.set_impairment(i), std::invalid_argument);
  i = {};
  i.duplicate_fraction = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(c.set_impairment(i), std::invalid_argument);
  i = {};
  i.burst_deliveries = -1.0;
  EXPECT_THROW(c.set_impairment(i), std::invalid_argument);
  i = {};
  i.latency_deliveries = -2;
  EXPECT_THROW(c.set_impairment(i), std::invalid_argument);
  EXPECT_TRUE(c.impairment().none());  // a refused one changes nothing
}

}  // namespace
}  // namespace ferret::link
