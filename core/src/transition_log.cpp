#include "ferret/core/transition_log.hpp"

#include <cstdio>

namespace ferret {

void TransitionLog::add(Transition t) {
  transitions_.push_back(std::move(t));
  if (listener_) listener_(transitions_.back());
}

std::string TransitionLog::format(const Transition& t) {
  char time[32];
  std::snprintf(time, sizeof time, "%8.2f s", t.t_s);
  std::string s = std::string(time) + "  " + t.component + "  " + t.from + " -> " + t.to;
  if (!t.reason.empty()) s += "  (" + t.reason + ")";
  return s;
}

}  // namespace ferret
