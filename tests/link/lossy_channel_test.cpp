#include "ferret/link/lossy_channel.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
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

}  // namespace
}  // namespace ferret::link
