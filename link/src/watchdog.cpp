#include "ferret/link/watchdog.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ferret::link {

Watchdog::Watchdog(const Clock& clock, double timeout_s) : clock_(&clock), timeout_s_(timeout_s) {
  if (!std::isfinite(timeout_s) || timeout_s <= 0)
    throw std::invalid_argument("link watchdog: timeout_s: expected a number > 0 s (got " +
                                std::to_string(timeout_s) + ")");
}

void Watchdog::heard() {
  ever_heard_ = true;
  heard_at_s_ = clock_->now_s();
}

void Watchdog::reset() { ever_heard_ = false; }

double Watchdog::since_heard_s() const {
  return ever_heard_ ? clock_->now_s() - heard_at_s_ : std::numeric_limits<double>::infinity();
}

bool Watchdog::expired() const { return since_heard_s() > timeout_s_; }

}  // namespace ferret::link
