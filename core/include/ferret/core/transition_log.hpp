#pragma once
// The state transitions of a mission controller, each with the (simulated) time and
// the reason: what `ferret mission` prints as they happen and what the report keeps.

#include <functional>
#include <string>
#include <vector>

namespace ferret {

struct Transition {
  double t_s = 0.0;
  std::string component;  ///< "ugv", "uav", ...
  std::string from, to;
  std::string reason;
};

class TransitionLog {
 public:
  using Listener = std::function<void(const Transition&)>;
  /// Records a transition and tells the listener (if any).
  void add(Transition t);
  [[nodiscard]] const std::vector<Transition>& all() const { return transitions_; }
  /// Called on every add (printing, the MCAP log); replaces an earlier listener.
  void on_transition(Listener listener) { listener_ = std::move(listener); }
  /// "12.40 s  ugv  explore -> track  (object probability passed lambda2)"
  [[nodiscard]] static std::string format(const Transition& t);

 private:
  std::vector<Transition> transitions_;
  Listener listener_;
};

}  // namespace ferret
