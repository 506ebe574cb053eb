#include "ferret/link/lossy_channel.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ferret::link {
namespace {

void require_fraction(double value, const char* field) {
  if (!(value >= 0.0 && value <= 1.0))
    throw std::invalid_argument(
        fmt::format("lossy channel: {}: expected a number in [0, 1] (got {})", field, value));
}

std::uint8_t random_byte(Rng& rng) { return static_cast<std::uint8_t>(rng.next_u64()); }

std::size_t random_index(Rng& rng, std::size_t size) {
  return static_cast<std::size_t>(rng.uniform_int(0, static_cast<std::int64_t>(size) - 1));
}

}  // namespace

std::string_view to_string(Corruption kind) {
  switch (kind) {
    case Corruption::kFlipBits:
      return "flip bits";
    case Corruption::kTruncate:
      return "truncate";
    case Corruption::kExtend:
      return "extend";
    case Corruption::kOverwrite:
      return "overwrite";
  }
  return "unknown";
}

void corrupt(std::vector<std::uint8_t>& d, Corruption kind, Rng& rng) {
  if (d.empty()) kind = Corruption::kExtend;
  switch (kind) {
    case Corruption::kFlipBits: {
      // Distinct bits, so that no flip undoes another and the datagram always changes.
      const auto bits =
          static_cast<int>(std::min<std::size_t>(rng.uniform_int(1, 8), d.size() * 8));
      std::vector<std::size_t> flipped;
      while (static_cast<int>(flipped.size()) < bits) {
        const std::size_t bit = random_index(rng, d.size() * 8);
        if (std::find(flipped.begin(), flipped.end(), bit) != flipped.end()) continue;
        flipped.push_back(bit);
        d[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
      }
      break;
    }
    case Corruption::kTruncate:
      d.resize(random_index(rng, d.size()));
      break;
    case Corruption::kExtend: {
      const auto n = rng.uniform_int(1, 16);
      for (std::int64_t i = 0; i < n; ++i) d.push_back(random_byte(rng));
      break;
    }
    case Corruption::kOverwrite: {
      const std::size_t at = random_index(rng, d.size());
      const std::size_t n = std::min<std::size_t>(rng.uniform_int(1, 8), d.size() - at);
      const std::vector<std::uint8_t> before(d.begin() + at, d.begin() + at + n);
      do {
        for (std::size_t i = 0; i < n; ++i) d[at + i] = random_byte(rng);
      } while (std::equal(before.begin(), before.end(), d.begin() + at));
      break;
    }
  }
}

Corruption corrupt(std::vector<std::uint8_t>& d, Rng& rng) {
  const auto first = static_cast<Corruption>(rng.uniform_int(0, kCorruptionKinds - 1));
  const std::vector<std::uint8_t> original = d;
  corrupt(d, first, rng);
  if (rng.bernoulli(0.25)) {
    // A second damage may repair the first (a truncation after an extension); then
    // damage once more, so the datagram still differs.
    corrupt(d, static_cast<Corruption>(rng.uniform_int(0, kCorruptionKinds - 1)), rng);
    while (d == original) corrupt(d, Corruption::kFlipBits, rng);
  }
  return first;
}

LossyChannel::LossyChannel(LossyChannelOptions options)
    : options_(options),
      rng_(options.seed),
      impairment_rng_(derive_seed(options.seed, {stable_hash("impairment")})) {
  require_fraction(options.drop_fraction, "drop_fraction");
  require_fraction(options.duplicate_fraction, "duplicate_fraction");
  require_fraction(options.reorder_fraction, "reorder_fraction");
  require_fraction(options.corrupt_fraction, "corrupt_fraction");
  if (options.max_reorder_delay < 1)
    throw std::invalid_argument(
        fmt::format("lossy channel: max_reorder_delay: expected an integer >= 1 (got {})",
                    options.max_reorder_delay));
}

void LossyChannel::set_impairment(const LinkImpairment& i) {
  require_fraction(i.drop_fraction, "impairment drop_fraction");
  require_fraction(i.duplicate_fraction, "impairment duplicate_fraction");
  if (!(i.burst_deliveries >= 0.0) || !std::isfinite(i.burst_deliveries) ||
      i.latency_deliveries < 0 || i.jitter_deliveries < 0)
    throw std::invalid_argument(
        "lossy channel: impairment: expected a burst, latency and jitter >= 0");
  impairment_ = i;
  if (i.drop_fraction == 0.0 || i.burst_deliveries == 0.0) in_burst_ = false;
}

void LossyChannel::send(std::span<const std::uint8_t> datagram) {
  ++counters_.sent;
  if (rng_.bernoulli(options_.drop_fraction)) {
    ++counters_.dropped;
    return;
  }
  enqueue(datagram);
  if (rng_.bernoulli(options_.duplicate_fraction)) {
    ++counters_.duplicated;
    enqueue(datagram);
  }
}

void LossyChannel::enqueue(std::span<const std::uint8_t> datagram) {
  InFlight f{step_ + 1, false, order_++, {datagram.begin(), datagram.end()}};
  if (rng_.bernoulli(options_.reorder_fraction)) {
    ++counters_.reordered;
    f.held_back = true;
    f.due_step += static_cast<std::uint64_t>(rng_.uniform_int(1, options_.max_reorder_delay));
  }
  if (rng_.bernoulli(options_.corrupt_fraction)) {
    ++counters_.corrupted;
    corrupt(f.bytes, rng_);
  }
  if (impairment_.none()) {
    queue_.push_back(std::move(f));
    return;
  }
  impair(std::move(f));
}

void LossyChannel::impair(InFlight f) {
  const LinkImpairment& i = impairment_;
  const bool lost = i.outage || in_burst_ || i.drop_fraction >= 1.0 ||
                    (i.burst_deliveries == 0.0 && impairment_rng_.bernoulli(i.drop_fraction));
  if (lost) {
    ++counters_.dropped;
    ++counters_.impaired;
    return;
  }
  const int copies = impairment_rng_.bernoulli(i.duplicate_fraction) ? 2 : 1;
  if (copies == 2) ++counters_.duplicated;
  for (int c = 0; c < copies; ++c) {
    InFlight copy = f;
    copy.order = c == 0 ? f.order : order_++;
    copy.due_step += static_cast<std::uint64_t>(i.latency_deliveries);
    if (i.jitter_deliveries > 0)
      copy.due_step +=
          static_cast<std::uint64_t>(impairment_rng_.uniform_int(0, i.jitter_deliveries));
    queue_.push_back(std::move(copy));
  }
}

std::vector<std::vector<std::uint8_t>> LossyChannel::deliver() {
  ++step_;
  // Bursts of loss: a two-state chain stepped once a delivery, in a burst for
  // drop_fraction of the time with bursts burst_deliveries long on average.
  const LinkImpairment& i = impairment_;
  if (i.burst_deliveries > 0.0 && i.drop_fraction > 0.0) {
    const double leave = 1.0 / std::max(1.0, i.burst_deliveries);
    const double enter = i.drop_fraction >= 1.0
                             ? 1.0
                             : std::min(1.0, leave * i.drop_fraction / (1.0 - i.drop_fraction));
    in_burst_ = in_burst_ ? !impairment_rng_.bernoulli(leave) : impairment_rng_.bernoulli(enter);
  }
  const auto arrives = std::partition(queue_.begin(), queue_.end(),
                                      [&](const InFlight& f) { return f.due_step > step_; });
  // Arrival order: those sent on time in the order sent, then the held-back ones (they
  // come after datagrams sent later than them: that is the reordering).
  std::sort(arrives, queue_.end(), [](const InFlight& a, const InFlight& b) {
    return a.held_back != b.held_back ? !a.held_back : a.order < b.order;
  });
  std::vector<std::vector<std::uint8_t>> out;
  for (auto it = arrives; it != queue_.end(); ++it) out.push_back(std::move(it->bytes));
  queue_.erase(arrives, queue_.end());
  counters_.delivered += out.size();
  return out;
}

}  // namespace ferret::link
