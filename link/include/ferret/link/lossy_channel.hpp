#pragma once
// A network that misbehaves on purpose, for tests and simulation: between two sessions
// in one process it drops, duplicates, reorders and damages datagrams, the same way
// for the same seed on every machine (core/random.hpp). Time is counted in deliveries,
// not seconds: each deliver() is one step of the simulation, so it runs on a SimClock
// without knowing it.

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "ferret/core/random.hpp"

namespace ferret::link {

/// The ways a datagram is damaged.
enum class Corruption : std::uint8_t {
  kFlipBits,   ///< 1 to 8 bits flipped anywhere
  kTruncate,   ///< cut short (possibly to nothing)
  kExtend,     ///< 1 to 16 random bytes appended
  kOverwrite,  ///< a run of 1 to 8 bytes overwritten with random bytes (a field)
};
inline constexpr std::size_t kCorruptionKinds = 4;
[[nodiscard]] std::string_view to_string(Corruption kind);

/// Damages `datagram` by `kind`; the result always differs from the input (an empty
/// datagram can only be extended, so any kind extends it).
void corrupt(std::vector<std::uint8_t>& datagram, Corruption kind, Rng& rng);
/// Damages `datagram` in a way drawn at random, once or (one time in four) twice;
/// returns the first kind applied.
Corruption corrupt(std::vector<std::uint8_t>& datagram, Rng& rng);

struct LossyChannelOptions {
  double drop_fraction = 0.0;       ///< datagrams lost
  double duplicate_fraction = 0.0;  ///< datagrams delivered twice (each copy on its own)
  double reorder_fraction = 0.0;    ///< datagrams held back past later ones
  /// A held-back datagram arrives 1 to this many deliveries late, after the datagrams
  /// sent in between.
  int max_reorder_delay = 3;
  double corrupt_fraction = 0.0;  ///< copies damaged by corrupt()
  std::uint64_t seed = 1;
};

/// Faults that come and go on top of the channel's options (a fault plan's link faults:
/// sim/fault_plan.hpp), set by the simulation before each step. Time counts in
/// deliveries, as everywhere in the channel.
struct LinkImpairment {
  bool outage = false;         ///< nothing gets through
  double drop_fraction = 0.0;  ///< a further share lost (of the time, with bursts)
  /// Mean length of a loss burst in deliveries: while a burst lasts every datagram is
  /// lost, and bursts cover drop_fraction of the time. 0: each datagram lost on its own.
  double burst_deliveries = 0.0;
  int latency_deliveries = 0;       ///< every datagram this many deliveries late
  int jitter_deliveries = 0;        ///< plus 0 to this many more, drawn each (reorders)
  double duplicate_fraction = 0.0;  ///< a further share delivered twice

  bool operator==(const LinkImpairment&) const = default;
  [[nodiscard]] bool none() const { return *this == LinkImpairment{}; }
};

class LossyChannel {
 public:
  struct Counters {
    std::uint64_t sent = 0, dropped = 0, duplicated = 0, reordered = 0, corrupted = 0,
                  delivered = 0;
    std::uint64_t impaired = 0;  ///< copies lost to the impairment (also in `dropped`)
  };

  /// @throws std::invalid_argument for a fraction outside [0, 1] or a delay < 1
  explicit LossyChannel(LossyChannelOptions options = {});

  /// Into the channel.
  void send(std::span<const std::uint8_t> datagram);
  void send(const std::vector<std::vector<std::uint8_t>>& datagrams) {
    for (const auto& d : datagrams) send(d);
  }
  /// One step: what arrives now, in arrival order. A datagram sent before this call
  /// arrives now unless it is dropped or held back; held-back ones arrive after the
  /// datagrams sent in the step they arrive in.
  [[nodiscard]] std::vector<std::vector<std::uint8_t>> deliver();

  /// The impairment from now on (none: the options alone). Its random numbers come from
  /// a stream of their own, so a run keeps the options' draws whatever is impaired.
  /// @throws std::invalid_argument for a fraction outside [0, 1], a negative delay or burst
  void set_impairment(const LinkImpairment& impairment);
  [[nodiscard]] const LinkImpairment& impairment() const { return impairment_; }

  /// Datagrams in the channel, not yet delivered.
  [[nodiscard]] std::size_t in_flight() const { return queue_.size(); }
  [[nodiscard]] const Counters& counters() const { return counters_; }

 private:
  struct InFlight {
    std::uint64_t due_step;
    bool held_back;
    std::uint64_t order;
    std::vector<std::uint8_t> bytes;
  };
  void enqueue(std::span<const std::uint8_t> datagram);
  void impair(InFlight f);

  LossyChannelOptions options_;
  Rng rng_;
  LinkImpairment impairment_;
  Rng impairment_rng_;
  bool in_burst_ = false;
  std::uint64_t step_ = 0;
  std::uint64_t order_ = 0;
  std::vector<InFlight> queue_;
  Counters counters_;
};

}  // namespace ferret::link
